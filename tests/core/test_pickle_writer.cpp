// Writing pickles, zips and torch files without Python (core/pickle_writer.hpp,
// core/stored_zip.hpp, core/torch_file_writer.hpp, core/numpy_pickle_writer.hpp), read back
// by rlrun's own readers. tests/python/test_sb3_models.py reads the same bytes with Python's
// pickle and zipfile modules.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "rlrun/core/base64.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/numpy_pickle.hpp"
#include "rlrun/core/numpy_pickle_writer.hpp"
#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/pickle_writer.hpp"
#include "rlrun/core/stored_zip.hpp"
#include "rlrun/core/torch_file_writer.hpp"
#include "rlrun/core/torch_state_dict.hpp"
#include "rlrun/core/zip_reader.hpp"

using namespace rlrun;

namespace {

PickleDocument read_back(const std::vector<uint8_t>& bytes, const PickleGlobalFilter& allowed) {
  return read_pickle(bytes.data(), bytes.size(), "test", allowed);
}

const PickleGlobalFilter kNoGlobals = [](const std::string&, const std::string&) { return false; };

Tensor float_tensor(std::vector<int64_t> shape, float first) {
  Tensor t;
  t.dtype = DType::kFloat32;
  t.shape = std::move(shape);
  t.bytes.resize(static_cast<size_t>(t.numel()) * sizeof(float));
  for (int64_t i = 0; i < t.numel(); ++i) t.data<float>()[i] = first + static_cast<float>(i);
  return t;
}

}  // namespace

TEST_CASE("pickle writer: every value reads back as written", "[pickle]") {
  const std::vector<int64_t> ints = {0,
                                     1,
                                     255,
                                     256,
                                     65535,
                                     65536,
                                     -1,
                                     std::numeric_limits<int32_t>::min(),
                                     std::numeric_limits<int32_t>::max(),
                                     int64_t{1} << 40,
                                     std::numeric_limits<int64_t>::min(),
                                     std::numeric_limits<int64_t>::max()};
  PickleWriter p(3);
  p.empty_dict();
  p.mark();
  p.text("ints");
  p.int_list(ints);
  p.text("float");
  p.real(-0.1);
  p.text("tuple");
  p.mark();
  p.none();
  p.boolean(true);
  p.boolean(false);
  p.text("caf\xc3\xa9");
  const uint8_t raw[3] = {0, '\n', 255};
  p.bytes(raw, 3);
  p.tuple_from_mark();
  p.text("empty");
  p.empty_tuple();
  p.set_items();
  const PickleDocument doc = read_back(p.finish(), kNoGlobals);
  const PickleValue& root = doc.root();
  REQUIRE(root.kind == PickleKind::kDict);
  const PickleValue* list = pickle_dict_get(root, "ints");
  REQUIRE(list);
  REQUIRE(list->items.size() == ints.size());
  for (size_t i = 0; i < ints.size(); ++i) {
    INFO(ints[i]);
    CHECK(list->items[i]->kind == PickleKind::kInt);
    CHECK(list->items[i]->integer == ints[i]);
  }
  CHECK(pickle_dict_get(root, "float")->number == -0.1);
  const PickleValue& tuple = *pickle_dict_get(root, "tuple");
  REQUIRE(tuple.items.size() == 5);
  CHECK(tuple.items[0]->kind == PickleKind::kNone);
  CHECK(tuple.items[1]->boolean);
  CHECK_FALSE(tuple.items[2]->boolean);
  CHECK(tuple.items[3]->text == "caf\xc3\xa9");
  CHECK(tuple.items[4]->text == std::string("\0\n\xff", 3));
  CHECK(pickle_dict_get(root, "empty")->kind == PickleKind::kTuple);
}

TEST_CASE("pickle writer: globals, calls and BUILD read back, bytes need protocol 3", "[pickle]") {
  PickleWriter p(4);
  p.global_ref("collections", "OrderedDict");
  p.empty_tuple();
  p.reduce();
  p.empty_dict();
  p.build();
  const PickleDocument doc = read_back(p.finish(), [](const std::string& m, const std::string& n) {
    return m == "collections" && n == "OrderedDict";
  });
  REQUIRE(doc.root().callee());
  CHECK(doc.root().callee()->is_global("collections", "OrderedDict"));
  CHECK(doc.root().state);
  // The reader's allowlist still holds for what the writer writes.
  PickleWriter os(2);
  os.global_ref("os", "system");
  CHECK_THROWS_AS(read_back(os.finish(), kNoGlobals), RuntimeFailure);
  PickleWriter old(2);
  const uint8_t b = 1;
  CHECK_THROWS(old.bytes(&b, 1));
  CHECK_THROWS(old.global_ref("a\nb", "c"));
}

