// core/pickle_reader.hpp and core/base64.hpp. The pickles are what CPython 3.11's pickle.dumps
// wrote (the line above each says what it pickled), so the reader is checked against the real
// format, not against the test's idea of it.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "rlrun/core/base64.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/pickle_reader.hpp"

using namespace rlrun;

namespace {

std::vector<uint8_t> from_hex(const std::string& hex) {
  std::vector<uint8_t> out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    out.push_back(static_cast<uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return out;
}

bool no_globals(const std::string&, const std::string&) { return false; }

PickleDocument read_hex(const std::string& hex, const PickleGlobalFilter& allowed = no_globals) {
  const std::vector<uint8_t> bytes = from_hex(hex);
  return read_pickle(bytes.data(), bytes.size(), "test.pkl", allowed);
}

std::string refusal(const std::string& hex, const PickleGlobalFilter& allowed = no_globals) {
  try {
    read_hex(hex, allowed);
  } catch (const RuntimeFailure& e) {
    return e.what();
  }
  return "";
}

const PickleValue* item(const PickleValue& dict, const std::string& key) {
  for (size_t i = 0; i + 1 < dict.items.size(); i += 2)
    if (dict.items[i]->text == key) return dict.items[i + 1];
  return nullptr;
}

// {'a': [1, -2, 3.5, 'x', b'yz', None, True], 'big': 2**40, 'neg': -2**40, 't': (1, 2, 3, 4),
//  'u': 'é'}, protocol 5
const char* kDictProtocol5 =
    "8005955c000000000000007d94288c0161945d94284b014afeffffff47400c0000000000008c0178944302797a9"
    "44e88658c03626967948a060000000000018c036e6567948a060000000000ff8c017494284b014b024b034b0474"
    "948c0175948c02c3a994752e";
// The same, protocol 2 (bytes are written as a call of _codecs.encode there).
const char* kDictProtocol2 =
    "80027d71002858010000006171015d7102284b014afeffffff47400c0000000000005801000000787103635f636"
    "f646563730a656e636f64650a71045802000000797a710558060000006c6174696e3171068671075271084e8865"
    "580300000062696771098a0600000000000158030000006e6567710a8a060000000000ff580100000074710b284"
    "b014b024b034b0474710c580100000075710d5802000000c3a9710e752e";

}  // namespace

TEST_CASE("the pickle reader reads protocol 5 data as Python wrote it", "[pickle]") {
  const PickleDocument doc = read_hex(kDictProtocol5);
  const PickleValue& root = doc.root();
  REQUIRE(root.kind == PickleKind::kDict);
  const PickleValue* a = item(root, "a");
  REQUIRE(a);
  REQUIRE(a->kind == PickleKind::kList);
  REQUIRE(a->items.size() == 7);
  CHECK(a->items[0]->integer == 1);
  CHECK(a->items[1]->integer == -2);
  CHECK(a->items[2]->number == 3.5);
  CHECK(a->items[3]->text == "x");
  CHECK(a->items[4]->kind == PickleKind::kBytes);
  CHECK(a->items[4]->text == "yz");
  CHECK(a->items[5]->kind == PickleKind::kNone);
  CHECK(a->items[6]->boolean);
  CHECK(item(root, "big")->integer == (int64_t{1} << 40));
  CHECK(item(root, "neg")->integer == -(int64_t{1} << 40));
  CHECK(item(root, "t")->kind == PickleKind::kTuple);
  CHECK(item(root, "t")->items.size() == 4);
  CHECK(item(root, "u")->text == "\xc3\xa9");
}

TEST_CASE("the pickle reader reads protocol 2 and keeps calls as data", "[pickle]") {
  CHECK_THAT(refusal(kDictProtocol2), Catch::Contains("_codecs.encode"));
  const PickleDocument doc = read_hex(
      kDictProtocol2,
      [](const std::string& m, const std::string& n) { return m == "_codecs" && n == "encode"; });
  const PickleValue* bytes = item(doc.root(), "a")->items[4];
  REQUIRE(bytes->kind == PickleKind::kCall);
  REQUIRE(bytes->callee());
  CHECK(bytes->callee()->is_global("_codecs", "encode"));
  CHECK(bytes->arguments().items[0]->text == "yz");
}

TEST_CASE("the pickle reader keeps an OrderedDict's items and state", "[pickle]") {
  // od = OrderedDict([('w', 1.0), ('b', 2)]); od.extra = 'x'; protocols 2 and 5
  for (const char* hex :
       {"800263636f6c6c656374696f6e730a4f726465726564446963740a71002952710128580100000077710247"
        "3ff000000000000058010000006271034b02757d7104580500000065787472617105580100000078710673"
        "622e",
        "80059547000000000000008c0b636f6c6c656374696f6e73948c0b4f72646572656444696374949394295"
        "294288c017794473ff00000000000008c0162944b02757d948c056578747261948c01789473622e"}) {
    const PickleDocument doc = read_hex(hex, [](const std::string& m, const std::string& n) {
      return m == "collections" && n == "OrderedDict";
    });
    const PickleValue& od = doc.root();
    REQUIRE(od.callee());
    CHECK(od.callee()->is_global("collections", "OrderedDict"));
    REQUIRE(od.added_pairs);
    REQUIRE(od.added_items.size() == 4);
    CHECK(od.added_items[0]->text == "w");
    CHECK(od.added_items[1]->number == 1.0);
    CHECK(od.added_items[3]->integer == 2);
    REQUIRE(od.state);
    CHECK(item(*od.state, "extra")->text == "x");
  }
}

TEST_CASE("the pickle reader shares memoised values without copying them", "[pickle]") {
  // s = [1, 2]; [s, s, (s,)]
  const PickleDocument doc = read_hex(
      "80059513000000000000005d94285d94284b014b02656801680185946"
      "52e");
  const PickleValue& root = doc.root();
  REQUIRE(root.items.size() == 3);
  CHECK(root.items[0] == root.items[1]);
  CHECK(root.items[2]->items[0] == root.items[0]);
}

TEST_CASE("a pickle that would run code is refused before anything runs", "[pickle][security]") {
  // class E: __reduce__ = lambda self: (os.system, ("touch /tmp/rlrun_pwned",)); protocol 5
  const std::string evil =
      "80059531000000000000008c05706f736978948c0673797374656d9493948c16746f756368202f746d702f72"
      "6c72756e5f70776e656494859452942e";
  CHECK_THAT(refusal(evil), Catch::Contains("posix.system") && Catch::Contains("does not read"));
  // Allowed, the call is a node of the tree: still nothing runs.
  const PickleDocument doc =
      read_hex(evil, [](const std::string&, const std::string&) { return true; });
  CHECK(doc.root().kind == PickleKind::kCall);
}

TEST_CASE("the pickle reader refuses what it does not read", "[pickle][security]") {
  // l = []; l.append(l)
  CHECK_THAT(refusal("80059506000000000000005d946800612e"), Catch::Contains("contains itself"));
  // 100 nested lists
  std::string deep = "800595";
  deep += "2f01000000000000";
  for (int i = 0; i < 100; ++i) deep += "5d94";
  deep += "4b00";
  for (int i = 0; i < 100; ++i) deep += "61";
  deep += "2e";
  CHECK_THAT(refusal(deep), Catch::Contains("nested deeper"));
  // protocol 0: [1]
  CHECK_THAT(refusal("286c70300a49310a612e"), Catch::Contains("opcode PUT"));
  // 2**100 is read as a big int; an int of 100 bytes is refused
  CHECK(read_hex("80059510000000000000008a0d000000000000000000000000102e").root().kind ==
        PickleKind::kBigInt);
  CHECK_THAT(refusal("80058a64" + std::string(200, '0') + "2e"), Catch::Contains("100 bytes"));
  // truncated, trailing data, no STOP, a string running past the end, an unknown opcode
  CHECK_THAT(refusal("80055d94"), Catch::Contains("without STOP"));
  CHECK_THAT(refusal("80054b012e00"), Catch::Contains("after STOP"));
  CHECK_THAT(refusal("80058c05616263"), Catch::Contains("past the end"));
  CHECK_THAT(refusal("8005ff2e"), Catch::Contains("not a pickle opcode"));
  CHECK_THAT(refusal("8005582000000000"), Catch::Contains("past the end"));  // 32 bytes, none there
  CHECK_THAT(refusal("80052e"), Catch::Contains("STOP leaves 0 values"));
  CHECK_THAT(refusal("8005612e"), Catch::Contains("stack is empty"));
  CHECK_THAT(refusal("8005680a2e"), Catch::Contains("never stored"));
  CHECK_THAT(refusal("800a4b012e"), Catch::Contains("protocol 10"));
  CHECK_THAT(refusal("80058c02c3284b012e"), Catch::Contains("not UTF-8"));
}

TEST_CASE("base64 decodes what Python's b64encode writes and nothing else", "[pickle]") {
  const auto decoded = decode_base64("gAWVLQ==");
  REQUIRE(decoded);
  CHECK(*decoded == std::vector<uint8_t>{0x80, 0x05, 0x95, 0x2d});
  CHECK(decode_base64("")->empty());
  CHECK(*decode_base64("YWJj") == std::vector<uint8_t>{'a', 'b', 'c'});
  CHECK(*decode_base64("YWI=") == std::vector<uint8_t>{'a', 'b'});
  CHECK_FALSE(decode_base64("YWJ"));
  CHECK_FALSE(decode_base64("YW=j"));
  CHECK_FALSE(decode_base64("YW J"));
  CHECK_FALSE(decode_base64("YQ==YQ=="));
}
