// A model file or checkpoint whose weights or normalisation statistics are not numbers an
// evaluation can use (NaN, infinity, a negative variance or count): every command that loads
// one refuses it naming the tensor (runtime/io/model_file.hpp), instead of evaluating to a mean
// reward of nan with exit 0 or exporting it. A resume skips such a checkpoint for the previous
// good one, with a note, and never calls it "the last good checkpoint".
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/crafted_zip.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/policy.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A tiny CartPole PPO run with observation statistics and checkpoints at steps 64 and 128.
struct TinyRun {
  explicit TinyRun(const std::string& name) : dir(name) {
    std::ofstream(dir / "tiny.yaml")
        << "run: {name: tiny, seed: 1, total_timesteps: 128}\n"
           "env: {id: CartPole-v1, wrappers: [{id: NormalizeObservation}]}\n"
           "algo: {id: PPO, n_steps: 32, batch_size: 32, n_epochs: 1, policy: {net_arch: [4]}}\n"
           "checkpoint: {freq: 64}\n";
    const auto r = run_rlrun("train " + dir / "tiny.yaml" + " --set run.out_dir=" + dir / "runs");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  std::string run() const { return dir / "runs/tiny/seed1"; }
  std::string model() const { return run() + "/model.zip"; }
  std::string checkpoint(int step) const {
    return run() + "/checkpoints/step_" + std::to_string(step) + ".zip";
  }
  TempDir dir;
};

// `source` with element `index` of tensor member `member` (float32 or float64) set to `value`,
// written to `path`.
std::string tampered(const std::string& source, const std::string& path, const std::string& member,
                     size_t index, double value) {
  ZipMembers members = read_zip(source);
  Tensor t = decode_npy(members.at(member), member);
  if (t.dtype == DType::kFloat32)
    t.data<float>()[index] = static_cast<float>(value);
  else
    t.data<double>()[index] = value;
  members[member] = encode_npy(t);
  std::vector<CraftedMember> crafted;
  for (auto& [name, data] : members) crafted.push_back(CraftedMember{name, data});
  write_crafted_zip(path, crafted);
  return path;
}

void check_refused(const CommandResult& r, const std::string& fragment) {
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find(fragment) != std::string::npos);
}

}  // namespace

TEST_CASE("non-finite model: eval, record, export and init-from refuse it naming the tensor",
          "[cli][untrusted][non_finite]") {
  TinyRun tiny("non_finite_model");
  const std::string nan_weight =
      tampered(tiny.model(), tiny.dir / "nan_weight.zip", "action_net.weight.npy", 3, kNan);
  const std::string named =
      nan_weight + ": parameter action_net.weight has 1 non-finite value (first: nan)";
  check_refused(run_rlrun("eval --model " + nan_weight + " --episodes 1"), named);
  check_refused(run_rlrun("record --model " + nan_weight + " --frames " + tiny.dir / "frames"),
                named);
  check_refused(run_rlrun("export --model " + nan_weight + " --output " + tiny.dir / "p.onnx"),
                named);
  CHECK_FALSE(fs::exists(tiny.dir / "p.onnx"));
  check_refused(run_rlrun("train " + tiny.dir / "tiny.yaml" +
                          " --set run.out_dir=" + tiny.dir / "again --init-from " + nan_weight),
                named);
  // The embeddable library too (Python's rlrun.load: tests/python/test_predict.py).
  CHECK_THROWS_WITH(Policy::load(nan_weight),
                    Catch::Contains("action_net.weight has 1 non-finite"));

  // Normalisation statistics: finite, variances and counts >= 0.
  const std::string stats = "wrappers/NormalizeObservation/";
  const auto statistic = [&](const std::string& field, size_t index, double value) {
    return tampered(tiny.model(), tiny.dir / (field + ".zip"), stats + field + ".npy", index,
                    value);
  };
  check_refused(run_rlrun("eval --model " + statistic("mean", 2, kInf)),
                "statistic " + stats + "mean has 1 non-finite value (first: inf)");
  check_refused(run_rlrun("eval --model " + statistic("var", 0, -1.0)),
                "statistic " + stats + "var has a negative value (-1.000000)");
  check_refused(run_rlrun("export --format c --output " + tiny.dir / "c --model " +
                          statistic("count", 0, -5.0)),
                "statistic " + stats + "count has a negative value");
  check_refused(run_rlrun("eval --model " + statistic("count", 0, kNan)),
                "statistic " + stats + "count has 1 non-finite value (first: nan)");
  // The untouched model still evaluates.
  CHECK(run_rlrun("eval --model " + tiny.model() + " --episodes 1").exit_code == 0);
}

TEST_CASE("non-finite checkpoint: resume skips it for the previous good one, or refuses",
          "[cli][resume][non_finite]") {
  TinyRun tiny("non_finite_resume");
  const std::string newest = tiny.checkpoint(128), older = tiny.checkpoint(64);
  const std::string good_newest = tiny.dir / "step_128.zip", good_older = tiny.dir / "step_64.zip";
  fs::copy_file(newest, good_newest);
  fs::copy_file(older, good_older);
  // NaN weights in the newest checkpoint: skipped with a note, the run goes on from step 64.
  tampered(good_newest, newest, "action_net.weight.npy", 0, kNan);
  const auto skipped = run_rlrun("train --resume " + tiny.run());
  INFO(skipped.output);
  CHECK(skipped.exit_code == 0);
  CHECK(skipped.output.find("note: skipping checkpoint " + newest + ": " + newest +
                            ": parameter action_net.weight has 1 non-finite value") !=
        std::string::npos);
  CHECK(skipped.output.find("from " + older) != std::string::npos);
  CHECK(skipped.output.find("last good checkpoint") == std::string::npos);

  // Both damaged: refused, naming each.
  tampered(good_newest, newest, "action_net.weight.npy", 0, kNan);
  tampered(good_older, older, "wrappers/NormalizeObservation/var.npy", 1, -2.0);
  const auto none = run_rlrun("train --resume " + tiny.run());
  check_refused(none, "cannot resume: no checkpoint can continue the run; tried:");
  CHECK(none.output.find("statistic wrappers/NormalizeObservation/var has a negative value") !=
        std::string::npos);
  CHECK(none.output.find("last good checkpoint") == std::string::npos);

  // NaN in the training state (optimizer moments, the env's running statistics): refused.
  fs::copy_file(good_older, older, fs::copy_options::overwrite_existing);
  tampered(good_newest, newest, "training/algo/optimizer/exp_avg_sq.0.npy", 5, kNan);
  check_refused(
      run_rlrun("train --resume " + newest),
      "checkpoint state 'training/algo/optimizer/exp_avg_sq.0' holds a NaN or infinite value");
  const std::string env_var = "training/env/0/normalize_observation/var.npy";
  REQUIRE(read_zip(good_newest).count(env_var) == 1);
  tampered(good_newest, newest, env_var, 0, -1.0);
  check_refused(run_rlrun("train --resume " + newest),
                "normalize_observation/var' is not a finite variance >= 0");
}
