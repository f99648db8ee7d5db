// Optuna 3.1's _ParzenEstimator, number for number. The expected values were printed by
// tests/tune/optuna_reference.py, which builds the same estimators with Optuna's own class
// (Debian's python3-optuna 3.1.0, /usr/bin/python3); the observations here are the script's.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/tune/parzen_estimator.hpp"

using namespace rlrun::tune;

namespace {

void check_all(const std::vector<double>& got, const std::vector<double>& expected,
               double eps = 1e-12) {
  REQUIRE(got.size() == expected.size());
  for (size_t i = 0; i < got.size(); ++i) {
    INFO("index " << i);
    CHECK(got[i] == Approx(expected[i]).epsilon(eps));
  }
}

ParzenEstimatorParameters parameters(bool multivariate) {
  ParzenEstimatorParameters p;
  p.multivariate = multivariate;
  return p;
}

SearchSpace mixed_space() {
  return {{"c", make_categorical_distribution("c", {"a", "b", "c"})},
          {"lr", make_float_distribution("lr", 1e-4, 1e-1, true, std::nullopt)},
          {"n", make_int_distribution("n", 0, 10, false, 2)},
          {"x", make_float_distribution("x", -5.0, 5.0, false, std::nullopt)}};
}

Observations mixed_observations() {
  return {{"c", {0, 2, 2, 1}},
          {"lr", {1e-3, 3e-2, 2e-4, 5e-3}},
          {"n", {2, 10, 4, 4}},
          {"x", {-4.0, 0.5, 1.0, 3.0}}};
}

}  // namespace

TEST_CASE("parzen estimator: default_weights is flat below 25 then ramps the oldest", "[tune]") {
  CHECK(default_weights(0).empty());
  CHECK(default_weights(3) == std::vector<double>{1, 1, 1});
  CHECK(default_weights(25) == std::vector<double>(25, 1.0));
  const auto w = default_weights(30);  // numpy.linspace(1/30, 1, 5), then 25 ones
  REQUIRE(w.size() == 30);
  for (int k = 0; k < 5; ++k) CHECK(w[k] == Approx(1.0 / 30 + k * (29.0 / 30) / 4).epsilon(1e-14));
  for (int k = 5; k < 30; ++k) CHECK(w[k] == 1.0);
}

TEST_CASE("parzen estimator: multivariate kernels use Scott's rule over all parameters", "[tune]") {
  const ParzenEstimator pe(mixed_observations(), mixed_space(), parameters(true));
  // Four observations + the prior, equal weights.
  check_all(pe.weights(), {0.2, 0.2, 0.2, 0.2, 0.2});
  // sigma0 = 0.2 * 4^(-1/(4+4)); sigma = sigma0 * (high - low) in kernel space.
  const auto& lr = pe.dimension("lr");
  CHECK(lr.low == Approx(-9.210340371976182).epsilon(1e-14));
  CHECK(lr.high == Approx(-2.3025850929940455).epsilon(1e-14));
  CHECK(!lr.q);
  check_all(lr.mus, {-6.907755278982137, -3.506557897319982, -8.517193191416236, -5.298317366548036,
                     -5.756462732485113});
  check_all(lr.sigmas, {1.1617413303092003, 1.1617413303092003, 1.1617413303092003,
                        1.1617413303092003, 6.907755278982137});
  const auto& n = pe.dimension("n");  // int step 2 on [0, 10]: kernel range [-1, 11]
  CHECK(n.low == -1.0);
  CHECK(n.high == 11.0);
  REQUIRE(n.q);
  CHECK(*n.q == 2.0);
  check_all(n.mus, {2.0, 10.0, 4.0, 4.0, 5.0});
  check_all(n.sigmas,
            {2.018151396608915, 2.018151396608915, 2.018151396608915, 2.018151396608915, 12.0});
  const auto& x = pe.dimension("x");
  check_all(x.mus, {-4.0, 0.5, 1.0, 3.0, 0.0});
  check_all(x.sigmas,
            {1.6817928305074292, 1.6817928305074292, 1.6817928305074292, 1.6817928305074292, 10.0});
  // prior_weight / (n + 1) = 0.2 on every choice, +1 on the observed one, rows normalised.
  const auto& c = pe.dimension("c");
  check_all(c.categorical_weights, {0.75, 0.125, 0.125, 0.125, 0.125, 0.75, 0.125, 0.125, 0.75,
                                    0.125, 0.75, 0.125, 1.0 / 3, 1.0 / 3, 1.0 / 3});
  // The joint log density (a log-mass for the stepped int) at three points.
  const Observations samples = {
      {"c", {0, 2, 1}}, {"lr", {1e-3, 0.08, 1e-4}}, {"n", {4, 0, 10}}, {"x", {0.0, -4.9, 4.5}}};
  check_all(pe.log_pdf(samples), {-4.292724588173246, -4.693945399577744, -4.690473372457843},
            1e-10);
}

