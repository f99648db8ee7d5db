#include <catch2/catch.hpp>

#include "rlrun/algos/common/explained_variance.hpp"
#include "rlrun/algos/common/gae.hpp"

using namespace rlrun;

TEST_CASE("GAE matches a hand computation, episode boundaries included", "[algos][gae]") {
  // 3 steps, 1 env; an episode starts at t = 2 (so t = 1 was terminal).
  StepEnvMatrix rewards(3, 1), values(3, 1), starts(3, 1), adv(3, 1), ret(3, 1);
  rewards << 1, 2, 3;
  values << 0.5, 1.0, 1.5;
  starts << 1, 0, 1;
  Eigen::RowVectorXf last_values(1), last_dones(1);
  last_values << 2.0;
  last_dones << 0;
  const float g = 0.9f, l = 0.8f;
  compute_gae(rewards, values, starts, last_values, last_dones, g, l, adv, ret);
  // t=2: delta = 3 + 0.9*2 - 1.5 = 3.3, A2 = 3.3
  // t=1: next is an episode start -> delta = 2 - 1.0 = 1.0, A1 = 1.0
  // t=0: delta = 1 + 0.9*1.0 - 0.5 = 1.4, A0 = 1.4 + 0.9*0.8*1.0 = 2.12
  CHECK(adv(2, 0) == Approx(3.3));
  CHECK(adv(1, 0) == Approx(1.0));
  CHECK(adv(0, 0) == Approx(2.12));
  CHECK(ret(0, 0) == Approx(2.62));
  CHECK(ret(2, 0) == Approx(4.8));
  // A done last step cuts the bootstrap.
  last_dones << 1;
  compute_gae(rewards, values, starts, last_values, last_dones, g, l, adv, ret);
  CHECK(adv(2, 0) == Approx(1.5));
}

TEST_CASE("explained variance as SB3", "[algos][gae]") {
  Eigen::VectorXf y(4), p(4);
  y << 1, 2, 3, 4;
  p = y;
  CHECK(explained_variance(p, y) == Approx(1.0));
  p.setConstant(2.5f);
  CHECK(explained_variance(p, y) == Approx(0.0));
  CHECK(std::isnan(explained_variance(p, Eigen::VectorXf::Ones(4))));
}
