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
