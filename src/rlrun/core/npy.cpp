#include "rlrun/core/npy.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace rlrun {

namespace {

const char* descr(DType t) {
  switch (t) {
    case DType::kFloat32: return "<f4";
    case DType::kFloat64: return "<f8";
    case DType::kInt64: return "<i8";
    case DType::kUInt64: return "<u8";
    case DType::kUInt8: return "|u1";
  }
  return "";
}

// A strict reader of the header dict numpy writes with repr() (numpy/lib/format.py,
// _write_array_header), e.g. {'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }.
// numpy reads it with ast.literal_eval; this accepts the subset a dict of these three keys
// can be written in (either quote, any spaces, trailing commas) and nothing else.
class HeaderDict {
 public:
  HeaderDict(std::string_view text, const std::string& what) : text_(text), what_(what) {}

  NpyHeader parse() {
    NpyHeader h;
    bool have_descr = false, have_order = false, have_shape = false;
    expect('{');
    while (true) {
      skip_spaces();
      if (peek() == '}') break;
      const std::string key = quoted();
      skip_spaces();
      expect(':');
      skip_spaces();
      if (key == "descr" && !have_descr) {
        h.dtype = dtype(quoted());
        have_descr = true;
      } else if (key == "fortran_order" && !have_order) {
        if (!word("False")) {
          if (word("True")) fail("Fortran order is not supported (save with C order)");
          fail("fortran_order is not True or False");
        }
        have_order = true;
      } else if (key == "shape" && !have_shape) {
        h.shape = shape();
        have_shape = true;
      } else {
        fail("unexpected or repeated key '" + printable(key) + "' in the header");
      }
      skip_spaces();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      skip_spaces();
      if (peek() != '}') fail("malformed header dict");
    }
    ++pos_;  // '}'
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n')) ++pos_;
    if (pos_ != text_.size()) fail("bytes after the header dict");
    if (!have_descr || !have_order || !have_shape)
      fail("the header needs 'descr', 'fortran_order' and 'shape'");
    return h;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error(what_ + ": not a supported .npy array (" + why + ")");
  }
  static std::string printable(std::string_view s) {
    std::string out;
    for (char c : s.substr(0, 40)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
    return out;
  }
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  void skip_spaces() {
    while (pos_ < text_.size() && text_[pos_] == ' ') ++pos_;
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("malformed header dict (expected '") + c + "')");
    ++pos_;
  }
  bool word(std::string_view w) {
    if (text_.substr(pos_, w.size()) != w) return false;
    pos_ += w.size();
    return true;
  }
  std::string quoted() {
    const char quote = peek();
    if (quote != '\'' && quote != '"') fail("malformed header dict (expected a quoted key)");
    const size_t end = text_.find(quote, pos_ + 1);
    if (end == std::string_view::npos) fail("unterminated string in the header");
    std::string s(text_.substr(pos_ + 1, end - pos_ - 1));
    if (s.find('\\') != std::string::npos) fail("escapes in header strings are not supported");
    pos_ = end + 1;
    return s;
  }
  DType dtype(const std::string& d) {
    if (d == "<f4") return DType::kFloat32;
    if (d == "<f8") return DType::kFloat64;
    if (d == "<i8") return DType::kInt64;
    if (d == "<u8") return DType::kUInt64;
    if (d == "|u1") return DType::kUInt8;  // numpy's descr for uint8 (no byte order)
    fail("unsupported dtype '" + printable(d) + "' (rlrun reads <f4, <f8, <i8, <u8 and |u1)");
  }
  // "(" [dim ("," dim)* [","]] ")": Python's tuple repr; one dimension is written (n,),
  // since (n) is not a tuple.
  std::vector<int64_t> shape() {
    std::vector<int64_t> dims;
    bool trailing_comma = false;
    expect('(');
    while (true) {
      skip_spaces();
      if (peek() == ')') break;
      if (dims.size() == kNpyMaxDims) fail("more than 32 dimensions");
      dims.push_back(dimension());
      skip_spaces();
      trailing_comma = peek() == ',';
      if (trailing_comma) {
        ++pos_;
        continue;
      }
      skip_spaces();
      if (peek() != ')') fail("malformed shape");
    }
    ++pos_;
    if (dims.size() == 1 && !trailing_comma)
      fail("malformed shape (one dimension is written (n,))");
    return dims;
  }
  // A non-negative decimal integer below 2^63, without std::stoll (which throws
  // std::invalid_argument / std::out_of_range with the message "stoll").
  int64_t dimension() {
    if (peek() < '0' || peek() > '9')
      fail("a dimension of the shape is not a non-negative integer");
    uint64_t value = 0;
    while (peek() >= '0' && peek() <= '9') {
      const uint64_t digit = static_cast<uint64_t>(peek() - '0');
      if (value > (static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) - digit) / 10)
        fail("a dimension of the shape is too large");
      value = value * 10 + digit;
      ++pos_;
    }
    return static_cast<int64_t>(value);
  }

