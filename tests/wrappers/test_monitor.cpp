#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "rlrun/core/float_format.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/wrappers/monitor.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;

TEST_CASE("python_float_repr matches Python's repr", "[wrappers][monitor]") {
  CHECK(python_float_repr(21.0) == "21.0");
  CHECK(python_float_repr(0.98) == "0.98");
  CHECK(python_float_repr(-0.123456) == "-0.123456");
  CHECK(python_float_repr(1e-05) == "1e-05");
  CHECK(python_float_repr(500.0) == "500.0");
  CHECK(python_float_repr(0.1 + 0.2) == "0.30000000000000004");
  CHECK(python_float_repr(10.0) == "10.0");
  CHECK(python_float_repr(123456.789) == "123456.789");
  CHECK(python_float_repr(1e16) == "1e+16");
  CHECK(python_float_repr(1.5e-7) == "1.5e-07");
  CHECK(python_float_repr(0.0001) == "0.0001");
  CHECK(python_float_repr(1732243200.123456) == "1732243200.123456");
}

TEST_CASE("python_float_repr: the fewest digits that read back, for any double",
          "[wrappers][monitor]") {
  // The reference is the definition: the first number of significant digits at which the
  // correctly rounded "%.*e" text reads back to the same double (what rlrun did before it used
  // std::to_chars). Random bit patterns cover every exponent; rounded numbers of every scale
  // the values monitor.csv really holds (returns, lengths, times).
  const auto reference_digits = [](double v) {
    char text[64];
    for (int precision = 0; precision < 17; ++precision) {
      std::snprintf(text, sizeof text, "%.*e", precision, v);
      if (std::strtod(text, nullptr) == v) break;
    }
    return std::string(text, std::strchr(text, 'e'));
  };
  // The significant digits of a decimal text: no sign, point, exponent, leading or trailing 0.
  const auto significant = [](const std::string& text) {
    std::string digits;
    for (char c : text.substr(0, text.find('e')))
      if (c >= '0' && c <= '9' && !(digits.empty() && c == '0')) digits += c;
    while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
    return digits;
  };
  std::mt19937_64 bits(24);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    double v;
    if (i % 2 == 0) {
      const uint64_t b = bits();
      std::memcpy(&v, &b, sizeof v);
    } else {
      v = static_cast<double>(static_cast<int64_t>(bits() % 2000001) - 1000000) *
          std::pow(10.0, static_cast<int>(bits() % 25) - 12);
    }
    if (!std::isfinite(v) || v == 0.0) continue;
    const std::string repr = python_float_repr(v);
    INFO(repr);
    REQUIRE(std::strtod(repr.c_str(), nullptr) == v);
    REQUIRE(significant(repr) == significant(reference_digits(v)));
    ++checked;
  }
  CHECK(checked > 190000);
}

TEST_CASE("Monitor writes SB3's monitor.csv format and reports episodes", "[wrappers][monitor]") {
  const auto dir = std::filesystem::temp_directory_path() / "rlrun_test_monitor";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "0.monitor.csv").string();
  {
    Monitor env(std::make_unique<TimeLimit>(std::make_unique<CartPole>(CartPole::Config{}), 500),
                path, 1732243200.5);
    std::vector<float> obs(4);
    const float push_right = 1.0f;
    int episodes = 0;
    env.reset(7, obs);
    double total = 0;
    int length = 0;
    while (episodes < 2) {
      const StepResult r = env.step({&push_right, 1}, obs);
      total += r.reward;
      ++length;
      if (r.terminated || r.truncated) {
        const Info& info = env.info();
        CHECK(info.get(info.find("episode.r")) == total);
        CHECK(info.get(info.find("episode.l")) == length);
        ++episodes;
        total = 0;
        length = 0;
        env.reset(std::nullopt, obs);
      } else {
        CHECK(!env.info().has(env.info().find("episode.r")));
      }
    }
    CHECK(env.total_episodes() == 2);
    // Stepping a finished episode without reset is refused (SB3's Monitor raises too).
  }
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  CHECK(line == "#{\"t_start\": 1732243200.500000, \"env_id\": \"CartPole-v1\"}");
  std::getline(in, line);
  CHECK(line == "r,l,t");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    std::stringstream ss(line);
    std::string r, l, t;
    std::getline(ss, r, ',');
    std::getline(ss, l, ',');
    std::getline(ss, t, ',');
    CHECK(r == std::to_string(std::stoi(l)) + ".0");  // CartPole: reward 1 per step
    CHECK(std::stod(t) >= 0.0);
  }
  CHECK(rows == 2);
  std::filesystem::remove_all(dir);
}
