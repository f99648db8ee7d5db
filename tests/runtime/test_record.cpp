// End-to-end tests of `rlrun record`, `rlrun eval --record` and the training video callback,
// run as a user would, with every video checked by ffprobe.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "rlrun/core/npy.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

struct Probe {
  std::string codec;
  int width = 0, height = 0;
  int64_t frames = -1;
  std::string rate;
};

// ffprobe's view of the first video stream, frames counted by decoding.
Probe probe(const std::string& path) {
  const auto r = run_command(
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,width,height,nb_read_frames,r_frame_rate -of "
      "default=noprint_wrappers=1 '" +
      path + "'");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  Probe p;
  std::istringstream lines(r.output);
  std::string line;
  while (std::getline(lines, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "codec_name") p.codec = value;
    if (key == "width") p.width = std::stoi(value);
    if (key == "height") p.height = std::stoi(value);
    if (key == "nb_read_frames") p.frames = std::stoll(value);
    if (key == "r_frame_rate") p.rate = value;
  }
  return p;
}

// Episode lengths from `rlrun eval --csv`.
std::vector<int64_t> eval_lengths(const std::string& model, int episodes, int seed,
                                  const std::string& csv) {
  const auto r = run_rlrun("eval --model " + model + " --episodes " + std::to_string(episodes) +
                           " --seed " + std::to_string(seed) + " --csv " + csv);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  REQUIRE(line.rfind("policy,episode,return,length", 0) == 0);  // eval --csv's fixed columns
  std::vector<int64_t> lengths;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    lengths.push_back(std::stoll(cells.at(3)));
  }
  return lengths;
}

int64_t printed_frames(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("([0-9]+) frames at")));
  return std::stoll(m[1]);
}

double printed_mean_reward(const std::string& output) {
  std::smatch m;
  REQUIRE(std::regex_search(output, m, std::regex("mean_reward = (-?[0-9.]+)")));
  return std::stod(m[1]);
}

int count_files(const std::string& dir, const std::string& extension) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == extension;
  return n;
}

// Trains briefly and returns the model path. The shipped PPO configs where there is one;
// a small PPO run elsewhere (the shipped DQN/SAC configs take longer than a test should).
std::string train_briefly(const TempDir& dir, const std::string& env_id) {
  std::string config;
  std::string sets = " --set run.out_dir=" + dir.str() + " --threads 1";
  if (env_id == "CartPole-v1") {
    config = kSource + "/configs/cartpole_ppo.yaml";
    sets += " --set run.total_timesteps=3000";
  } else if (env_id == "Pendulum-v1") {
    config = kSource + "/configs/pendulum_ppo.yaml";
    sets += " --set run.total_timesteps=2000";
  } else {
    config = dir / "ppo.yaml";
    write_file(config,
               "run: {name: brief, seed: 1, total_timesteps: 1024}\n"
               "env: {id: " +
                   env_id +
                   ", n_envs: 4}\n"
                   "algo: {id: PPO, n_steps: 128, batch_size: 128, n_epochs: 2}\n");
  }
  const auto r = run_rlrun("train " + config + sets);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(r.output, m, std::regex("model saved to (\\S+model\\.zip)")));
  return m[1];
}

// `record --env CartPole-v1 --policy random --output <dir>/out/v.mp4` with RLRUN_FFMPEG set to
// a stand-in script (<dir>/fake_ffmpeg).
CommandResult record_with_fake_ffmpeg(const TempDir& dir, const std::string& script) {
  const std::string fake = dir / "fake_ffmpeg";
  write_file(fake, script);
  fs::permissions(fake, fs::perms::owner_all);
  fs::create_directories(dir / "out");
  return run_command("env RLRUN_FFMPEG=" + fake + " " + std::string(RLRUN_BINARY) +
                     " record --env CartPole-v1 --policy random --output " + (dir / "out/v.mp4"));
}

}  // namespace