TEST_CASE("parzen estimator: univariate sigmas are neighbour distances without endpoints",
          "[tune]") {
  SECTION("float") {
    const ParzenEstimator pe({{"u", {1.0, 2.0, 2.0, 7.0, 9.5}}},
                             {{"u", make_float_distribution("u", 0, 10, false, std::nullopt)}},
                             parameters(false));
    check_all(pe.weights(), std::vector<double>(6, 1.0 / 6));
    const auto& u = pe.dimension("u");
    check_all(u.mus, {1.0, 2.0, 2.0, 7.0, 9.5, 5.0});
    // The two 2.0s: one gets the gap 0 (clipped to range / 6), the other the gap to 5.0.
    check_all(u.sigmas, {1.4285714285714286, 1.4285714285714286, 3.0, 2.5, 2.5, 10.0});
    check_all(pe.log_pdf({{"u", {0.0, 2.0, 5.5, 10.0}}}),
              {-1.1325602941904807, -0.8968206278210037, -1.1464528952076212, -1.1874630473210335},
              1e-10);
  }
  SECTION("int") {
    const ParzenEstimator pe({{"k", {1, 8, 3, 3, 5}}},
                             {{"k", make_int_distribution("k", 1, 8, false, 1)}},
                             parameters(false));
    const auto& k = pe.dimension("k");
    check_all(k.mus, {1.0, 8.0, 3.0, 3.0, 5.0, 4.5});
    check_all(k.sigmas, {2.0, 3.0, 2.0, 1.5, 3.0, 8.0});
    check_all(pe.log_pdf({{"k", {1, 3, 6, 8}}}),
              {-2.0354057781701567, -1.775610600086822, -2.3011930058950822, -2.554197622363714},
              1e-10);
  }
  SECTION("log int") {
    const ParzenEstimator pe({{"m", {1, 16, 1024, 64, 2}}},
                             {{"m", make_int_distribution("m", 1, 1024, true, 1)}},
                             parameters(false));
    const auto& m = pe.dimension("m");
    check_all(m.mus, {0.0, 2.772588722239781, 6.931471805599453, 4.1588830833596715,
                      0.6931471805599453, 3.119406393559504});
    check_all(m.sigmas, {1.0893010211769856, 2.0794415416798357, 2.7725887222397816,
                         2.7725887222397816, 2.0794415416798357, 7.625107148238899});
    check_all(pe.log_pdf({{"m", {1, 3, 100, 1024}}}),
              {-0.9254619020819066, -0.8656710620607408, -0.8914473068316079, -1.0555603001848648},
              1e-10);
  }
}

TEST_CASE("parzen estimator: no observations leave the prior alone", "[tune]") {
  const ParzenEstimator pe({{"x", {}}},
                           {{"x", make_float_distribution("x", -5, 5, false, std::nullopt)}},
                           parameters(true));
  check_all(pe.weights(), {1.0});
  check_all(pe.dimension("x").sigmas, {10.0});
  check_all(pe.log_pdf({{"x", {0.0, 4.0}}}), {0.04097780049094957, -0.039022199509050504}, 1e-10);
}

TEST_CASE("parzen estimator: 30 observations ramp the weights and clip the sigmas", "[tune]") {
  const std::vector<double> obs = {0.549, 0.715, 0.603, 0.545, 0.424, 0.646, 0.438, 0.892,
                                   0.964, 0.383, 0.792, 0.529, 0.568, 0.926, 0.071, 0.087,
                                   0.02,  0.833, 0.778, 0.87,  0.979, 0.799, 0.461, 0.781,
                                   0.118, 0.64,  0.143, 0.945, 0.522, 0.415};
  const ParzenEstimator pe({{"x", obs}},
                           {{"x", make_float_distribution("x", 0, 1, false, std::nullopt)}},
                           parameters(false));
  const auto& w = pe.weights();
  REQUIRE(w.size() == 31);
  CHECK(w[0] == Approx(0.0011661807580174927).epsilon(1e-12));
  CHECK(w[3] == Approx(0.026530612244897955).epsilon(1e-12));
  for (size_t i = 4; i < 31; ++i) CHECK(w[i] == Approx(0.034985422740524776).epsilon(1e-12));
  check_all(pe.dimension("x").sigmas,
            {0.03125,
             0.06899999999999995,
             0.03700000000000003,
             0.03125,
             0.03125,
             0.06899999999999995,
             0.03125,
             0.03400000000000003,
             0.03125,
             0.24000000000000002,
             0.03125,
             0.03125,
             0.03500000000000003,
             0.03400000000000003,
             0.05099999999999999,
             0.03125,
             0.05099999999999999,
             0.03700000000000003,
             0.06300000000000006,
             0.03700000000000003,
             0.03125,
             0.03399999999999992,
             0.03899999999999998,
             0.03125,
             0.03125,
             0.03700000000000003,
             0.24000000000000002,
             0.03125,
             0.03125,
             0.03199999999999997,
             1.0},
            1e-9);
  check_all(pe.log_pdf({{"x", {0.05, 0.5, 0.95}}}),
            {-2.33613841729578, -2.3516317132878655, -2.3981311576133155}, 1e-10);
}

TEST_CASE("parzen estimator: samples are valid values that follow the kernels", "[tune]") {
  const ParzenEstimator pe(mixed_observations(), mixed_space(), parameters(true));
  rlrun::Rng rng(3);
  const Observations s = pe.sample(rng, 2000);
  const SearchSpace space = mixed_space();
  int c_two = 0;
  for (size_t i = 0; i < 2000; ++i) {
    for (const auto& [name, distribution] : space) {
      INFO(name << " = " << s.at(name)[i]);
      REQUIRE(contains(distribution, s.at(name)[i]));
    }
    c_two += s.at("c")[i] == 2;
  }
  // Choice "c" (index 2): two of four kernels put 0.75 on it, the others 0.125 and 1/3.
  const double p_two = 0.2 * (0.75 + 0.75 + 0.125 + 0.125 + 1.0 / 3);
  CHECK(c_two / 2000.0 == Approx(p_two).margin(0.03));
}
