// `rlrun train --resume` of a checkpoint whose buffer indices disagree with each other
// (docs/security.md: a checkpoint is untrusted). The case: a HER checkpoint whose
// unfinished episode "starts" at slot 999 while only 200 slots are written resumed with exit 0
// and relabelled goals from uninitialised memory (valgrind: 274 reports). It must be refused
// with the reason, before any training.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/crafted_zip.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// `source` with the int64 tensor `member`'s element `index` set to `value`, written to `path`.
void set_int(const std::string& source, const std::string& path, const std::string& member,
             size_t index, int64_t value) {
  ZipMembers members = read_zip(source);
  Tensor t = decode_npy(members.at(member), member);
  REQUIRE(t.dtype == DType::kInt64);
  t.data<int64_t>()[index] = value;
  members[member] = encode_npy(t);
  std::vector<CraftedMember> crafted;
  for (auto& [name, data] : members) crafted.push_back(CraftedMember{name, data});
  write_crafted_zip(path, crafted);
}

}  // namespace

TEST_CASE("resume: a HER checkpoint with inconsistent episode indices is refused",
          "[cli][resume][her][untrusted]") {
  TempDir dir("tampered_her");
  std::ofstream(dir / "her.yaml")
      << "run: {name: her, seed: 1, total_timesteps: 400, out_dir: " << dir.str()
      << "/runs}\n"
         "env: {id: BitFlippingEnv-v0, kwargs: {n_bits: 4}}\n"
         "algo: {id: DQN, replay_buffer_class: HerReplayBuffer, buffer_size: 1000,\n"
         "       learning_starts: 50, batch_size: 8, policy: {net_arch: [8]}}\n"
         "checkpoint: {freq: 200}\n";
  const auto trained = run_rlrun("train " + dir / "her.yaml");
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  const std::string checkpoint = dir / "runs/her/seed1/checkpoints/step_200.zip";
  const std::string original = dir / "step_200.zip";
  fs::copy_file(checkpoint, original);
  const std::string her = "training/algo/off_policy/replay_buffer/her/";

  set_int(original, checkpoint, her + "current_ep_start.npy", 0, 999);
  const auto r = run_rlrun("train --resume " + checkpoint);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(r.output.find("cannot resume from " + checkpoint + ": checkpoint HER buffer") !=
        std::string::npos);
  CHECK(r.output.find("env 0: the unfinished episode starts at slot 999, but 200 of 1000 slots "
                      "are written") != std::string::npos);
  // A finished episode reaching slots not written yet.
  set_int(original, checkpoint, her + "ep_length.npy", 0, 900);
  const auto beyond = run_rlrun("train --resume " + checkpoint);
  INFO(beyond.output);
  CHECK(beyond.exit_code == 1);
  CHECK(beyond.output.find("outside the 200 written slots") != std::string::npos);
  // The untouched checkpoint resumes.
  fs::copy_file(original, checkpoint, fs::copy_options::overwrite_existing);
  const auto resumed = run_rlrun("train --resume " + checkpoint);
  INFO(resumed.output);
  CHECK(resumed.exit_code == 0);
}
