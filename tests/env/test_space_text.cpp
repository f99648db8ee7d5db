// Text forms of spaces and values (env/space_text.hpp), and check_env's reports on Dict
// observations built from them.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "rlrun/env/env_checker.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/env_base.hpp"

using namespace rlrun;

namespace {

const Space kDict = Space::dict({{"row", Space::discrete(4)},
                                 {"pos", Space::box(-1.0f, 1.0f, {2})},
                                 {"bits", Space::multi_binary(2)}});

// A Dict env whose 'row' goes one past its Discrete(4) after three steps.
class RowOverflow : public EnvBase {
 public:
  RowOverflow() {
    observation_space_ = kDict;
    action_space_ = Space::discrete(2);
    id_ = "RowOverflow-v0";
  }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    seeding_.on_reset(seed);
    row_ = 0;
    write(obs);
  }
  StepResult step(std::span<const float>, std::span<float> obs) override {
    ++row_;
    write(obs);
    return {0.0, false, row_ >= 6};
  }

 private:
  void write(std::span<float> obs) const {
    const std::vector<float> values{1, 0, 0.5f, -0.5f, static_cast<float>(row_)};
    std::copy(values.begin(), values.end(), obs.begin());
  }
  int row_ = 0;
};

}  // namespace

TEST_CASE("space text: Dict values key by key, the key outside named", "[env][space]") {
  // Sorted keys: bits [0, 2), pos [2, 4), row [4, 5).
  const std::vector<float> x{1, 0, 0.5f, -0.25f, 3};
  CHECK(format_value(kDict, x) == "{'bits': [1, 0], 'pos': [0.5, -0.25], 'row': [3]}");
  CHECK(outside_reason(kDict, x).empty());
  std::vector<float> bad = x;
  bad[4] = 4;
  CHECK(outside_reason(kDict, bad) == "key 'row' is 4, not in Discrete(4)");
  bad = x;
  bad[3] = 2;
  CHECK(outside_reason(kDict, bad) ==
        "key 'pos' entry 1 is 2, not in Box(-1.0, 1.0, (2,), float32)");
  bad = x;
  bad[0] = 0.5f;
  CHECK(outside_reason(kDict, bad) == "key 'bits' entry 0 is 0.5, not in MultiBinary(2)");
  CHECK(outside_reason(Space::multi_discrete({2, 3}), std::vector<float>{1, 3}) ==
        "entry 1 is 3, not in MultiDiscrete([2 3])");
  CHECK(format_value(Space::discrete(2), std::vector<float>{1}) == "[1]");

  const std::vector<std::string> lines = describe_lines(kDict);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "Dict (5 floats, keys in sorted order)");
  CHECK(lines[3] == "'row': Discrete(4)  floats [4, 5)");
  CHECK(describe_lines(Space::discrete(3)) == std::vector<std::string>{"Discrete(3)"});
  CHECK(flat_layout(kDict) == "5 floats: 'bits' [0, 2), 'pos' [2, 4), 'row' [4, 5)");
  CHECK(flat_layout(Space::box(0.0f, 1.0f, {3})) == "3 floats");
  CHECK(labeled_space("action_space", Space::discrete(2), 17) ==
        "  action_space       Discrete(2)\n");
  const std::string block = labeled_space("obs", kDict, 5);
  CHECK(block.find("  obs    Dict (5 floats") == 0);
  CHECK(block.find("\n           'bits': MultiBinary(2)  floats [0, 2)\n") != std::string::npos);
}

TEST_CASE("check_env reports a Dict observation outside its space by key", "[env][env_checker]") {
  RowOverflow env;
  const std::vector<std::string> problems = check_env(env, 0, 10);
  REQUIRE_FALSE(problems.empty());  // one per step whose row is outside
  CHECK(problems[0].find("{'bits': [1, 0], 'pos': [0.5, -0.5], 'row': [4]}") != std::string::npos);
  CHECK(problems[0].find("(key 'row' is 4, not in Discrete(4))") != std::string::npos);
}
