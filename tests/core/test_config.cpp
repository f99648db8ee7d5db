#include <catch2/catch.hpp>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"

using namespace rlrun;

namespace {
struct Inner {
  std::vector<int> net_arch = {64, 64};
  std::string activation_fn = "tanh";
  template <class V>
  void visit(V& v) {
    v("net_arch", net_arch, "");
    v("activation_fn", activation_fn, "");
  }
};
struct Outer {
  int n_steps = 2048;
  int64_t total = 0;
  double gamma = 0.99;
  bool flag = false;
  Schedule lr = Schedule::constant(3e-4);
  std::optional<double> target_kl;
  Inner policy;
  template <class V>
  void visit(V& v) {
    v("n_steps", n_steps, "");
    v("total", total, "");
    v("gamma", gamma, "");
    v("flag", flag, "");
    v("learning_rate", lr, "");
    v("target_kl", target_kl, "");
    v("policy", policy, "");
  }
};

std::string error_of(const std::string& yaml) {
  try {
    read_config<Outer>(ConfigNode::load_string(yaml, "exp.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("config: values are read, defaults kept", "[core][config]") {
  const Outer o = read_config<Outer>(ConfigNode::load_string(
      "n_steps: 32\ntotal: 1e5\ngamma: 0.98\nflag: yes\nlearning_rate: lin_0.001\n"
      "target_kl: 0.01\npolicy: {net_arch: [256, 256]}\n",
      "exp.yaml"));
  CHECK(o.n_steps == 32);
  CHECK(o.total == 100000);
  CHECK(o.gamma == 0.98);
  CHECK(o.flag);
  CHECK(o.lr.is_linear());
  CHECK(o.lr(0.5) == Approx(0.0005));
  REQUIRE(o.target_kl);
  CHECK(*o.target_kl == 0.01);
  CHECK(o.policy.net_arch == std::vector<int>{256, 256});
  CHECK(o.policy.activation_fn == "tanh");
}

TEST_CASE("config: YAML 1.1 digit separators are accepted", "[core][config]") {
  CHECK(read_config<Outer>(ConfigNode::load_string("total: 100_000", "x")).total == 100000);
}

TEST_CASE("config: unknown key names file, line, column, path and the closest key",
          "[core][config]") {
  const std::string e = error_of("n_steps: 32\npolicy:\n  net_arh: [64]\n");
  CHECK(e.find("exp.yaml:3:3") != std::string::npos);
  CHECK(e.find("policy.net_arh") != std::string::npos);
  CHECK(e.find("did you mean 'net_arch'") != std::string::npos);
}

TEST_CASE("config: wrong types are errors with the position of the value", "[core][config]") {
  CHECK(error_of("n_steps: abc").find("exp.yaml:1:10: n_steps: expected an integer, got 'abc'") !=
        std::string::npos);
  CHECK(error_of("n_steps: 1.5").find("expected an integer") != std::string::npos);
  CHECK(error_of("flag: maybe").find("expected true or false") != std::string::npos);
  CHECK(error_of("learning_rate: lin_x").find("learning_rate") != std::string::npos);
  CHECK(error_of("policy: {net_arch: 64}").find("expected a list") != std::string::npos);
  CHECK(error_of("policy: 3").find("expected a map") != std::string::npos);
}

TEST_CASE("config: invalid YAML reports the parser position", "[core][config]") {
  try {
    ConfigNode::load_string("a: {b: 1\nc: 2\n", "bad.yaml");
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind("bad.yaml:", 0) == 0);
  }
}

TEST_CASE("config: --set overrides create paths and are named in errors", "[core][config]") {
  ConfigNode root = ConfigNode::load_string("n_steps: 32\n", "exp.yaml");
  root.apply_override("policy.net_arch=[8, 8]");
  root.apply_override("gamma=0.9");
  const Outer o = read_config<Outer>(root);
  CHECK(o.policy.net_arch == std::vector<int>{8, 8});
  CHECK(o.gamma == 0.9);
  root.apply_override("gamm=0.9");
  try {
    read_config<Outer>(root);
    FAIL("no error");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("--set gamm=0.9") != std::string::npos);
    CHECK(msg.find("did you mean 'gamma'") != std::string::npos);
  }
  CHECK_THROWS_AS(root.apply_override("novalue"), UsageError);
}

TEST_CASE("config: resolved config round-trips", "[core][config]") {
  Outer o;
  o.n_steps = 7;
  o.lr = Schedule::linear(0.001);
  const YAML::Node written = write_config(o);
  CHECK(written["gamma"].Scalar() == "0.99");
  CHECK(written["learning_rate"].Scalar() == "lin_0.001");
  CHECK(written["target_kl"].IsNull());
  YAML::Emitter out;
  out << written;
  const Outer back = read_config<Outer>(ConfigNode::load_string(out.c_str(), "resolved"));
  CHECK(back.n_steps == 7);
  CHECK(back.gamma == 0.99);
  CHECK(back.lr.str() == "lin_0.001");
  CHECK(!back.target_kl);
}

TEST_CASE("did you mean: close names only", "[core][config]") {
  const std::vector<std::string> keys{"n_steps", "batch_size", "clip_range", "clip_range_vf"};
  CHECK(closest_name("n_stps", keys) == "n_steps");
  CHECK(closest_name("batchsize", keys) == "batch_size");
  CHECK(closest_name("cliprange", keys) == "clip_range");
  CHECK(closest_name("completely_unrelated", keys).empty());
}

TEST_CASE("schedule: SB3 / rl-zoo forms", "[core][config]") {
  CHECK(Schedule::parse("3e-4")(0.3) == Approx(3e-4));
  CHECK(Schedule::parse("lin_0.2")(1.0) == Approx(0.2));
  CHECK(Schedule::parse("lin_0.2")(0.25) == Approx(0.05));
  CHECK(Schedule::parse("lin_0.001").str() == "lin_0.001");
  CHECK(Schedule::parse("0.0003").str() == "0.0003");
  CHECK_THROWS(Schedule::parse("linear"));
  CHECK_THROWS(Schedule::parse("lin_"));
}
