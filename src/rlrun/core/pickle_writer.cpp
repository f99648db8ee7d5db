#include "rlrun/core/pickle_writer.hpp"

#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "rlrun/core/errors.hpp"

namespace rlrun {

// Opcodes (Lib/pickle.py); named apart from the reader's (a unity build joins the files).
namespace pickle_writer_ops {

constexpr uint8_t kProto = 0x80, kStop = '.', kNone = 'N', kNewTrue = 0x88, kNewFalse = 0x89,
                  kBinInt1 = 'K', kBinInt2 = 'M', kBinInt = 'J', kLong1 = 0x8a, kBinFloat = 'G',
                  kBinUnicode = 'X', kBinBytes = 'B', kGlobal = 'c', kMark = '(', kTuple = 't',
                  kEmptyTuple = ')', kEmptyList = ']', kAppends = 'e', kEmptyDict = '}',
                  kSetItems = 'u', kReduce = 'R', kNewObj = 0x81, kBuild = 'b', kBinPersId = 'Q';

}  // namespace pickle_writer_ops

namespace op = pickle_writer_ops;

PickleWriter::PickleWriter(int protocol) : protocol_(protocol) {
  if (protocol < 2 || protocol > 5)
    throw std::logic_error("PickleWriter: protocol " + std::to_string(protocol));
  op(op::kProto);
  op(static_cast<uint8_t>(protocol));
}

void PickleWriter::u32(uint32_t v) {
  for (int i = 0; i < 4; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void PickleWriter::none() { op(op::kNone); }
void PickleWriter::boolean(bool value) { op(value ? op::kNewTrue : op::kNewFalse); }

void PickleWriter::integer(int64_t value) {
  if (value >= 0 && value < 256) {
    op(op::kBinInt1);
    out_.push_back(static_cast<uint8_t>(value));
  } else if (value >= 0 && value < 65536) {
    op(op::kBinInt2);
    out_.push_back(static_cast<uint8_t>(value));
    out_.push_back(static_cast<uint8_t>(value >> 8));
  } else if (value >= std::numeric_limits<int32_t>::min() &&
             value <= std::numeric_limits<int32_t>::max()) {
    op(op::kBinInt);  // a signed 4-byte little-endian int
    u32(static_cast<uint32_t>(static_cast<int32_t>(value)));
  } else {
    op(op::kLong1);  // two's complement little-endian, 8 bytes
    out_.push_back(8);
    const uint64_t bits = static_cast<uint64_t>(value);
    for (int i = 0; i < 8; ++i) out_.push_back(static_cast<uint8_t>(bits >> (8 * i)));
  }
}

void PickleWriter::real(double value) {
  op(op::kBinFloat);
  const uint64_t bits = std::bit_cast<uint64_t>(value);
  for (int i = 7; i >= 0; --i) out_.push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

void PickleWriter::text(const std::string& s) {
  if (s.size() > std::numeric_limits<uint32_t>::max())
    throw RuntimeFailure("a pickled string of more than 4 GiB");
  op(op::kBinUnicode);
  u32(static_cast<uint32_t>(s.size()));
  out_.insert(out_.end(), s.begin(), s.end());
}

void PickleWriter::bytes(const uint8_t* data, std::size_t size) {
  if (protocol_ < 3) throw std::logic_error("PickleWriter: bytes need protocol 3");
  if (size > std::numeric_limits<uint32_t>::max())
    throw RuntimeFailure("a pickled bytes value of more than 4 GiB");
  op(op::kBinBytes);
  u32(static_cast<uint32_t>(size));
  out_.insert(out_.end(), data, data + size);
}

void PickleWriter::global_ref(const std::string& module, const std::string& name) {
  if (module.find('\n') != std::string::npos || name.find('\n') != std::string::npos)
    throw std::logic_error("PickleWriter: a newline in a global's name");
  op(op::kGlobal);
  out_.insert(out_.end(), module.begin(), module.end());
  out_.push_back('\n');
  out_.insert(out_.end(), name.begin(), name.end());
  out_.push_back('\n');
}

void PickleWriter::mark() { op(op::kMark); }
void PickleWriter::tuple_from_mark() { op(op::kTuple); }
void PickleWriter::empty_tuple() { op(op::kEmptyTuple); }
void PickleWriter::empty_list() { op(op::kEmptyList); }
void PickleWriter::appends() { op(op::kAppends); }
void PickleWriter::empty_dict() { op(op::kEmptyDict); }
void PickleWriter::set_items() { op(op::kSetItems); }
void PickleWriter::reduce() { op(op::kReduce); }
void PickleWriter::new_object() { op(op::kNewObj); }
void PickleWriter::build() { op(op::kBuild); }
void PickleWriter::persistent_id() { op(op::kBinPersId); }

void PickleWriter::int_tuple(const std::vector<int64_t>& values) {
  mark();
  for (const int64_t v : values) integer(v);
  tuple_from_mark();
}

void PickleWriter::int_list(const std::vector<int64_t>& values) {
  empty_list();
  if (values.empty()) return;
  mark();
  for (const int64_t v : values) integer(v);
  appends();
}

std::vector<uint8_t> PickleWriter::finish() {
  op(op::kStop);
  return std::move(out_);
}

}  // namespace rlrun
