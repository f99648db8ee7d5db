#include "rlrun/core/numpy_pickle.hpp"

#include <cstdint>
#include <cstring>
#include <string_view>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun {

namespace {

// "numpy.core.numeric" and numpy 2's "numpy._core.numeric" -> "numeric".
std::string numpy_core_module(const std::string& module) {
  for (const char* prefix : {"numpy.core.", "numpy._core."})
    if (module.rfind(prefix, 0) == 0) return module.substr(std::strlen(prefix));
  return "";
}

bool callee_is(const PickleValue& value, const char* core_module, const char* name) {
  const PickleValue* callee = value.callee();
  return callee && numpy_core_module(callee->module) == core_module && callee->text == name;
}

[[noreturn]] void fail(const std::string& what, const std::string& why) {
  throw RuntimeFailure(what + ": " + why);
}

std::vector<int64_t> shape_of(const PickleValue& value, const std::string& what) {
  if (value.kind != PickleKind::kTuple || value.items.size() > 32)
    fail(what, "an array shape that is not a tuple of at most 32 sizes");
  std::vector<int64_t> shape;
  for (const PickleValue* d : value.items) {
    if (d->kind != PickleKind::kInt || d->integer < 0)
      fail(what, "an array dimension that is not a size");
    shape.push_back(d->integer);
  }
  return shape;
}

NumpyArray make_array(NumpyDtype dtype, std::vector<int64_t> shape, const PickleValue& data,
                      const std::string& what) {
  if (data.kind != PickleKind::kBytes) fail(what, "an array whose data is not bytes");
  NumpyArray array{dtype, std::move(shape), data.text};
  int64_t count = 1;
  for (const int64_t d : array.shape)
    if (__builtin_mul_overflow(count, d, &count)) fail(what, "an array of too many elements");
  if (static_cast<uint64_t>(count) != data.text.size() / static_cast<uint64_t>(dtype.item_bytes) ||
      data.text.size() % static_cast<uint64_t>(dtype.item_bytes) != 0)
    fail(what, "an array whose data is " + std::to_string(data.text.size()) +
                   " bytes for its shape and dtype " + dtype.name());
  return array;
}

// _frombuffer(buffer, dtype, shape, order)
NumpyArray from_buffer(const PickleValue& value, const std::string& what) {
  const auto& args = value.arguments().items;
  if (args.size() != 4 || value.state) fail(what, "a numpy _frombuffer call of another form");
  std::vector<int64_t> shape = shape_of(*args[2], what);
  if (args[3]->kind != PickleKind::kString || (args[3]->text != "C" && args[3]->text != "F"))
    fail(what, "an array order other than C or F");
  if (args[3]->text == "F" && shape.size() > 1)
    fail(what, "an array in Fortran order (rlrun reads C order)");
  return make_array(numpy_dtype(*args[1], what), std::move(shape), *args[0], what);
}

// _reconstruct(ndarray, (0,), b'b') + BUILD (version, shape, dtype, is_fortran, data)
NumpyArray reconstructed(const PickleValue& value, const std::string& what) {
  const auto& args = value.arguments().items;
  const PickleValue* state = value.state;
  const bool ndarray =
      args.size() == 3 && args[0]->kind == PickleKind::kGlobal && args[0]->text == "ndarray";
  if (!ndarray || !state || state->kind != PickleKind::kTuple || state->items.size() != 5)
    fail(what, "a numpy _reconstruct call of another form");
  const auto& s = state->items;
  std::vector<int64_t> shape = shape_of(*s[1], what);
  if (s[3]->kind != PickleKind::kBool || (s[3]->boolean && shape.size() > 1))
    fail(what, "an array in Fortran order (rlrun reads C order)");
  return make_array(numpy_dtype(*s[2], what), std::move(shape), *s[4], what);
}

}  // namespace

bool is_numpy_pickle_global(const std::string& module, const std::string& name) {
  if (module == "numpy") return name == "dtype" || name == "ndarray";
  const std::string core = numpy_core_module(module);
  if (core == "numeric") return name == "_frombuffer";
  if (core == "multiarray") return name == "_reconstruct" || name == "scalar";
  return false;
}

std::string NumpyDtype::name() const {
  if (kind == 'b') return "bool";
  const std::string bits = std::to_string(8 * item_bytes);
  return (kind == 'f' ? "float" : kind == 'i' ? "int" : "uint") + bits;
}

int64_t NumpyArray::size() const { return static_cast<int64_t>(bytes.size()) / dtype.item_bytes; }

