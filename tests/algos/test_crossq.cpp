// CrossQ (src/rlrun/algos/crossq/, nn/batch_renorm*): sb3-contrib's BatchRenorm1d against a
// double re-implementation in train mode (warm-up and renorm with r/d clipping) and eval mode,
// its running statistics, its backward and the batch-renormalised MLP's against finite
// differences; one CrossQ gradient step (joint critic pass, target, critic loss, actor loss)
// against a double re-computation and its critic and actor gradients against finite
// differences; sb3-contrib's defaults and tensor names; the exported graph; short runs through
// the registry. The rl-zoo learning bar is hidden ([.slow]).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "algos/entropy_regularized_fixtures.hpp"
#include "rlrun/algos/crossq/crossq.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/nn/batch_renorm.hpp"
#include "rlrun/nn/batch_renorm_mlp.hpp"
#include "rlrun/nn/policy_graph.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;
using namespace rlrun::test;

namespace {

// ---- BatchRenorm1d.forward in double (sb3_contrib/common/torch_layers.py) ----

struct RefStats {
  Eigen::VectorXd mean, var;  // the batch's, unbiased
};

RefStats batch_stats(const Eigen::MatrixXd& x) {
  const Eigen::VectorXd mean = x.rowwise().mean();
  const Eigen::VectorXd var =
      (x.colwise() - mean).array().square().rowwise().sum() / static_cast<double>(x.cols() - 1);
  return {mean, var};
}

// r and d of the renorm phase (detached: computed once, then held fixed).
void renorm_factors(const Eigen::MatrixXd& x, const Eigen::VectorXd& ra_mean,
                    const Eigen::VectorXd& ra_var, double eps, Eigen::VectorXd& r,
                    Eigen::VectorXd& d) {
  const RefStats s = batch_stats(x);
  const Eigen::ArrayXd running_std = (ra_var.array() + eps).sqrt();
  r = ((s.var.array() + eps).sqrt() / running_std).cwiseMax(1.0 / 3.0).cwiseMin(3.0);
  d = ((s.mean - ra_mean).array() / running_std).cwiseMax(-5.0).cwiseMin(5.0);
}

// Train mode with given r, d (warm-up: r = 1, d = 0).
Eigen::MatrixXd bn_train(const Eigen::MatrixXd& x, const Eigen::VectorXd& scale,
                         const Eigen::VectorXd& bias, const Eigen::VectorXd& r,
                         const Eigen::VectorXd& d, double eps) {
  const RefStats s = batch_stats(x);
  const Eigen::ArrayXd mean = s.mean.array() - d.array() * s.var.array().sqrt() / r.array();
  const Eigen::ArrayXd std = (s.var.array() / r.array().square() + eps).sqrt();
  Eigen::MatrixXd y = x;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    y.col(j) = scale.array() * (x.col(j).array() - mean) / std + bias.array();
  return y;
}

Eigen::MatrixXd bn_eval(const Eigen::MatrixXd& x, const Eigen::VectorXd& scale,
                        const Eigen::VectorXd& bias, const Eigen::VectorXd& ra_mean,
                        const Eigen::VectorXd& ra_var, double eps) {
  Eigen::MatrixXd y = x;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    y.col(j) =
        scale.array() * (x.col(j) - ra_mean).array() / (ra_var.array() + eps).sqrt() + bias.array();
  return y;
}

Eigen::VectorXd ones(Eigen::Index n) { return Eigen::VectorXd::Ones(n); }
Eigen::VectorXd zeros(Eigen::Index n) { return Eigen::VectorXd::Zero(n); }

// ---- the batch-renormalised MLP in double, parameters in blocks() order ----

Eigen::VectorXd flat_values(BatchRenormMlp& net) {
  std::vector<double> v;
  for (const ParamBlock& b : net.blocks()) v.insert(v.end(), b.value, b.value + b.size);
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::VectorXd flat_grads(BatchRenormMlp& net) {
  std::vector<double> v;
  for (const ParamBlock& b : net.blocks()) v.insert(v.end(), b.grad, b.grad + b.size);
  return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::MatrixXd activate(Activation act, const Eigen::MatrixXd& z) {
  return act == Activation::kTanh ? Eigen::MatrixXd(z.array().tanh())
                                  : Eigen::MatrixXd(z.array().max(0.0));
}

// A BatchRenorm in train mode during warm-up (batch statistics) or in eval mode (the layer's
// running statistics), scale and bias read from p at `offset`.
Eigen::MatrixXd ref_norm(const BatchRenorm& norm, const Eigen::VectorXd& p, Eigen::Index& offset,
                         const Eigen::MatrixXd& h, bool training) {
  const int f = norm.features();
  const Eigen::VectorXd scale = p.segment(offset, f), bias = p.segment(offset + f, f);
  offset += 2 * f;
  const double eps = norm.options().eps;
  if (training) return bn_train(h, scale, bias, ones(f), zeros(f), eps);
  return bn_eval(h, scale, bias, norm.running_mean().cast<double>(),
                 norm.running_var().cast<double>(), eps);
}

Eigen::MatrixXd ref_net(const BatchRenormMlp& net, const Eigen::VectorXd& p, Eigen::MatrixXd h,
                        bool training) {
  Eigen::Index offset = 0;
  for (int l = 0; l < net.num_linear(); ++l) {
    if (const BatchRenorm* norm = net.norm(l)) h = ref_norm(*norm, p, offset, h, training);
    const Mlp& linear = net.linear(l);
    const int in = linear.in_dim(), out = linear.out_dim();
    const Eigen::MatrixXd w = Eigen::Map<const Eigen::MatrixXd>(p.data() + offset, out, in);
    const Eigen::VectorXd b = p.segment(offset + Eigen::Index{out} * in, out);
    offset += Eigen::Index{out} * in + out;
    h = (w * h).colwise() + b;
    if (l < static_cast<int>(net.hidden().size())) h = activate(net.activation(), h);
  }
  if (const BatchRenorm* norm = net.trailing_norm()) h = ref_norm(*norm, p, offset, h, training);
  return h;
}

// Small networks in warm-up (batch norm) unless a test says otherwise.
CrossQ::Config small_config() {
  CrossQ::Config c;
  c.policy.net_arch = {{8, 8}, {10, 10}};
  c.policy.activation_fn = Activation::kTanh;  // smooth for finite differences
  c.off_policy.batch_size = 6;
  c.off_policy.buffer_size = 1000;
  c.off_policy.gamma = 0.9;
  c.ent_coef = "auto_0.5";
  return c;
}

// The squashed Gaussian of SB3's Actor from the heads' output column [mu; log_std] and noise.
std::pair<Eigen::VectorXd, double> squash(const Eigen::VectorXd& out, int a_dim,
                                          const Eigen::VectorXd& noise) {
  Eigen::VectorXd a(a_dim);
  double logp = 0.0;
  for (int i = 0; i < a_dim; ++i) {
    const double mu = out(i), log_std = std::clamp(out(a_dim + i), -20.0, 2.0);
    const double u = mu + std::exp(log_std) * noise(i);
    a(i) = std::tanh(u);
    logp += -0.5 * noise(i) * noise(i) - log_std - kHalfLog2Pi - std::log(1.0 - a(i) * a(i) + 1e-6);
  }
  return {a, logp};
}

// The minimum over the critics in eval mode (their BatchRenorm folded) at (o, a).
double min_q_eval(const CrossQ& algo, const Eigen::VectorXd& o, const Eigen::VectorXd& a) {
  double q = std::numeric_limits<double>::infinity();
  for (int i = 0; i < algo.critic().n_critics(); ++i) {
    const Mlp f = algo.critic().q(i).folded();
    q = std::min(q, mlp_forward_one(f, params_of(f), concat(o, a))(0));
  }
  return q;
}

}  // namespace

TEST_CASE("BatchRenorm forward: warm-up, renorm with r/d clipping, eval, running statistics",
          "[algos][crossq][batch_renorm]") {
  Rng rng(3);
  const BatchRenormOptions options{0.1f, 1e-3f, 2};
  BatchRenorm norm(3, options);
  CHECK(norm.scale().isOnes());
  CHECK(norm.running_var().isOnes());
  // Scale and bias away from identity (as after training).
  Eigen::VectorXf p(6);
  p << 1.5f, -0.5f, 2.0f, 0.1f, 0.2f, -0.3f;
  norm.params() = p;
  const Eigen::VectorXd scale = p.head(3).cast<double>(), bias = p.tail(3).cast<double>();
  Eigen::VectorXd ra_mean = zeros(3), ra_var = ones(3);
  for (int call = 0; call < 5; ++call) {
    INFO("call " << call);
    // Feature 1 far from the running mean (d clipped at 5); feature 2 spread wide once the
    // renorm phase starts (r clipped at 3).
    Eigen::MatrixXf x = random_matrix(rng, 3, 7);
    x.row(1).array() += 40.0f;
    if (call > 2) x.row(2) *= 30.0f;
    const Eigen::MatrixXd xd = x.cast<double>();
    Eigen::VectorXd r = ones(3), d = zeros(3);
    const bool renorm = call > 2;  // steps > warmup_steps = 2 from the fourth call on
    if (renorm) renorm_factors(xd, ra_mean, ra_var, 1e-3, r, d);
    const Eigen::MatrixXd expected = bn_train(xd, scale, bias, r, d, 1e-3);
    const Eigen::MatrixXf& y = norm.forward(x, true);
    CHECK((y.cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-4);
    if (renorm) CHECK(d(1) == 5.0);
    if (call == 3) CHECK(r(2) == 3.0);  // the running variance of feature 2 still ~1
    const RefStats s = batch_stats(xd);
    ra_mean += 0.1 * (s.mean - ra_mean);
    ra_var += 0.1 * (s.var - ra_var);
    CHECK((norm.running_mean().cast<double>() - ra_mean).cwiseAbs().maxCoeff() < 1e-3);
    CHECK((norm.running_var().cast<double>() - ra_var).cwiseAbs().maxCoeff() < 1e-2);
    CHECK(norm.steps() == call + 1);
  }
  // Eval mode: the running statistics, nothing updated.
  const Eigen::MatrixXf x = random_matrix(rng, 3, 4);
  const Eigen::VectorXf mean_before = norm.running_mean();
  const Eigen::MatrixXd expected =
      bn_eval(x.cast<double>(), scale, bias, norm.running_mean().cast<double>(),
              norm.running_var().cast<double>(), 1e-3);
  CHECK((norm.forward(x, false).cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-5);
  CHECK(norm.running_mean() == mean_before);
  CHECK(norm.steps() == 5);
  // Eval mode as the affine map export folds.
  const Eigen::MatrixXf affine =
      (x.array().colwise() * norm.eval_scale().array()).colwise() + norm.eval_shift().array();
  CHECK((affine.cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-5);
  CHECK_THROWS_AS(norm.forward(random_matrix(rng, 3, 1), true), std::invalid_argument);
}

TEST_CASE("BatchRenorm backward matches finite differences in warm-up, renorm and eval mode",
          "[algos][crossq][batch_renorm][gradcheck]") {
  const int mode = GENERATE(0, 1, 2);  // warm-up, renorm (r, d detached), eval
  INFO("mode " << mode);
  Rng rng(5);
  // Renorm after the first train pass, except in the warm-up case.
  BatchRenorm norm(3, {0.2f, 1e-3f, mode == 0 ? 1000 : 1});
  Eigen::VectorXf p(6);
  p << 1.5f, -0.5f, 2.0f, 0.1f, 0.2f, -0.3f;
  norm.params() = p;
  // Two train passes: the running statistics move off (0, 1); renorm starts after them.
  for (int k = 0; k < 2; ++k) norm.forward(random_matrix(rng, 3, 5, 2.0), true);
  Eigen::MatrixXf x = random_matrix(rng, 3, 5, 1.5);
  x.row(0).array() += 3.0f;  // d and r clipped in some features
  x.row(2) *= 8.0f;
  const Eigen::MatrixXd xd = x.cast<double>();
  const Eigen::VectorXd ra_mean = norm.running_mean().cast<double>();
  const Eigen::VectorXd ra_var = norm.running_var().cast<double>();
  Eigen::VectorXd r = ones(3), d = zeros(3);
  if (mode == 1) renorm_factors(xd, ra_mean, ra_var, 1e-3, r, d);
  const Eigen::MatrixXf w = random_matrix(rng, 3, 5);
  // L = sum(w * y) over the parameters [scale; bias] and the input.
  const auto loss = [&](const Eigen::VectorXd& params, const Eigen::MatrixXd& in) {
    const Eigen::VectorXd s = params.head(3), b = params.tail(3);
    const Eigen::MatrixXd y =
        mode == 2 ? bn_eval(in, s, b, ra_mean, ra_var, 1e-3) : bn_train(in, s, b, r, d, 1e-3);
    return (y.array() * w.cast<double>().array()).sum();
  };
  norm.forward(x, mode != 2);
  norm.zero_grad();
  Eigen::MatrixXf grad_x;
  norm.backward(w, grad_x);
  const Eigen::VectorXd pd = p.cast<double>();
  require_grad_close(norm.grads().cast<double>(),
                     numeric_gradient([&](const Eigen::VectorXd& q) { return loss(q, xd); }, pd));
  const Eigen::VectorXd flat_x = Eigen::Map<const Eigen::VectorXd>(xd.data(), xd.size());
  const Eigen::VectorXd numeric = numeric_gradient(
      [&](const Eigen::VectorXd& v) {
        return loss(pd, Eigen::Map<const Eigen::MatrixXd>(v.data(), 3, 5));
      },
      flat_x);
  require_grad_close(Eigen::Map<const Eigen::VectorXf>(grad_x.data(), grad_x.size()).cast<double>(),
                     numeric, 2e-3);
}

TEST_CASE(
    "BatchRenormMlp: torch module indices, forward and backward against double and finite "
    "differences, the folded eval-mode network",
    "[algos][crossq][batch_renorm][gradcheck]") {
  const bool critic = GENERATE(true, false);  // an output Linear, or latent_pi's trailing BN
  INFO((critic ? "critic" : "actor latent_pi"));
  Rng rng(7);
  BatchRenormMlp net(4, {6, 5}, critic ? 2 : 0, Activation::kTanh, true, {0.01f, 1e-3f, 1000});
  Rng init(1);
  net.init_torch_default(init);
  // Scales and biases of the BatchRenorm layers away from identity.
  for (ParamBlock b : net.blocks())
    if (b.size % 2 == 0 && b.size <= 12)
      for (Eigen::Index k = 0; k < b.size; ++k)
        b.value[k] += 0.3f * static_cast<float>(rng.normal());
  TensorMap t;
  net.save("qf0", t);
  // [BN Linear Tanh] x 2, then BN Linear (critic) or BN (actor).
  for (const char* name :
       {"qf0.0.ra_var", "qf0.1.weight", "qf0.3.scale", "qf0.4.bias", "qf0.6.steps"}) {
    INFO(name);
    CHECK(t.count(name) == 1);
  }
  CHECK(t.count("qf0.7.weight") == (critic ? 1u : 0u));
  CHECK(t.size() == (critic ? 3 * 5 + 3 * 2 : 3 * 5 + 2 * 2));

  const Eigen::MatrixXf x = random_matrix(rng, 4, 7);
  const Eigen::MatrixXf w = random_matrix(rng, net.out_dim(), 7);
  const Eigen::VectorXd p = flat_values(net);
  const Eigen::MatrixXf& y = net.forward(x, true);
  CHECK((y.cast<double>() - ref_net(net, p, x.cast<double>(), true)).cwiseAbs().maxCoeff() < 1e-4);
  Eigen::MatrixXf grad_x;
  net.zero_grad_and_backward(w, &grad_x);
  const auto loss = [&](const Eigen::VectorXd& q, const Eigen::MatrixXd& in) {
    return (ref_net(net, q, in, true).array() * w.cast<double>().array()).sum();
  };
  require_grad_close(
      flat_grads(net),
      numeric_gradient([&](const Eigen::VectorXd& q) { return loss(q, x.cast<double>()); }, p));
  const Eigen::MatrixXd xd = x.cast<double>();
  require_grad_close(Eigen::Map<const Eigen::VectorXf>(grad_x.data(), grad_x.size()).cast<double>(),
                     numeric_gradient(
                         [&](const Eigen::VectorXd& v) {
                           return loss(p, Eigen::Map<const Eigen::MatrixXd>(v.data(), 4, 7));
                         },
                         Eigen::Map<const Eigen::VectorXd>(xd.data(), xd.size())),
                     2e-3);

  // Eval mode: the running statistics; the folded plain network computes the same.
  const Eigen::MatrixXf& ye = net.forward(x, false);
  CHECK((ye.cast<double>() - ref_net(net, p, xd, false)).cwiseAbs().maxCoeff() < 1e-4);
  if (critic) {
    const Mlp f = net.folded();
    CHECK((mlp_forward(f, params_of(f), xd) - ye.cast<double>()).cwiseAbs().maxCoeff() < 1e-4);
    // Input gradient rows [1, 4) in eval mode, against finite differences.
    Eigen::MatrixXf grad_tail;
    net.backward_input(w, grad_tail, 1);
    const Eigen::VectorXd numeric = numeric_gradient(
        [&](const Eigen::VectorXd& v) {
          return (ref_net(net, p, Eigen::Map<const Eigen::MatrixXd>(v.data(), 4, 7), false)
                      .array() *
                  w.cast<double>().array())
              .sum();
        },
        Eigen::Map<const Eigen::VectorXd>(xd.data(), xd.size()));
    const Eigen::MatrixXd numeric_m = Eigen::Map<const Eigen::MatrixXd>(numeric.data(), 4, 7);
    const Eigen::MatrixXd tail = numeric_m.bottomRows(3);
    require_grad_close(
        Eigen::Map<const Eigen::VectorXf>(grad_tail.data(), grad_tail.size()).cast<double>(),
        Eigen::Map<const Eigen::VectorXd>(tail.data(), tail.size()));
  }
}

TEST_CASE(
    "CrossQ train step: next actions in eval mode, the joint critic pass, target, critic loss, "
    "actor loss and temperature match a double re-computation, and gradients match finite "
    "differences",
    "[algos][crossq][gradcheck]") {
  const int n = GENERATE(6, 40);  // 40: the products split over two cores
  INFO("batch " << n);
  const int obs_dim = 3, act_dim = 2;
  CrossQ algo(small_config(), box_setup(obs_dim, act_dim));
  Rng rng(11);
  // A few steps first, so that the running statistics are not (0, 1).
  for (int k = 0; k < 3; ++k)
    algo.train_on_batch(random_batch(rng, obs_dim, act_dim, n, 2.0), 1e-3f, true);
  const ReplayBatch b = random_batch(rng, obs_dim, act_dim, n, 2.0);
  const Mlp actor_eval = algo.actor().latent_pi().folded(&algo.actor().heads().net());
  const double alpha = std::exp(static_cast<double>(algo.ent_coef().log_value()));
  std::vector<Eigen::VectorXd> critic_p;
  for (int i = 0; i < 2; ++i) critic_p.push_back(flat_values(algo.critic().q(i)));
  const int64_t actor_steps = algo.actor().latent_pi().norm(0)->steps();

  // Learning rate 0: the parameters stay; the gradients and statistics are the step's.
  const CrossQStepStats stats = algo.train_on_batch(b, 0.0f, true);
  CHECK(stats.ent_coef == Approx(alpha));
  CHECK(algo.actor().latent_pi().norm(0)->steps() == actor_steps + 1);  // one train-mode pass

  // Next actions from the eval-mode actor (running statistics before the step).
  Eigen::MatrixXd next_a(act_dim, n);
  Eigen::VectorXd next_logp(n);
  for (int j = 0; j < n; ++j) {
    const auto [a, lp] =
        squash(mlp_forward_one(actor_eval, params_of(actor_eval), b.next_obs.col(j).cast<double>()),
               act_dim, algo.last_next_noise().col(j).cast<double>());
    next_a.col(j) = a;
    next_logp(j) = lp;
  }
  CHECK((algo.last_next_actions().cast<double>() - next_a).cwiseAbs().maxCoeff() < 1e-4);
  // The joint pass: one train-mode batch of [obs, next_obs] x [actions, next_actions].
  Eigen::MatrixXd joint(obs_dim + act_dim, 2 * n);
  joint << b.obs.cast<double>(), b.next_obs.cast<double>(), b.actions.cast<double>(),
      algo.last_next_actions().cast<double>();
  std::vector<Eigen::MatrixXd> q;
  for (int i = 0; i < 2; ++i) q.push_back(ref_net(algo.critic().q(i), critic_p[i], joint, true));
  double critic_loss = 0.0;
  for (int j = 0; j < n; ++j) {
    const double next_q = std::min(q[0](0, n + j), q[1](0, n + j)) - alpha * next_logp(j);
    const double y = b.rewards(j) + (1.0 - b.dones(j)) * 0.9 * next_q;
    CHECK(algo.last_critic_target()(0, j) == Approx(y).epsilon(1e-4).margin(1e-4));
    for (int i = 0; i < 2; ++i) critic_loss += 0.5 * std::pow(q[i](0, j) - y, 2) / n;
  }
  CHECK(stats.critic_loss == Approx(critic_loss).epsilon(1e-4));

  // d critic_loss / d critic i's parameters, the target fixed, through both halves' statistics.
  const Eigen::RowVectorXd target = algo.last_critic_target().cast<double>();
  for (int i = 0; i < 2; ++i) {
    INFO("critic " << i);
    const auto loss_of = [&](const Eigen::VectorXd& p) {
      const Eigen::MatrixXd qi = ref_net(algo.critic().q(i), p, joint, true);
      return 0.5 * (qi.leftCols(n) - target).squaredNorm() / n;
    };
    require_grad_close(flat_grads(algo.critic().q(i)), numeric_gradient(loss_of, critic_p[i]));
  }

  // The actor: latent_pi in train mode over the batch, the critics in eval mode (their running
  // statistics now include the joint pass).
  const Eigen::MatrixXd noise = algo.last_policy_noise().cast<double>();
  const Eigen::VectorXd latent_p = flat_values(algo.actor().latent_pi());
  const Eigen::VectorXd head_p = params_of(algo.actor().heads().net());
  const Mlp& head = algo.actor().heads().net();
  double mean_logp = 0.0;
  const auto actor_loss_of = [&](const Eigen::VectorXd& p) {
    const Eigen::MatrixXd latent =
        ref_net(algo.actor().latent_pi(), p.head(latent_p.size()), b.obs.cast<double>(), true);
    const Eigen::MatrixXd out = mlp_forward(head, p.tail(head_p.size()), latent);
    double loss = 0.0;
    mean_logp = 0.0;
    for (int j = 0; j < n; ++j) {
      const auto [a, lp] = squash(out.col(j), act_dim, noise.col(j));
      loss += alpha * lp - min_q_eval(algo, b.obs.col(j).cast<double>(), a);
      mean_logp += lp / n;
    }
    return loss / n;
  };
  Eigen::VectorXd actor_p(latent_p.size() + head_p.size());
  actor_p << latent_p, head_p;
  CHECK(stats.actor_loss == Approx(actor_loss_of(actor_p)).epsilon(1e-4));
  // The temperature's loss: -(log_alpha * (log_prob + target_entropy)).mean().
  CHECK(stats.ent_coef_loss ==
        Approx(-std::log(alpha) * (mean_logp - act_dim)).epsilon(1e-3).margin(1e-5));
  Eigen::VectorXd analytic(actor_p.size());
  analytic << flat_grads(algo.actor().latent_pi()),
      algo.actor().heads().net().grads().cast<double>();
  require_grad_close(analytic, numeric_gradient(actor_loss_of, actor_p));
}

TEST_CASE("CrossQ defaults are sb3-contrib 2.4's", "[algos][crossq]") {
  const CrossQ::Config c;
  CHECK(c.learning_rate(1.0) == 1e-3);
  CHECK(c.off_policy.buffer_size == 1000000);
  CHECK(c.off_policy.learning_starts == 100);
  CHECK(c.off_policy.batch_size == 256);
  CHECK(c.off_policy.tau == 1.0);
  CHECK(c.off_policy.gamma == 0.99);
  CHECK(c.off_policy.train_freq.frequency == 1);
  CHECK(c.off_policy.gradient_steps == 1);
  CHECK(c.ent_coef == "auto");
  CHECK(c.target_entropy == "auto");
  CHECK(c.policy_delay == 3);
  CHECK_FALSE(c.use_sde);
  CHECK(c.sde_sample_freq == -1);
  const CrossQPolicyConfig& p = c.policy;
  CHECK(p.net_arch.pi == std::vector<int>{256, 256});
  CHECK(p.net_arch.qf == std::vector<int>{1024, 1024});
  CHECK(p.activation_fn == Activation::kReLU);
  CHECK(p.batch_norm);
  CHECK(p.batch_norm_momentum == 0.01);
  CHECK(p.batch_norm_eps == 0.001);
  CHECK(p.renorm_warmup_steps == 100000);
  CHECK(p.log_std_init == -3.0);
  CHECK(p.clip_mean == 2.0);
  CHECK(p.n_critics == 2);
  // Adam with betas (0.5, 0.999) for the actor and the critics, torch's defaults for ent_coef.
  CrossQ::Config small = small_config();
  const CrossQ algo(small, box_setup(3, 1));
  CHECK(algo.actor_optimizer().config().beta1 == 0.5);
  CHECK(algo.critic_optimizer(1).config().beta1 == 0.5);
  CHECK(algo.critic_optimizer(0).config().beta2 == 0.999);
  CHECK(algo.ent_coef().target_entropy() == -1.0f);
  CHECK(algo.actor().latent_pi().norm(0)->options().momentum == 0.01f);
  // Settings sb3-contrib does not have: tau, and a batch the statistics cannot use.
  small.off_policy.tau = 0.005;
  CHECK_THROWS_AS(CrossQ(small, box_setup(3, 1)), std::invalid_argument);
  CHECK(CrossQ::check(small, box_setup(3, 1)).at(0).key == "tau");
  small = small_config();
  small.off_policy.batch_size = 1;
  CHECK_THROWS_AS(CrossQ(small, box_setup(3, 1)), std::invalid_argument);
  CHECK_THROWS_AS(CrossQ(small_config(),
                         AlgorithmSetup{Space::box(-1.0f, 1.0f, {3}), Space::discrete(2), 1, 0}),
                  std::invalid_argument);
}

TEST_CASE("CrossQ model tensors use sb3-contrib's names and load back, and the exported graph",
          "[algos][crossq]") {
  CrossQ::Config cfg = small_config();
  cfg.policy.net_arch = {{8}, {8}};
  CrossQ a(cfg, box_setup(3, 1, 1));
  Rng rng(4);
  for (int k = 0; k < 3; ++k) a.train_on_batch(random_batch(rng, 3, 1, 6), 1e-2f, k == 2);
  TensorMap t;
  a.save(t);
  for (const char* name :
       {"actor.latent_pi.0.scale", "actor.latent_pi.0.ra_mean", "actor.latent_pi.1.weight",
        "actor.latent_pi.3.ra_var", "actor.latent_pi.3.steps", "actor.mu.weight",
        "actor.log_std.bias", "critic.qf0.0.steps", "critic.qf0.1.weight", "critic.qf1.3.bias",
        "critic.qf1.4.weight", "log_ent_coef"}) {
    INFO(name);
    CHECK(t.count(name) == 1);
  }
  // Actor: 2 BatchRenorm x 5 + Linear 2 + mu 2 + log_std 2; critics: 2 x (2 x 5 + 2 x 2).
  CHECK(t.size() == 16 + 28 + 1);
  CHECK(t.count("critic_target.qf0.1.weight") == 0);
  CHECK(*t.at("critic.qf0.0.steps").data<int64_t>() == 3);
  CHECK(*t.at("actor.latent_pi.0.steps").data<int64_t>() == 1);
  CHECK(t.at("critic.qf0.1.weight").shape == std::vector<int64_t>{8, 4});

  CrossQ b(cfg, box_setup(3, 1, 99));
  b.load(t);
  const Eigen::MatrixXf obs = random_matrix(rng, 3, 4);
  Eigen::MatrixXf pa, pb;
  a.predict(obs, true, pa);
  b.predict(obs, true, pb);
  CHECK(pa == pb);
  CHECK(b.critic().q(1).norm(1)->running_var() == a.critic().q(1).norm(1)->running_var());
  TensorMap bad = t;
  bad["critic.qf0.0.steps"] = scalar_tensor<int64_t>(-1);
  CHECK_THROWS(b.load(bad));
  bad = t;
  bad.erase("actor.latent_pi.3.ra_mean");
  CHECK_THROWS(b.load(bad));

  // The graph: the deterministic action and Q_0(s, a) with eval-mode BatchRenorm folded.
  PolicyGraph graph;
  graph.add_input("obs", 3);
  a.export_policy(graph, "obs", true);
  const auto values = evaluate_graph(graph, {obs});
  CHECK((values.at(graph.action()) - pa).cwiseAbs().maxCoeff() < 1e-5f);
  Eigen::MatrixXf scaled;
  a.actor().mode(obs, scaled);
  a.critic().forward(obs, scaled, false);
  CHECK((values.at(graph.value()) - a.critic().q(0).output()).cwiseAbs().maxCoeff() < 1e-5f);
}

namespace {
double evaluate_model(const std::string& model_path, int episodes, uint64_t seed) {
  return test::evaluate_model(read_model(model_path), episodes, seed).mean_return();
}
}  // namespace

TEST_CASE(
    "CrossQ trains on Pendulum-v1 through the registry, deterministically, the actor every "
    "policy_delay updates",
    "[algos][crossq]") {
  testing::TempDir dir("crossq_smoke");
  const auto run = [&](uint64_t seed, const std::string& extra) {
    const Experiment e = pendulum_experiment(
        "CrossQ", dir.str(), 400, seed,
        ", learning_starts: 100, batch_size: 32, policy: {net_arch: [32, 32]}" + extra);
    const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
    CHECK(outcome.timesteps == 400);
    return outcome.model_path;
  };
  const ModelFile m1 = read_model(run(3, ""));
  const ModelFile m2 = read_model(run(3, ""));
  CHECK(m1.meta.algorithm == "CrossQ");
  for (const char* name :
       {"actor.mu.weight", "critic.qf1.4.weight", "critic.qf0.3.ra_var", "log_ent_coef"}) {
    INFO(name);
    CHECK(m1.tensors.at(name).bytes == m2.tensors.at(name).bytes);
  }
  // 300 gradient steps (steps 101..400): every one passes the critics' BatchRenorm in train
  // mode, every third (policy_delay 3) the actor's.
  CHECK(*m1.tensors.at("critic.qf0.0.steps").data<int64_t>() == 300);
  CHECK(*m1.tensors.at("actor.latent_pi.6.steps").data<int64_t>() == 100);
  // gSDE runs too; the model evaluates a whole episode.
  const std::string gsde = run(3, ", use_sde: true, sde_sample_freq: 4, policy_delay: 2");
  CHECK(read_model(gsde).tensors.count("actor.log_std") == 1);
  CHECK(std::isfinite(evaluate_model(gsde, 1, 5)));
}

// The zoo's Pendulum-v1 entry (crossq.yml: 20000 steps, policy_delay 2, net_arch [256, 256]),
// seed 1; docs/benchmarks.md has the three seeds.
TEST_CASE("CrossQ learns Pendulum-v1 with the zoo's entry", "[.slow][crossq_learning]") {
  testing::TempDir dir("crossq_learn");
  const Experiment e = pendulum_experiment("CrossQ", dir.str(), 20000, 1,
                                           ", policy_delay: 2, policy: {net_arch: [256, 256]}");
  const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
  const double mean = evaluate_model(outcome.model_path, 10, 1000);
  INFO("mean return " << mean);
  CHECK(mean > -250.0);
}

namespace {
// Best-of-3 wall time of one gradient step (mean over `iters`).
template <class Step>
double seconds_per_step(Step&& step, int iters) {
  for (int i = 0; i < 30; ++i) step(i);
  double best = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) step(i);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / iters);
  }
  return best;
}
}  // namespace

// Per gradient step against SAC with the same networks (the zoo's Pendulum entry: 256x256 actor
// and critics, batch 256); CrossQ's critics run 2 x 256 columns in train mode.
TEST_CASE("CrossQ update micro-benchmark against SAC (rl-zoo Pendulum sizes)",
          "[.bench][crossq_bench]") {
  AlgorithmSetup setup = box_setup(3, 1);
  setup.pool = &testing::test_thread_pool();
  Rng rng(1);
  const ReplayBatch b = random_batch(rng, 3, 1, 256);
  SAC sac(SAC::Config{}, setup);
  CrossQ::Config cfg;
  cfg.policy.net_arch = {{256, 256}, {256, 256}};
  CrossQ crossq(cfg, setup);
  const int iters = 300;
  const double t_sac = seconds_per_step([&](int) { sac.train_on_batch(b, 1e-3f, true); }, iters);
  const double t_every =
      seconds_per_step([&](int) { crossq.train_on_batch(b, 1e-3f, true); }, iters);
  const double t_delay2 =
      seconds_per_step([&](int i) { crossq.train_on_batch(b, 1e-3f, i % 2 == 0); }, iters);
  std::printf(
      "gradient step, 256x256 networks, batch 256, %d threads: SAC %.0f us; CrossQ with the "
      "actor every step %.0f us (%.2fx), policy_delay 2 %.0f us (%.2fx)\n",
      testing::test_thread_pool().threads(), t_sac * 1e6, t_every * 1e6, t_every / t_sac,
      t_delay2 * 1e6, t_delay2 / t_sac);
  CHECK(std::isfinite(t_every));
}