TEST_CASE("record: an H.264 mp4 of a trained model for each classic env", "[record][cli]") {
  struct Case {
    std::string env;
    int width, height;
    std::string rate;
  };
  const Case cases[] = {{"CartPole-v1", 600, 400, "50/1"},
                        {"Pendulum-v1", 500, 500, "30/1"},
                        {"MountainCar-v0", 600, 400, "30/1"},
                        {"MountainCarContinuous-v0", 600, 400, "30/1"},
                        {"Acrobot-v1", 500, 500, "15/1"}};
  for (const Case& c : cases) {
    SECTION(c.env) {
      TempDir dir("record_" + c.env);
      const std::string model = train_briefly(dir, c.env);
      // The same seeded episode, measured by eval: one frame after reset + one per step.
      const std::vector<int64_t> lengths = eval_lengths(model, 1, 7, dir / "eval.csv");
      REQUIRE(lengths.size() == 1);
      const std::string video = dir / "video.mp4";
      const auto r =
          run_rlrun("record --model " + model + " --output " + video + " --episodes 1 --seed 7");
      INFO(r.output);
      REQUIRE(r.exit_code == 0);
      CHECK(printed_frames(r.output) == lengths[0] + 1);
      const Probe p = probe(video);
      CHECK(p.codec == "h264");
      CHECK(p.width == c.width);
      CHECK(p.height == c.height);
      CHECK(p.rate == c.rate);
      CHECK(p.frames == lengths[0] + 1);
    }
  }
}

TEST_CASE("record: size, fps, PNG frames, stochastic policy, several episodes", "[record][cli]") {
  TempDir dir("record_options");
  const std::string model = train_briefly(dir, "CartPole-v1");
  const std::string video = dir / "small.mp4", frames = dir / "frames";
  const auto r = run_rlrun("record --model " + model + " --output " + video + " --frames " +
                           frames + " --episodes 3 --seed 2 --size 320x240 --fps 20 --stochastic");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const int64_t n = printed_frames(r.output);
  const Probe p = probe(video);
  CHECK(p.width == 320);
  CHECK(p.height == 240);
  CHECK(p.rate == "20/1");
  CHECK(p.frames == n);
  CHECK(count_files(frames, ".png") == n);
  CHECK(fs::exists(frames + "/frame_000000.png"));

  // PNGs alone need no ffmpeg.
  const auto png_only =
      run_command("env PATH=/nonexistent " + std::string(RLRUN_BINARY) + " record --model " +
                  model + " --frames " + (dir / "png_only") + " --episodes 1 --size 120x80");
  INFO(png_only.output);
  CHECK(png_only.exit_code == 0);
  CHECK(count_files(dir / "png_only", ".png") == printed_frames(png_only.output));
}

TEST_CASE("eval --record: the same episodes and numbers as eval, on video", "[record][cli]") {
  TempDir dir("eval_record");
  const std::string model = train_briefly(dir, "CartPole-v1");
  const auto plain = run_rlrun("eval --model " + model + " --episodes 3 --seed 4");
  const std::string video = dir / "eval.mp4";
  const auto recorded =
      run_rlrun("eval --model " + model + " --episodes 3 --seed 4 --record " + video);
  INFO(recorded.output);
  REQUIRE(plain.exit_code == 0);
  REQUIRE(recorded.exit_code == 0);
  CHECK(printed_mean_reward(recorded.output) == printed_mean_reward(plain.output));
  const std::vector<int64_t> lengths = eval_lengths(model, 3, 4, dir / "eval.csv");
  int64_t expected = 0;
  for (int64_t l : lengths) expected += l + 1;
  CHECK(probe(video).frames == expected);
}

TEST_CASE("record: random policy from a config or an env id", "[record][cli]") {
  TempDir dir("record_random");
  const auto a = run_rlrun("record --config " + kSource +
                           "/configs/mountaincar_dqn.yaml --policy random --output " +
                           (dir / "mc.mp4") + " --seed 3");
  INFO(a.output);
  REQUIRE(a.exit_code == 0);
  CHECK(probe(dir / "mc.mp4").frames == 201);  // MountainCar's time limit: 200 steps + reset
  const auto b = run_rlrun("record --env Acrobot-v1 --policy random --output " + (dir / "ac.mp4") +
                           " --no-overlay");
  INFO(b.output);
  REQUIRE(b.exit_code == 0);
  CHECK(probe(dir / "ac.mp4").codec == "h264");
}

