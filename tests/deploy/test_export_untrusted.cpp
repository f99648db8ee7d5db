// `rlrun export` of an untrusted model file (docs/security.md): the strings of its meta.json
// reach the generated C header's comment and the ONNX metadata, and its numbers the C literals.
// A string must not end the comment (`*/`, `*\` newline `/`, the trigraph `??/`), nor make the
// ONNX file unreadable (protobuf strings are UTF-8); a number C cannot write (NaN, an infinite
// weight) is refused. The C files are compiled with -std=c99 -Wall -Wextra -Werror -pedantic
// -trigraphs, their preprocessed text must hold nothing of the injected code, and Debian's
// python3-onnx checker must accept the ONNX file with the metadata readable.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/crafted_zip.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/utf8_text.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/deploy/c_comment_text.hpp"
#include "rlrun/deploy/c_writer.hpp"
#include "rlrun/deploy/onnx_writer.hpp"
#include "rlrun/nn/policy_graph.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// A tiny CartPole PPO model with observation statistics: <dir>/runs/t/seed1/model.zip.
struct TinyModel {
  explicit TinyModel(const std::string& name) : dir(name) {
    std::ofstream(dir / "t.yaml")
        << "run: {name: t, seed: 1, total_timesteps: 64, out_dir: " << dir.str() << "/runs}\n"
        << "env: {id: CartPole-v1, wrappers: [{id: NormalizeObservation}]}\n"
        << "algo: {id: PPO, n_steps: 32, batch_size: 32, n_epochs: 1, policy: {net_arch: [4]}}\n";
    const auto r = run_rlrun("train " + dir / "t.yaml");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  std::string path() const { return dir / "runs/t/seed1/model.zip"; }
  // The model with `edit` applied to its members, as `<dir>/<name>.zip`.
  template <class Edit>
  std::string variant(const std::string& name, Edit edit) const {
    ZipMembers members = read_zip(path());
    edit(members);
    std::vector<CraftedMember> crafted;
    for (auto& [member, data] : members) crafted.push_back(CraftedMember{member, data});
    const std::string out = dir / (name + ".zip");
    write_crafted_zip(out, crafted);
    return out;
  }
  std::string with_meta(const std::string& name, const std::string& key,
                        const std::string& value) const {
    return variant(name, [&](ZipMembers& members) {
      nlohmann::json meta = nlohmann::json::parse(members.at("meta.json"));
      meta[key] = value;
      const std::string text = meta.dump(2);
      members["meta.json"] = std::vector<uint8_t>(text.begin(), text.end());
    });
  }
  TempDir dir;
};

// Exports `model` as C into <dir>/<name>_c, compiles policy.c with the test driver under the
// strictest flags (-trigraphs: `??/` is a backslash), and returns policy.h as the preprocessor
// sees it (comments gone): whatever escaped the comment is in there.
std::string export_c_and_compile(const TinyModel& tiny, const std::string& model,
                                 const std::string& name) {
  const std::string c_dir = tiny.dir / (name + "_c");
  const auto x = run_rlrun("export --model " + model + " --format c --output " + c_dir);
  INFO(x.output);
  REQUIRE(x.exit_code == 0);
  const std::string flags =
      "-std=c99 -Wall -Wextra -Werror -pedantic -trigraphs -I'" + c_dir + "' ";
  const CommandResult cc = run_command("cc " + flags + "'" + std::string(RLRUN_SOURCE_DIR) +
                                       "/tests/deploy/c_policy_main.c' '" + c_dir +
                                       "/policy.c' -lm -o '" + tiny.dir / (name + "_run") + "'");
  INFO(read_text(c_dir + "/policy.h"));
  INFO(cc.output);
  REQUIRE(cc.exit_code == 0);
  const CommandResult pre = run_command("cc -std=c99 -trigraphs -E -P '" + c_dir + "/policy.h'");
  REQUIRE(pre.exit_code == 0);
  return pre.output;
}

// Exports `model` as ONNX; Debian's onnx checker must accept it; returns its env_id metadata.
std::string export_onnx_env_id(const TinyModel& tiny, const std::string& model,
                               const std::string& name) {
  const std::string onnx = tiny.dir / (name + ".onnx");
  const auto x = run_rlrun("export --model " + model + " --output " + onnx);
  INFO(x.output);
  REQUIRE(x.exit_code == 0);
  const CommandResult check = run_command(
      "/usr/bin/python3 -c \"import onnx, sys; m = onnx.load(sys.argv[1]); "
      "onnx.checker.check_model(m, full_check=True); "
      "sys.stdout.write({p.key: p.value for p in m.metadata_props}['env_id'])\" '" +
      onnx + "'");
  INFO(check.output);
  REQUIRE(check.exit_code == 0);
  return check.output;
}

// One Dense layer obs (2) -> action (1) with `weight` and `bias`, and `metadata`.
PolicyGraph one_layer(float weight, float bias, std::map<std::string, std::string> metadata = {}) {
  PolicyGraph graph;
  graph.add_input("obs", 2);
  graph.set_action(graph.dense("obs", Eigen::MatrixXf::Constant(1, 2, weight),
                               Eigen::VectorXf::Constant(1, bias)));
  graph.metadata = std::move(metadata);
  return graph;
}

}  // namespace

