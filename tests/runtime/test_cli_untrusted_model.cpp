// Hostile model files and checkpoints through the real binary (docs/security.md): each file is
// crafted by the test from a real tiny run (core/crafted_zip.hpp); rlrun must refuse it with
// exit 1 and a message naming the file and member — or skip what it does not use — while its
// peak memory stays small (a 4 GiB member must never be allocated or inflated).
#include <catch2/catch.hpp>
#include <filesystem>

#include "core/crafted_zip.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/peak_memory_bound.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// rlrun eval of a tiny CartPole model needs ~15 MB (more under ASan: peak_memory_bound.hpp); a
// member of the crafted sizes read or inflated whole would need 1 to 4 GiB.
constexpr long kMaxPeakRssKb = peak_rss_bound_kb(300 * 1024);
constexpr uint64_t kFourGiB = uint64_t{4} << 30;

const std::string kTinyConfig = R"(run: {name: tiny, seed: 1, total_timesteps: 128}
env: {id: CartPole-v1, n_envs: 2, wrappers: [{id: NormalizeObservation}]}
algo: {id: PPO, n_steps: 32, batch_size: 32, n_epochs: 1, policy: {net_arch: [8]}}
checkpoint: {freq: 64}
)";

// A tiny finished run: <dir>/runs/tiny/seed1 with model.zip and checkpoints/step_{64,128}.zip.
struct TinyRun {
  explicit TinyRun(const std::string& name) : dir(name) {
    std::ofstream(dir / "tiny.yaml") << kTinyConfig;
    const auto r = run_rlrun("train " + dir / "tiny.yaml" + " --set run.out_dir=" + dir / "runs");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
  }
  std::string run() const { return dir / "runs/tiny/seed1"; }
  std::string model() const { return run() + "/model.zip"; }
  std::string checkpoint() const { return run() + "/checkpoints/step_128.zip"; }
  TempDir dir;
};

std::vector<CraftedMember> members_of(const std::string& zip) {
  std::vector<CraftedMember> members;
  for (const auto& [name, data] : read_zip(zip)) members.push_back(CraftedMember{name, data});
  return members;
}

// `source`'s members with `name` replaced by `replacement` (or added), written to `path`.
std::string variant(const std::string& source, const std::string& path, CraftedMember replacement) {
  std::vector<CraftedMember> members = members_of(source);
  bool replaced = false;
  for (CraftedMember& m : members)
    if (m.name == replacement.name) {
      m = replacement;
      replaced = true;
    }
  if (!replaced) members.push_back(replacement);
  write_crafted_zip(path, members);
  return path;
}

CraftedMember declaring(const std::string& name, uint64_t declared, std::vector<uint8_t> inflated) {
  CraftedMember m{name, raw_deflate(inflated)};
  m.raw = true;
  m.declared_size = declared;
  m.crc = static_cast<uint32_t>(crc32(0, inflated.data(), static_cast<uInt>(inflated.size())));
  return m;
}

CraftedMember zero_bomb(const std::string& name, const std::vector<uint8_t>& prefix, uint64_t zeros,
                        uint64_t declared) {
  CraftedMember m{name, {}};
  m.raw = true;
  m.data = deflate_bomb(prefix, zeros, m.crc);
  m.declared_size = declared;
  return m;
}

// A .npy member with this header dict and `data_bytes` zero bytes of data.
CraftedMember npy_member(const std::string& name, const std::string& dict, size_t data_bytes,
                         unsigned header_len = 0) {
  std::string header = dict;
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  if (header_len == 0) header_len = static_cast<unsigned>(header.size());
  std::string file("\x93NUMPY\x01\x00", 8);
  file += static_cast<char>(header_len & 0xff);
  file += static_cast<char>(header_len >> 8);
  file += header;
  file.append(data_bytes, '\0');
  return CraftedMember{name, bytes_of(file)};
}

CommandResult rlrun_measured(const std::string& args) {
  return run_command_measured("timeout 120 " + std::string(RLRUN_BINARY) + " " + args);
}

void check_refused(const CommandResult& r, const std::vector<std::string>& fragments) {
  INFO(r.output);
  CHECK(r.exit_code == 1);
  for (const std::string& f : fragments) CHECK(r.output.find(f) != std::string::npos);
  CHECK(r.output.find("stoll") == std::string::npos);
  CHECK(r.output.find("bad_alloc") == std::string::npos);
  CHECK(r.peak_rss_kb > 0);
  CHECK(r.peak_rss_kb < kMaxPeakRssKb);
}

const std::string kWeight = "action_net.weight.npy";  // (2, 8) float32 in the tiny PPO

}  // namespace