TEST_CASE("record --from-obs: one frame per logged observation, chunks in order", "[record][cli]") {
  TempDir dir("record_from_obs");
  // An observation log like the obs_log callback writes: (steps, obs_dim) float32 chunks.
  rlrun::CartPole env;
  std::vector<float> obs(4);
  env.reset(9, obs);
  auto chunk = [&](int rows) {
    rlrun::Tensor t;
    t.shape = {rows, 4};
    t.bytes.resize(static_cast<size_t>(rows) * 4 * sizeof(float));
    float* out = t.data<float>();
    for (int i = 0; i < rows; ++i) {
      const float action[] = {static_cast<float>(i % 2)};
      if (env.step(action, obs).terminated) env.reset(std::nullopt, obs);
      std::copy(obs.begin(), obs.end(), out + 4 * i);
    }
    const auto bytes = rlrun::encode_npy(t);
    return std::string(bytes.begin(), bytes.end());
  };
  fs::create_directories(dir / "log");
  write_file(dir / "log/obs_2.npy", chunk(30));
  write_file(dir / "log/obs_10.npy", chunk(25));

  const auto r = run_rlrun("record --from-obs " + (dir / "log") + " --env CartPole-v1 --output " +
                           (dir / "log.mp4") + " --frames " + (dir / "log_frames"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(probe(dir / "log.mp4").frames == 55);
  CHECK(count_files(dir / "log_frames", ".png") == 55);
  const auto single = run_rlrun("record --from-obs " + (dir / "log/obs_10.npy") +
                                " --env CartPole-v1 --output " + (dir / "one.mp4"));
  REQUIRE(single.exit_code == 0);
  CHECK(probe(dir / "one.mp4").frames == 25);

  // A log of another env: a clear usage error.
  const auto wrong = run_rlrun("record --from-obs " + (dir / "log") +
                               " --env Acrobot-v1 --output " + (dir / "wrong.mp4"));
  CHECK(wrong.exit_code == 2);
  CHECK_THAT(wrong.output, Catch::Contains("another env"));
  CHECK_FALSE(fs::exists(dir / "wrong.mp4"));
}

TEST_CASE("record without ffmpeg: exit 1, names the package, writes nothing", "[record][cli]") {
  TempDir dir("record_no_ffmpeg");
  const std::string video = dir / "video.mp4";
  const auto r = run_command("env PATH=/nonexistent RLRUN_FFMPEG= " + std::string(RLRUN_BINARY) +
                             " record --env CartPole-v1 --policy random --output " + video);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("ffmpeg"));
  CHECK_THAT(r.output, Catch::Contains("apt-get install ffmpeg"));
  CHECK(fs::is_empty(dir.str()));
}

TEST_CASE("record with a failing ffmpeg: exit 1 with its error output, no partial file",
          "[record][cli]") {
  TempDir dir("record_bad_ffmpeg");
  const auto r = record_with_fake_ffmpeg(
      dir, "#!/bin/sh\ncat > /dev/null\necho 'x264 [error]: malloc failed' >&2\nexit 1\n");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("malloc failed"));
  CHECK(fs::is_empty(dir / "out"));
}

// Issue 15, item 13: the output is a plain path whatever it looks like to ffmpeg (which reads
// "proto:..." as a protocol), and no temporary .part file outlives a failure.
TEST_CASE("record --output file:x.mp4 / pipe:1: files of those names, nothing else",
          "[record][cli]") {
  TempDir dir("record_protocol_names");
  const std::string cd = "cd '" + dir.str() + "' && " + RLRUN_BINARY;
  for (const std::string name : {"file:x.mp4", "pipe:1", "file:sub/y.mp4"}) {
    const auto r = run_command(cd + " record --env CartPole-v1 --policy random --output " + name);
    INFO(name << "\n" << r.output);
    CHECK(r.exit_code == 0);
    CHECK(r.output.size() < 2000);  // no video on stdout
    CHECK(probe(dir / name).codec == "h264");
  }
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir.str()))
    names.push_back(fs::relative(e.path(), dir.str()).string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"file:sub", "file:sub/y.mp4", "file:x.mp4", "pipe:1"});
}