TEST_CASE("export: c_comment_text and printable_utf8 keep hostile text inert",
          "[deploy][export][untrusted]") {
  const std::string plain =
      "Box([-4.8 -inf], [4.8 inf], (2,), float32) Dict('a': Discrete(3)) ~^|{}";
  CHECK(c_comment_text(plain) == plain);
  CHECK(c_comment_text("*/") == "%2A/");
  CHECK(c_comment_text("*\\\n/") == "%2A%5C%0A/");
  CHECK(c_comment_text("?\?/") == "%3F%3F/");
  static constexpr char kBytes[] = "a\0b\x7f\x1b$@`%";
  CHECK(c_comment_text(std::string(kBytes, sizeof kBytes - 1)) == "a%00b%7F%1B%24%40%60%25");
  CHECK(c_comment_text("\xc3\xa9") == "%C3%A9");

  CHECK(valid_utf8("plain \xc3\xa9 \xe2\x88\x9e \xf0\x9f\x98\x80"));
  CHECK_FALSE(valid_utf8("\xff"));
  CHECK_FALSE(valid_utf8("\xc0\xaf"));          // overlong '/'
  CHECK_FALSE(valid_utf8("\xed\xa0\x80"));      // a surrogate
  CHECK_FALSE(valid_utf8("\xf4\x90\x80\x80"));  // beyond U+10FFFF
  CHECK_FALSE(valid_utf8("\xe2\x88"));          // cut short
  CHECK(printable_utf8("CartPole-v1 \xc3\xa9") == "CartPole-v1 \xc3\xa9");
  CHECK(printable_utf8(std::string("a\0\n\\\xff\xc2\x85", 7)) == "a\\x00\\x0a\\\\\\xff\\xc2\\x85");
  CHECK(valid_utf8(printable_utf8("\xf4\x90\x80\x80 \xed\xa0\x80 \xc3")));
}

TEST_CASE("export: meta.json strings cannot end the C header's comment or break the ONNX file",
          "[deploy][export][untrusted]") {
  TinyModel tiny("export_injection");
  static constexpr char kControls[] = "a\0b\x07\x1b[2J\x7f \xc3\xa9 \xc2\x85 */ int injected_c;";
  // The case: `*\` newline `/` is `*/` after line splicing (translation phase 2).
  const std::vector<std::pair<std::string, std::string>> attacks = {
      {"splice",
       "CartPole-v1 *\\\n/ __attribute__((constructor)) static void injected(void) "
       "{ __builtin_trap(); } /*"},
      {"close", "x */ int injected_global = 1; /* "},
      {"trigraph", "x *?\?/\n/ int injected_trigraph; /* ?\?= ?\?' "},
      {"controls", std::string(kControls, sizeof kControls - 1)},
  };
  for (const auto& [name, text] : attacks) {
    INFO(name);
    const std::string model = tiny.with_meta(name, "env_id", text);
    const std::string header = export_c_and_compile(tiny, model, name);
    CHECK(header.find("void policy_act(const float *obs, float *action);") != std::string::npos);
    CHECK(header.find("injected") == std::string::npos);
    CHECK(export_onnx_env_id(tiny, model, name) == printable_utf8(text));
  }
  // The model's version string reaches the comment too (model_rlrun_version).
  const std::string version = tiny.with_meta("version", "rlrun_version", "1 */ int injected_v; /*");
  CHECK(export_c_and_compile(tiny, version, "version").find("injected") == std::string::npos);
}