TEST_CASE("numpy values written into a pickle read back", "[pickle]") {
  PickleWriter p(3);
  p.mark();
  pickle_numpy_float32_array(p, {1.5f, -INFINITY, 3.0f, 4.0f}, {2, 2});
  pickle_numpy_int64_array(p, {3, 5, 7});
  pickle_numpy_bool_array(p, {true, false}, {2});
  pickle_numpy_int64(p, -42);
  pickle_numpy_dtype(p, "u1");
  p.tuple_from_mark();
  const PickleDocument doc = read_back(p.finish(), is_numpy_pickle_global);
  const auto& items = doc.root().items;
  REQUIRE(items.size() == 5);
  const NumpyArray f = numpy_array(*items[0], "f");
  CHECK(f.dtype.name() == "float32");
  CHECK(f.shape == std::vector<int64_t>{2, 2});
  CHECK(f.to_doubles() == std::vector<double>{1.5, -INFINITY, 3.0, 4.0});
  CHECK(numpy_array(*items[1], "i").to_doubles() == std::vector<double>{3, 5, 7});
  CHECK(numpy_array(*items[2], "b").dtype.name() == "bool");
  CHECK(pickled_integer(*items[3], "s") == -42);
  CHECK(numpy_dtype(*items[4], "d").name() == "uint8");
}

TEST_CASE("stored zip: members, CRCs and 64-byte aligned data read back", "[pickle]") {
  CHECK(zip_crc32(reinterpret_cast<const uint8_t*>("123456789"), 9) == 0xCBF43926u);
  std::vector<StoredZipMember> members;
  for (int i = 0; i < 5; ++i)
    members.emplace_back(
        "dir/member" + std::string(static_cast<size_t>(i), 'x'),
        std::vector<uint8_t>(static_cast<size_t>(i * 37), static_cast<uint8_t>(i)));
  const std::vector<uint8_t> bytes = stored_zip(members, 64);
  CHECK(stored_zip(members, 64) == bytes);  // the same bytes every time
  const ZipReader zip(bytes, "test.zip");
  REQUIRE(zip.entries().size() == members.size());
  for (const auto& [name, data] : members) {
    const ZipEntry* entry = zip.find(name);
    REQUIRE(entry);
    CHECK(zip.read(*entry, 1 << 20) == data);
    if (data.empty()) continue;
    // The data starts at a multiple of 64: find it right after the member's local header.
    const auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
    REQUIRE(at != bytes.end());
    const size_t header = static_cast<size_t>(at - bytes.begin()) - 30;
    const size_t extra = bytes[header + 28] | (bytes[header + 29] << 8);
    CHECK((header + 30 + name.size() + extra) % 64 == 0);
  }
}

TEST_CASE("torch files written without torch read back as the same tensors", "[pickle]") {
  Tensor weight = float_tensor({3, 2}, 0.5f);
  Tensor bias = float_tensor({3}, -1.0f);
  Tensor scalar = float_tensor({}, 7.0f);
  Tensor steps;
  steps.dtype = DType::kInt64;
  steps.shape = {2};
  steps.bytes.resize(16);
  const int64_t values[2] = {5, -6};
  std::memcpy(steps.bytes.data(), values, 16);
  const std::vector<uint8_t> file = torch_save_state_dict(
      {{"net.0.weight", &weight}, {"net.0.bias", &bias}, {"log_std", &scalar}, {"n", &steps}});
  const TensorMap back = read_torch_tensors(file, "test.pth", 1 << 20);
  REQUIRE(back.size() == 4);
  for (const auto& [name, tensor] : {std::pair<std::string, const Tensor*>{"net.0.weight", &weight},
                                     {"net.0.bias", &bias},
                                     {"log_std", &scalar},
                                     {"n", &steps}}) {
    INFO(name);
    REQUIRE(back.count(name));
    CHECK(back.at(name).dtype == tensor->dtype);
    CHECK(back.at(name).shape == tensor->shape);
    CHECK(back.at(name).bytes == tensor->bytes);
  }
  // torch's layout: archive/data.pkl first, then byteorder, the storages and version.
  const ZipReader zip(file, "test.pth");
  CHECK(zip.entries().front().name == "archive/data.pkl");
  CHECK(zip.find("archive/version"));
  CHECK(zip.find("archive/data/3"));
  // An empty dict (SB3's pytorch_variables.pth of PPO) reads back empty.
  CHECK(read_torch_tensors(torch_save_state_dict({}), "empty.pth", 1 << 20).empty());
  Tensor unsigned64;
  unsigned64.dtype = DType::kUInt64;
  unsigned64.shape = {1};
  unsigned64.bytes.resize(8);
  CHECK_THROWS_AS(torch_save_state_dict({{"u", &unsigned64}}), RuntimeFailure);
}

TEST_CASE("base64 encoding is Python's b64encode and decodes back", "[pickle]") {
  CHECK(encode_base64({}).empty());
  CHECK(encode_base64({'f'}) == "Zg==");
  CHECK(encode_base64({'f', 'o'}) == "Zm8=");
  CHECK(encode_base64({'f', 'o', 'o'}) == "Zm9v");
  CHECK(encode_base64({'f', 'o', 'o', 'b', 'a', 'r'}) == "Zm9vYmFy");
  std::vector<uint8_t> all;
  for (int i = 0; i < 256; ++i) all.push_back(static_cast<uint8_t>(i));
  CHECK(decode_base64(encode_base64(all)) == all);
}