std::vector<double> NumpyArray::to_doubles() const {
  std::vector<double> out(static_cast<size_t>(size()));
  const char* p = bytes.data();
  for (size_t i = 0; i < out.size(); ++i, p += dtype.item_bytes) {
    if (dtype.kind == 'f' && dtype.item_bytes == 4) {
      float f;
      std::memcpy(&f, p, 4);
      out[i] = f;
    } else if (dtype.kind == 'f') {
      std::memcpy(&out[i], p, 8);
    } else {
      uint64_t bits = 0;
      std::memcpy(&bits, p, static_cast<size_t>(dtype.item_bytes));
      const int shift = 64 - 8 * dtype.item_bytes;
      out[i] = dtype.kind == 'i' ? static_cast<double>(static_cast<int64_t>(bits << shift) >> shift)
                                 : static_cast<double>(bits);
    }
  }
  return out;
}

NumpyDtype numpy_dtype(const PickleValue& value, const std::string& what) {
  const PickleValue* callee = value.callee();
  if (!callee || !callee->is_global("numpy", "dtype") || value.arguments().items.empty() ||
      value.arguments().items[0]->kind != PickleKind::kString)
    fail(what, "a dtype that is not numpy.dtype(...)");
  const std::string& code = value.arguments().items[0]->text;  // 'f4', 'i8', 'u1', 'b1'
  NumpyDtype dtype;
  const bool known = code.size() == 2 &&
                     std::string_view("biuf").find(code[0]) != std::string_view::npos &&
                     std::string_view("1248").find(code[1]) != std::string_view::npos;
  if (known) dtype = NumpyDtype{code[0], code[1] - '0'};
  if (!known || (dtype.kind == 'f' && dtype.item_bytes < 4) ||
      (dtype.kind == 'b' && dtype.item_bytes != 1))
    fail(what, "numpy dtype '" + quoted_text(code) + "' (rlrun reads bool, int, uint, float32/64)");
  // BUILD's state: (version, byte order, ...); '|' (single bytes) and '<' are what x86 and ARM
  // write; '>' would need swapping.
  const PickleValue* state = value.state;
  if (state && (state->kind != PickleKind::kTuple || state->items.size() < 2 ||
                state->items[1]->kind != PickleKind::kString ||
                (state->items[1]->text != "<" && state->items[1]->text != "|" &&
                 state->items[1]->text != "=")))
    fail(what, "a numpy dtype that is not little-endian");
  return dtype;
}

bool is_numpy_array(const PickleValue& value) {
  return callee_is(value, "numeric", "_frombuffer") ||
         callee_is(value, "multiarray", "_reconstruct");
}

NumpyArray numpy_array(const PickleValue& value, const std::string& what) {
  if (callee_is(value, "numeric", "_frombuffer")) return from_buffer(value, what);
  if (callee_is(value, "multiarray", "_reconstruct")) return reconstructed(value, what);
  fail(what, describe_pickle_value(value) + " where a numpy array belongs");
}

int64_t pickled_integer(const PickleValue& value, const std::string& what) {
  if (value.kind == PickleKind::kInt) return value.integer;
  if (callee_is(value, "multiarray", "scalar") && value.arguments().items.size() == 2) {
    const PickleValue& data = *value.arguments().items[1];
    const NumpyDtype dtype = numpy_dtype(*value.arguments().items[0], what);
    if ((dtype.kind == 'i' || dtype.kind == 'u') && data.kind == PickleKind::kBytes &&
        data.text.size() == static_cast<size_t>(dtype.item_bytes)) {
      uint64_t bits = 0;
      std::memcpy(&bits, data.text.data(), data.text.size());
      const int shift = 64 - 8 * dtype.item_bytes;
      if (dtype.kind == 'i') return static_cast<int64_t>(bits << shift) >> shift;
      if (bits <= static_cast<uint64_t>(INT64_MAX)) return static_cast<int64_t>(bits);
    }
  }
  fail(what, describe_pickle_value(value) + " where an integer belongs");
}

double pickled_number(const PickleValue& value, const std::string& what) {
  if (value.kind == PickleKind::kFloat) return value.number;
  if (value.kind == PickleKind::kInt) return static_cast<double>(value.integer);
  if (callee_is(value, "multiarray", "scalar") && value.arguments().items.size() == 2) {
    const PickleValue& data = *value.arguments().items[1];
    const NumpyDtype dtype = numpy_dtype(*value.arguments().items[0], what);
    if (data.kind == PickleKind::kBytes &&
        data.text.size() == static_cast<size_t>(dtype.item_bytes))
      return NumpyArray{dtype, {}, data.text}.to_doubles()[0];
  }
  if (is_numpy_array(value)) {
    const NumpyArray array = numpy_array(value, what);
    if (array.size() == 1) return array.to_doubles()[0];
  }
  fail(what, describe_pickle_value(value) + " where a number belongs");
}

}  // namespace rlrun