TEST_CASE("export: metadata that is not UTF-8 is escaped, Dict keys that cannot be names refused",
          "[deploy][export][untrusted]") {
  // meta.json is JSON (UTF-8 by rule), but the writers take any graph: text reaching a protobuf
  // string must be UTF-8, or python's onnx.load refuses the whole file.
  TempDir dir("export_utf8");
  const PolicyGraph graph =
      one_layer(0.5f, 0.25f, {{"env_id", "bad \xff\xfe end"}, {"key \xc0", "value"}});
  const std::string onnx = dir / "p.onnx";
  std::ofstream(onnx, std::ios::binary) << onnx_model_bytes(graph);
  const CommandResult check = run_command(
      "/usr/bin/python3 -c \"import onnx, sys; m = onnx.load(sys.argv[1]); "
      "onnx.checker.check_model(m, full_check=True); "
      "sys.stdout.write({p.key: p.value for p in m.metadata_props}['env_id'])\" '" +
      onnx + "'");
  INFO(check.output);
  REQUIRE(check.exit_code == 0);
  CHECK(check.output == "bad \\xff\\xfe end");

  for (const std::string& key :
       {std::string("k\xff"), std::string("a\nb"), std::string("rlrun/Gemm_0")}) {
    PolicyGraph dict;
    dict.add_input(key, 2);
    dict.add_input("other", 1);
    dict.set_action(dict.concat({key, "other"}));
    CHECK_THROWS_AS(onnx_model_bytes(dict), ExportError);
    // C: a key is only named in the comment, escaped. (Appended: GCC 12 warns -Wrestrict on
    // `" " + string`.)
    std::string listed = " ";
    listed += c_comment_text(key);
    listed += " [0, 2)";
    CHECK(c_policy_source(dict).header.find(listed) != std::string::npos);
  }
  // A Dict key spelled like a node's name: the node moves aside, the graph stays SSA.
  PolicyGraph clash;
  clash.add_input("concat_0", 1);
  clash.add_input("b", 1);
  const std::string both = clash.concat({"concat_0", "b"});
  CHECK(both != "concat_0");
  CHECK(clash.width("concat_0") == 1);
  CHECK(clash.width(both) == 2);
}

TEST_CASE("export: NaN and infinite numbers are refused naming the tensor, bounds may be infinite",
          "[deploy][export][untrusted]") {
  constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  CHECK_THROWS_WITH(c_policy_source(one_layer(kNan, 0.0f)),
                    Catch::Contains("dense_0 (Dense weight) holds nan at row 0, column 0"));
  CHECK_THROWS_WITH(onnx_model_bytes(one_layer(kNan, 0.0f)),
                    Catch::Contains("dense_0 (Dense weight) holds nan"));
  CHECK_THROWS_WITH(
      c_policy_source(one_layer(1.0f, -kInf)),
      Catch::Contains("dense_0 (Dense bias) holds -inf at index 0 (only bounds may be infinite)"));
  // Infinite bounds are HUGE_VALF; a NaN bound is refused.
  PolicyGraph clamp = one_layer(1.0f, 0.0f);
  clamp.set_action(clamp.clamp(clamp.action(), Eigen::VectorXf::Constant(1, -kInf),
                               Eigen::VectorXf::Constant(1, 2.0f)));
  CHECK(c_policy_source(clamp).source.find("-HUGE_VALF") != std::string::npos);
  CHECK_NOTHROW(onnx_model_bytes(clamp));
  PolicyGraph nan_bound = one_layer(1.0f, 0.0f);
  nan_bound.set_action(nan_bound.clamp(nan_bound.action(), Eigen::VectorXf::Constant(1, kNan),
                                       Eigen::VectorXf::Constant(1, 2.0f)));
  CHECK_THROWS_WITH(c_policy_source(nan_bound), Catch::Contains("(Clamp low) holds nan"));

  // Through the binary: observation statistics that are finite in float64 but not in float32
  // (a mean of 1e300) cannot be exported; eval still runs them (its arithmetic is float64).
  TinyModel tiny("export_overflow");
  const std::string model = tiny.variant("huge_mean", [](ZipMembers& members) {
    std::vector<uint8_t>& mean = members.at("wrappers/NormalizeObservation/mean.npy");
    Tensor t = decode_npy(mean, "mean");
    t.data<double>()[1] = 1e300;
    mean = encode_npy(t);
  });
  for (const char* format : {"c", "onnx"}) {
    const std::string out = tiny.dir / (std::string("huge_") + format);
    const auto r =
        run_rlrun("export --model " + model + " --format " + format + " --output " + out);
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(r.output.find("(Affine shift) holds -inf at index 1") != std::string::npos);
    CHECK_FALSE(fs::exists(out + "/policy.c"));
    CHECK_FALSE(fs::exists(out));
  }
}
