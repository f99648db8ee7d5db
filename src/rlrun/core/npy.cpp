#include "rlrun/core/npy.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace rlrun {

namespace {

const char* descr(DType t) {
  switch (t) {
    case DType::kFloat32: return "<f4";
    case DType::kFloat64: return "<f8";
    case DType::kInt64: return "<i8";
    case DType::kUInt64: return "<u8";
  }
  return "";
}

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
  const size_t unpadded = 10 + header.size() + 1;
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

Tensor decode_npy(const std::vector<uint8_t>& bytes, const std::string& what) {
  auto bad = [&](const std::string& why) -> std::runtime_error {
    return std::runtime_error(what + ": not a supported .npy array (" + why + ")");
  };
  if (bytes.size() < 10 || std::memcmp(bytes.data(), "\x93NUMPY", 6) != 0) throw bad("no magic");
  if (bytes[6] != 1) throw bad("only format version 1.0 is supported");
  const size_t header_len = bytes[8] | (bytes[9] << 8);
  if (10 + header_len > bytes.size()) throw bad("truncated header");
  const std::string header(bytes.begin() + 10, bytes.begin() + 10 + header_len);
  Tensor t;
  if (header.find("'<f4'") != std::string::npos)
    t.dtype = DType::kFloat32;
  else if (header.find("'<f8'") != std::string::npos)
    t.dtype = DType::kFloat64;
  else if (header.find("'<i8'") != std::string::npos)
    t.dtype = DType::kInt64;
  else if (header.find("'<u8'") != std::string::npos)
    t.dtype = DType::kUInt64;
  else
    throw bad("unsupported dtype");
  if (header.find("'fortran_order': False") == std::string::npos) throw bad("Fortran order");
  const auto open = header.find("'shape': (");
  const auto close = header.find(')', open);
  if (open == std::string::npos || close == std::string::npos) throw bad("no shape");
  const std::string dims = header.substr(open + 10, close - open - 10);
  size_t pos = 0;
  while (pos < dims.size()) {
    while (pos < dims.size() && (dims[pos] == ' ' || dims[pos] == ',')) ++pos;
    if (pos >= dims.size()) break;
    size_t used = 0;
    t.shape.push_back(std::stoll(dims.substr(pos), &used));
    pos += used;
  }
  const size_t data_bytes = static_cast<size_t>(t.numel()) * dtype_size(t.dtype);
  if (10 + header_len + data_bytes != bytes.size()) throw bad("data size does not match shape");
  t.bytes.assign(bytes.begin() + 10 + header_len, bytes.end());
  return t;
}

}  // namespace rlrun