TEST_CASE("untrusted model: eval refuses huge declared members before allocating",
          "[cli][untrusted]") {
  TinyRun tiny("untrusted_sizes");
  const std::string& src = tiny.model();
  // The issue's case: a 6 KB file whose tensor declares 4 GiB.
  const std::string liar =
      variant(src, tiny.dir / "liar.zip", declaring(kWeight, kFourGiB, {1, 2, 3}));
  CHECK(fs::file_size(liar) < 8000);
  check_refused(rlrun_measured("eval --model " + liar + " --episodes 1"),
                {liar + ": its tensors declare ", "bytes a model of its configuration holds"});
  // A real bomb: 4 GiB of zeros (a 4 MB file), honestly declared.
  const std::string bomb =
      variant(src, tiny.dir / "bomb.zip", zero_bomb(kWeight, {}, kFourGiB, kFourGiB));
  check_refused(rlrun_measured("eval --model " + bomb + " --episodes 1"),
                {bomb + ": its tensors declare "});
  // record reads model files the same way.
  check_refused(rlrun_measured("record --model " + bomb + " --frames " + tiny.dir / "frames"),
                {bomb + ": its tensors declare "});
  // The bomb declaring the tensor's true size: inflating stops one byte past it.
  const std::vector<uint8_t> real = read_zip(src).at(kWeight);
  const std::string lying_bomb = variant(src, tiny.dir / "lying_bomb.zip",
                                         zero_bomb(kWeight, real, uint64_t{1} << 30, real.size()));
  check_refused(rlrun_measured("eval --model " + lying_bomb + " --episodes 1"),
                {lying_bomb + ": member '" + kWeight + "' holds more data than its declared " +
                 std::to_string(real.size()) + " bytes"});
  // meta.json and config.yaml are capped at 1 MiB.
  const std::string big_meta =
      variant(src, tiny.dir / "big_meta.zip", declaring("meta.json", 2 << 20, {'{', '}'}));
  check_refused(rlrun_measured("eval --model " + big_meta),
                {"member 'meta.json' declares 2097152 bytes, more than the 1048576 allowed"});
}

TEST_CASE("untrusted model: members rlrun does not use are skipped unread", "[cli][untrusted]") {
  TinyRun tiny("untrusted_unknown");
  const std::string path = variant(tiny.model(), tiny.dir / "extra.zip",
                                   zero_bomb("notes/bomb.bin", {}, kFourGiB, kFourGiB));
  const CommandResult r = rlrun_measured("eval --model " + path + " --episodes 1");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("mean_reward = ") != std::string::npos);
  CHECK(r.peak_rss_kb < kMaxPeakRssKb);
  // A checkpoint's training state is not read by eval either.
  CHECK(rlrun_measured("eval --model " + tiny.checkpoint() + " --episodes 1").exit_code == 0);
}

TEST_CASE("untrusted model: corrupt data, bad names and bad npy headers name the member",
          "[cli][untrusted]") {
  TinyRun tiny("untrusted_corrupt");
  const std::string& src = tiny.model();
  const auto eval_refuses = [&](const std::string& file, CraftedMember m,
                                const std::vector<std::string>& fragments) {
    const std::string path = variant(src, tiny.dir / file, std::move(m));
    std::vector<std::string> expected{path + ": member '"};
    expected.insert(expected.end(), fragments.begin(), fragments.end());
    check_refused(rlrun_measured("eval --model " + path + " --episodes 1"), expected);
  };
  CraftedMember corrupt{kWeight, std::vector<uint8_t>(40, 0xff)};  // invalid block type
  corrupt.raw = true;
  corrupt.declared_size = 192;
  eval_refuses("corrupt.zip", corrupt, {"member '" + kWeight + "' is corrupt ("});
  eval_refuses("dotdot.zip", CraftedMember{"../evil.npy", {1}},
               {"'../evil.npy' has a '..' component"});
  eval_refuses("absolute.zip", CraftedMember{"/tmp/evil.npy", {1}}, {"has an absolute path"});
  const std::string f4 = "{'descr': '<f4', 'fortran_order': False, 'shape': ";
  eval_refuses("shape_text.zip", npy_member(kWeight, f4 + "('a', 8), }", 64),
               {kWeight + "': not a supported .npy array (a dimension of the shape is not a "
                          "non-negative integer)"});
  eval_refuses("shape_overflow.zip", npy_member(kWeight, f4 + "(9223372036854775807, 2), }", 64),
               {"the shape's size overflows"});
  eval_refuses("shape_huge.zip", npy_member(kWeight, f4 + "(99999999999999999999999, 2), }", 64),
               {"a dimension of the shape is too large"});
  eval_refuses("header_len.zip", npy_member(kWeight, f4 + "(2, 8), }", 64, 65535),
               {"its header is longer than the member"});
  eval_refuses("truncated.zip", npy_member(kWeight, f4 + "(2, 8), }", 48),
               {"its shape needs 64 bytes of data, the zip declares 48"});
  eval_refuses(
      "dtype.zip",
      npy_member(kWeight, "{'descr': '<i4', 'fortran_order': False, 'shape': (2, 8), }", 64),
      {"unsupported dtype '<i4'"});
  // A well-formed tensor of another shape is the algorithm's refusal (it names the tensor).
  const std::string other =
      variant(src, tiny.dir / "other_shape.zip", npy_member(kWeight, f4 + "(3, 8), }", 96));
  check_refused(rlrun_measured("eval --model " + other), {other + ": ", "action_net.weight"});
}

