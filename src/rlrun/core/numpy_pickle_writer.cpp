#include "rlrun/core/numpy_pickle_writer.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace rlrun {

// Raw bytes are the host's: numpy's pickles here say little-endian.
static_assert(std::endian::native == std::endian::little);

namespace {

constexpr const char* kMultiarray = "numpy.core.multiarray";

std::size_t item_bytes(const std::string& code) {
  if (code.size() != 2 || code[1] < '1' || code[1] > '8')
    throw std::logic_error("numpy type code " + code);
  return static_cast<std::size_t>(code[1] - '0');
}

template <class T>
std::vector<uint8_t> raw_bytes(const std::vector<T>& values) {
  std::vector<uint8_t> out(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

}  // namespace

void pickle_numpy_dtype(PickleWriter& p, const std::string& code) {
  p.global_ref("numpy", "dtype");
  p.mark();
  p.text(code);
  p.boolean(false);  // align
  p.boolean(true);   // copy
  p.tuple_from_mark();
  p.reduce();
  // State version 3: byte order ('|' when it does not apply), no subarray, no fields, no
  // names, elsize and alignment -1 (derived), no flags.
  p.mark();
  p.integer(3);
  p.text(item_bytes(code) == 1 ? "|" : "<");
  p.none();
  p.none();
  p.none();
  p.integer(-1);
  p.integer(-1);
  p.integer(0);
  p.tuple_from_mark();
  p.build();
}

void pickle_numpy_array(PickleWriter& p, const std::string& code, const std::vector<int64_t>& shape,
                        const std::vector<uint8_t>& bytes) {
  int64_t count = 1;
  for (const int64_t d : shape) count *= d;
  if (bytes.size() != static_cast<std::size_t>(count) * item_bytes(code))
    throw std::logic_error("numpy array bytes do not match its shape");
  p.global_ref(kMultiarray, "_reconstruct");
  p.mark();
  p.global_ref("numpy", "ndarray");
  p.int_tuple({0});
  const uint8_t b = 'b';
  p.bytes(&b, 1);
  p.tuple_from_mark();
  p.reduce();
  p.mark();
  p.integer(1);  // state version
  p.int_tuple(shape);
  pickle_numpy_dtype(p, code);
  p.boolean(false);  // C order
  p.bytes(bytes.data(), bytes.size());
  p.tuple_from_mark();
  p.build();
}

void pickle_numpy_float32_array(PickleWriter& p, const std::vector<float>& values,
                                const std::vector<int64_t>& shape) {
  pickle_numpy_array(p, "f4", shape, raw_bytes(values));
}

void pickle_numpy_int64_array(PickleWriter& p, const std::vector<int64_t>& values) {
  pickle_numpy_array(p, "i8", {static_cast<int64_t>(values.size())}, raw_bytes(values));
}

void pickle_numpy_bool_array(PickleWriter& p, const std::vector<bool>& values,
                             const std::vector<int64_t>& shape) {
  std::vector<uint8_t> bytes;
  for (const bool v : values) bytes.push_back(v ? 1 : 0);
  pickle_numpy_array(p, "b1", shape, bytes);
}

void pickle_numpy_int64(PickleWriter& p, int64_t value) {
  p.global_ref(kMultiarray, "scalar");
  p.mark();
  pickle_numpy_dtype(p, "i8");
  std::vector<uint8_t> bytes(sizeof value);
  std::memcpy(bytes.data(), &value, sizeof value);
  p.bytes(bytes.data(), bytes.size());
  p.tuple_from_mark();
  p.reduce();
}

}  // namespace rlrun