TEST_CASE("record: ffmpeg failing after writing part of the video leaves no file",
          "[record][cli]") {
  TempDir dir("record_partial");
  // A stand-in ffmpeg that writes half a video to its output, then fails.
  const auto r = record_with_fake_ffmpeg(
      dir,
      "#!/bin/sh\nfor last; do :; done\nprintf '%s\\n' \"$last\" > \"$(dirname "
      "\"$0\")/output_arg\"\n"
      "cat > /dev/null\necho partial > \"${last#file:}\"\necho 'encoder died' >&2\nexit 1\n");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.output, Catch::Contains("encoder died"));
  CHECK(fs::is_empty(dir / "out"));
  // ffmpeg was given the temporary file as an absolute file: URL, beside the output.
  const std::string arg = read_text(dir / "output_arg");
  CHECK(arg.rfind("file:" + dir / "out/.v.mp4.", 0) == 0);
  CHECK(arg.find(".part\n") != std::string::npos);

  // The rename into place fails (a directory holds the name): no .part left either.
  fs::create_directories(dir / "out/taken.mp4");
  const auto taken =
      run_rlrun("record --env CartPole-v1 --policy random --output " + (dir / "out/taken.mp4"));
  INFO(taken.output);
  CHECK(taken.exit_code == 1);
  CHECK_THAT(taken.output, Catch::Contains("cannot rename"));
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "out")) entries += e.exists();
  CHECK(entries == 1);
}

TEST_CASE("record: bad command lines exit 2", "[record][cli]") {
  TempDir dir("record_usage");
  const std::string out = " --output " + (dir / "v.mp4");
  CHECK(run_rlrun("record" + out).exit_code == 2);                              // no source
  CHECK(run_rlrun("record --env CartPole-v1" + out).exit_code == 2);            // no policy
  CHECK(run_rlrun("record --env CartPole-v1 --policy random").exit_code == 2);  // no output
  CHECK(run_rlrun("record --env CartPole-v1 --policy greedy" + out).exit_code == 2);
  CHECK(run_rlrun("record --env CartPole-v1 --policy random --size 601x400" + out).exit_code == 2);
  CHECK(run_rlrun("record --env CartPole-v1 --policy random --size big" + out).exit_code == 2);
  CHECK(run_rlrun("record --env CartPol-v1 --policy random" + out).exit_code == 2);
  CHECK(run_rlrun("record --from-obs " + (dir / "none") + " --env CartPole-v1" + out).exit_code ==
        2);
  CHECK(fs::is_empty(dir.str()));
}

TEST_CASE("train with video.freq writes videos/step_<N>.mp4", "[record][cli]") {
  TempDir dir("train_video");
  const auto r = run_rlrun("train " + kSource +
                           "/configs/cartpole_ppo.yaml --threads 1 --set run.out_dir=" + dir.str() +
                           " --set run.total_timesteps=4000 --set video.freq=2000 "
                           "--set video.width=300 --set video.height=200");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // 8 envs: num_timesteps moves in steps of 8 and crosses 2000 and 4000 exactly.
  const std::string videos = dir / "cartpole_ppo/seed1/videos";
  REQUIRE(fs::exists(videos + "/step_2000.mp4"));
  REQUIRE(fs::exists(videos + "/step_4000.mp4"));
  CHECK(count_files(videos, ".mp4") == 2);
  CHECK_THAT(r.output, Catch::Contains("video at 2000 steps"));
  const Probe p = probe(videos + "/step_4000.mp4");
  CHECK(p.codec == "h264");
  CHECK(p.width == 300);
  CHECK(p.frames > 1);

  // Without ffmpeg the run fails before training, naming the package.
  const auto missing = run_command(
      "env PATH=/nonexistent " + std::string(RLRUN_BINARY) + " train " + kSource +
      "/configs/cartpole_ppo.yaml --set run.out_dir=" + (dir / "b") + " --set video.freq=2000");
  CHECK(missing.exit_code == 1);
  CHECK_THAT(missing.output, Catch::Contains("apt-get install ffmpeg"));
  // Odd sizes are a config error.
  CHECK(run_rlrun("train " + kSource +
                  "/configs/cartpole_ppo.yaml --set run.out_dir=" + (dir / "c") +
                  " --set video.freq=2000 --set video.width=301 --set video.height=200")
            .exit_code == 2);
}