TEST_CASE("untrusted model: train --init-from refuses hostile files", "[cli][untrusted]") {
  TinyRun tiny("untrusted_init_from");
  const std::string& src = tiny.model();
  const std::string train = "train " + tiny.dir / "tiny.yaml" +
                            " --set run.out_dir=" + tiny.dir / "again" + " --init-from ";
  const std::string liar = variant(src, tiny.dir / "liar.zip", declaring(kWeight, kFourGiB, {1}));
  check_refused(rlrun_measured(train + liar), {liar + ": its tensors declare "});
  const std::string bomb =
      variant(src, tiny.dir / "bomb.zip", zero_bomb(kWeight, {}, kFourGiB, kFourGiB));
  check_refused(rlrun_measured(train + bomb), {bomb + ": its tensors declare "});
  CraftedMember corrupt{kWeight, std::vector<uint8_t>(40, 0xff)};
  corrupt.raw = true;
  corrupt.declared_size = 192;
  const std::string broken = variant(src, tiny.dir / "corrupt.zip", corrupt);
  check_refused(rlrun_measured(train + broken),
                {broken + ": member '" + kWeight + "' is corrupt ("});
  const std::string shape = variant(
      src, tiny.dir / "shape.zip",
      npy_member(kWeight, "{'descr': '<f4', 'fortran_order': False, 'shape': (2, x), }", 64));
  check_refused(rlrun_measured(train + shape),
                {shape + ": member '" + kWeight + "': not a supported"});
  // No run directory is left behind by a refused start.
  CHECK(!fs::exists(tiny.dir / "again/tiny/seed1"));
  // The unmodified model still initialises a run.
  CHECK(run_rlrun(train + src).exit_code == 0);
}

TEST_CASE("untrusted model: train --resume refuses hostile checkpoints", "[cli][untrusted]") {
  TinyRun tiny("untrusted_resume");
  const std::string checkpoint = tiny.checkpoint();
  const std::string original = tiny.dir / "step_128.zip";
  fs::copy_file(checkpoint, original);
  // The checkpoint named itself: resuming the run directory would skip a damaged newest
  // checkpoint for the one before it (runtime/run/resume_point.hpp; tested in test_cli_resume.cpp).
  const std::string resume = "train --resume " + checkpoint + " --timesteps 256";
  const std::string state = "training/algo/optimizer/exp_avg.0.npy";
  REQUIRE(read_zip(original).count(state) == 1);
  const auto refused = [&](CraftedMember m, const std::vector<std::string>& fragments) {
    variant(original, checkpoint, std::move(m));
    check_refused(rlrun_measured(resume), fragments);
  };
  refused(declaring(state, kFourGiB, {1}), {checkpoint + ": its tensors declare "});
  refused(zero_bomb(state, {}, kFourGiB, kFourGiB), {checkpoint + ": its tensors declare "});
  const std::vector<uint8_t> real = read_zip(original).at(state);
  refused(zero_bomb(state, real, uint64_t{1} << 30, real.size()),
          {checkpoint + ": member '" + state + "' holds more data than its declared"});
  CraftedMember corrupt{state, std::vector<uint8_t>(40, 0xff)};
  corrupt.raw = true;
  corrupt.declared_size = real.size();
  refused(corrupt, {checkpoint + ": member '" + state + "' is corrupt ("});
  refused(npy_member(state, "{'descr': '<f4', 'fortran_order': False, 'shape': (1e9,), }", 0),
          {"not a supported .npy array (malformed shape)"});
  refused(CraftedMember{"training/../../x.npy", {1}}, {"has a '..' component"});
  // A log mark naming a file outside the run directory (resume would delete it: 0 lines).
  const std::string victim = tiny.dir / "victim.txt";
  std::ofstream(victim) << "keep me\n";
  const std::string escape = "../../../victim.txt";
  std::vector<CraftedMember> marks = members_of(original);
  for (CraftedMember& m : marks) {
    if (m.name == "training/files/0/name.npy")
      m.data = encode_npy(vector_tensor(std::vector<int64_t>(escape.begin(), escape.end())));
    if (m.name == "training/files/0/lines.npy")
      m.data = encode_npy(vector_tensor(std::vector<int64_t>{0}));
  }
  write_crafted_zip(checkpoint, marks);
  check_refused(rlrun_measured(resume),
                {"names a log file '" + escape + "' that this run does not write"});
  CHECK(fs::exists(victim));
  // The real checkpoint still resumes.
  fs::copy_file(original, checkpoint, fs::copy_options::overwrite_existing);
  const auto r = run_rlrun(resume);
  INFO(r.output);
  CHECK(r.exit_code == 0);
}
