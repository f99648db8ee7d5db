#include <catch2/catch.hpp>
#include <filesystem>

#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"

using namespace rlrun;

TEST_CASE("npy: header is numpy's v1.0 layout and data round-trips", "[core][npy]") {
  Eigen::MatrixXf m(2, 3);
  m << 1, 2, 3, 4, 5, 6;
  const Tensor t = to_tensor(m);
  REQUIRE(t.shape == std::vector<int64_t>{2, 3});
  // C order: row 0 first.
  CHECK(t.data<float>()[1] == 2.0f);
  CHECK(t.data<float>()[3] == 4.0f);
  const std::vector<uint8_t> bytes = encode_npy(t);
  const size_t header_len = bytes[8] | (bytes[9] << 8);
  CHECK((10 + header_len) % 64 == 0);
  const std::string header(bytes.begin() + 10, bytes.begin() + 10 + header_len);
  CHECK(header.find("'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }") !=
        std::string::npos);
  CHECK(header.back() == '\n');
  const Tensor back = decode_npy(bytes, "x");
  CHECK(back.shape == t.shape);
  CHECK(back.bytes == t.bytes);
  Eigen::MatrixXf m2(2, 3);
  TensorMap map{{"w", back}};
  from_tensor(map, "w", m2);
  CHECK(m2 == m);
}

TEST_CASE("npy: vectors, scalars and other dtypes", "[core][npy]") {
  const Tensor v = to_tensor(Eigen::VectorXf(Eigen::VectorXf::Ones(5)));
  CHECK(v.shape == std::vector<int64_t>{5});
  const std::vector<uint8_t> bytes = encode_npy(v);
  CHECK(std::string(bytes.begin() + 10, bytes.end()).find("'shape': (5,)") != std::string::npos);
  const Tensor s = scalar_tensor<int64_t>(42);
  const Tensor s2 = decode_npy(encode_npy(s), "s");
  CHECK(s2.shape.empty());
  CHECK(scalar_from<int64_t>(TensorMap{{"s", s2}}, "s") == 42);
  CHECK_THROWS(decode_npy({1, 2, 3}, "junk"));
}

TEST_CASE("zip: members round-trip and the write is atomic", "[core][npy]") {
  const auto dir = std::filesystem::temp_directory_path() / "rlrun_test_zip";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "a.zip").string();
  ZipMembers members{{"a.npy", {1, 2, 3}}, {"meta.json", {'{', '}'}}};
  write_zip_atomic(path, members);
  CHECK(!std::filesystem::exists(path + ".tmp"));
  CHECK(read_zip(path) == members);
  std::filesystem::remove_all(dir);
}

namespace {

// A .npy file with the given header dict (padded as numpy pads it) and `data_bytes` zeros.
std::vector<uint8_t> npy_with_header(const std::string& dict, size_t data_bytes) {
  std::string header = dict;
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string file("\x93NUMPY\x01\x00", 8);
  file += static_cast<char>(header.size() & 0xff);
  file += static_cast<char>(header.size() >> 8);
  file += header;
  file.append(data_bytes, '\0');
  return std::vector<uint8_t>(file.begin(), file.end());
}

std::string decode_error(const std::vector<uint8_t>& bytes) {
  try {
    decode_npy(bytes, "m.zip:w.npy");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("npy: headers as numpy writes them in any key order", "[core][npy]") {
  const Tensor t = decode_npy(
      npy_with_header("{'shape': (2,), \"fortran_order\": False, 'descr': '<f8'}", 16), "x");
  CHECK(t.dtype == DType::kFloat64);
  CHECK(t.shape == std::vector<int64_t>{2});
  CHECK(decode_npy(npy_with_header("{'descr':'<i8','fortran_order':False,'shape':(),}", 8), "x")
            .shape.empty());
  CHECK(decode_npy(
            npy_with_header("{'descr': '<u8', 'fortran_order': False, 'shape': (3, 0, 2)}", 0), "x")
            .numel() == 0);
}

TEST_CASE("npy: malformed headers are refused with a reason, never 'stoll'", "[core][npy]") {
  const auto refused = [](const std::string& dict, size_t data, const std::string& reason) {
    const std::string error = decode_error(npy_with_header(dict, data));
    INFO(dict << " -> " << error);
    CHECK(error.find("m.zip:w.npy: not a supported .npy array") == 0);
    CHECK(error.find(reason) != std::string::npos);
    CHECK(error.find("stoll") == std::string::npos);
  };
  const std::string f4 = "{'descr': '<f4', 'fortran_order': False, 'shape': ";
  refused(f4 + "('a', 3), }", 0, "not a non-negative integer");
  refused(f4 + "(3, x), }", 0, "not a non-negative integer");
  refused(f4 + "(-1,), }", 0, "not a non-negative integer");
  refused(f4 + "(99999999999999999999,), }", 0, "too large");
  refused(f4 + "(9223372036854775807,), }", 0, "overflows");
  refused(f4 + "(4294967296, 4294967296), }", 0, "overflows");
  refused(f4 + "(5), }", 20, "malformed shape");
  refused(f4 + "(2, 3), }", 23, "data size does not match shape");
  refused(f4 + "(2, 3), }", 25, "data size does not match shape");
  refused(f4 + "(2, 3), 'extra': 1}", 24, "unexpected or repeated key 'extra'");
  refused(f4 + "(2, 3), 'shape': (1,)}", 24, "unexpected or repeated key 'shape'");
  refused("{'descr': '<f4', 'shape': (1,)}", 4, "needs 'descr', 'fortran_order' and 'shape'");
  refused("{'descr': '<f4', 'fortran_order': True, 'shape': (1,)}", 4, "Fortran order");
  refused("{'descr': '<i4', 'fortran_order': False, 'shape': (1,)}", 4, "unsupported dtype '<i4'");
  refused("{'descr': '>f4', 'fortran_order': False, 'shape': (1,)}", 4, "unsupported dtype '>f4'");
  refused("{'descr': '|O', 'fortran_order': False, 'shape': (1,)}", 8, "unsupported dtype '|O'");
  refused("{'descr': '<f4', 'fortran_order': False, 'shape': (1,)} junk", 4, "bytes after");
  refused("{'descr': '<f4\\'', 'fortran_order': False, 'shape': (1,)}", 4, "escapes");
  refused(f4 + std::string(100, '(') + "1,), }", 4, "not a non-negative integer");
  std::string many_dims = f4 + "(";
  for (int i = 0; i < 40; ++i) many_dims += "1, ";
  refused(many_dims + "), }", 4, "more than 32 dimensions");
}

TEST_CASE("npy: prelude problems: magic, version, header length past the end", "[core][npy]") {
  std::vector<uint8_t> bytes =
      npy_with_header("{'descr': '<f4', 'fortran_order': False, 'shape': (1,)}", 4);
  std::vector<uint8_t> v2 = bytes;
  v2[6] = 2;
  CHECK(decode_error(v2).find("only format version 1.0") != std::string::npos);
  std::vector<uint8_t> huge_header = bytes;
  huge_header[8] = huge_header[9] = 0xff;  // header_len 65535 in a 132-byte file
  CHECK(decode_error(huge_header).find("truncated header") != std::string::npos);
  std::vector<uint8_t> no_magic = bytes;
  no_magic[1] = 'X';
  CHECK(decode_error(no_magic).find("no magic") != std::string::npos);
  CHECK(decode_error({0x93, 'N', 'U'}).find("no magic") != std::string::npos);
}