  std::string_view text_;
  const std::string& what_;
  size_t pos_ = 0;
};

}  // namespace

std::vector<uint8_t> encode_npy(const Tensor& tensor) {
  std::string shape = "(";
  for (size_t i = 0; i < tensor.shape.size(); ++i) shape += std::to_string(tensor.shape[i]) + ", ";
  if (tensor.shape.size() > 1) shape.resize(shape.size() - 2);
  if (tensor.shape.size() == 1) shape.resize(shape.size() - 1);
  shape += ")";
  std::string header = std::string("{'descr': '") + descr(tensor.dtype) +
                       "', 'fortran_order': False, 'shape': " + shape + ", }";
  // magic(6) + version(2) + header_len(2) + header + '\n', total a multiple of 64.
  const size_t unpadded = kNpyPreludeBytes + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::string prefix("\x93NUMPY\x01\x00", 8);
  prefix += static_cast<char>(header.size() & 0xff);
  prefix += static_cast<char>(header.size() >> 8);
  prefix += header;
  std::vector<uint8_t> out(prefix.size() + tensor.bytes.size());
  std::copy(prefix.begin(), prefix.end(), out.begin());
  std::copy(tensor.bytes.begin(), tensor.bytes.end(), out.begin() + prefix.size());
  return out;
}

std::size_t npy_header_length(const uint8_t* prelude, std::size_t size, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    return std::runtime_error(what + ": not a supported .npy array (" + why + ")");
  };
  if (size < kNpyPreludeBytes || std::memcmp(prelude, "\x93NUMPY", 6) != 0) throw bad("no magic");
  // Version 2.0 and 3.0 (4-byte header_len) are only written for headers over 64 KiB.
  if (prelude[6] != 1 || prelude[7] != 0) throw bad("only format version 1.0 is supported");
  return static_cast<std::size_t>(prelude[8]) | (static_cast<std::size_t>(prelude[9]) << 8);
}

NpyHeader parse_npy_header(const uint8_t* bytes, std::size_t size, const std::string& what) {
  const std::size_t header_len = npy_header_length(bytes, size, what);
  if (size < kNpyPreludeBytes + header_len)
    throw std::runtime_error(what + ": not a supported .npy array (truncated header)");
  const std::string_view text(reinterpret_cast<const char*>(bytes) + kNpyPreludeBytes, header_len);
  NpyHeader h = HeaderDict(text, what).parse();
  h.header_bytes = kNpyPreludeBytes + header_len;
  // The data size, refusing anything whose byte count does not fit in int64 (Tensor::numel()).
  uint64_t total = dtype_size(h.dtype);
  for (const int64_t d : h.shape)
    if (__builtin_mul_overflow(total, static_cast<uint64_t>(d), &total) ||
        total > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()))
      throw std::runtime_error(what + ": not a supported .npy array (the shape's size overflows)");
  h.data_bytes = total;
  return h;
}

Tensor decode_npy(const std::vector<uint8_t>& bytes, const std::string& what) {
  const NpyHeader h = parse_npy_header(bytes.data(), bytes.size(), what);
  if (bytes.size() - h.header_bytes != h.data_bytes)
    throw std::runtime_error(what +
                             ": not a supported .npy array (data size does not match shape)");
  Tensor t;
  t.dtype = h.dtype;
  t.shape = h.shape;
  t.bytes.assign(bytes.begin() + static_cast<std::ptrdiff_t>(h.header_bytes), bytes.end());
  return t;
}

}  // namespace rlrun
