#include "rlrun/nn/mlp.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::numeric_gradient;
using test::require_grad_close;

Eigen::MatrixXf random_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng, double scale = 1.0) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = static_cast<float>(scale * rng.normal());
  }
  return m;
}

struct Case {
  int in;
  std::vector<int> hidden;
  int out;
  Activation act;
  int batch;
};

void check_mlp_gradients(const Case& c, uint64_t seed) {
  Rng rng(seed);
  Mlp net(c.in, c.hidden, c.out, c.act);
  net.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
  // Non-zero biases so that their gradients flow through a generic point.
  for (int l = 0; l < net.num_layers(); ++l) {
    net.bias(l) = random_matrix(net.layer_out(l), 1, rng, 0.1);
  }
  const Eigen::MatrixXf x = random_matrix(c.in, c.batch, rng);
  const Eigen::MatrixXf weights = random_matrix(c.out, c.batch, rng);  // L = sum(weights .* y)

  const Eigen::MatrixXf& y = net.forward(x);
  const Eigen::VectorXd params = net.params().cast<double>();
  const Eigen::MatrixXd xd = x.cast<double>();
  const Eigen::MatrixXd wd = weights.cast<double>();
  const Eigen::MatrixXd y_ref = test::mlp_forward(net, params, xd);
  CHECK((y.cast<double>() - y_ref).cwiseAbs().maxCoeff() <
        1e-5 * (1.0 + y_ref.cwiseAbs().maxCoeff()));

  net.zero_grad();
  Eigen::MatrixXf grad_x;
  net.backward(weights, &grad_x);
  REQUIRE(grad_x.rows() == c.in);
  REQUIRE(grad_x.cols() == c.batch);

  const auto loss_of_params = [&](const Eigen::VectorXd& p) {
    return (test::mlp_forward(net, p, xd).array() * wd.array()).sum();
  };
  const auto loss_of_input = [&](const Eigen::VectorXd& xv) {
    const Eigen::Map<const Eigen::MatrixXd> xm(xv.data(), c.in, c.batch);
    return (test::mlp_forward(net, params, xm).array() * wd.array()).sum();
  };
  {
    INFO("parameter gradient");
    require_grad_close(net.grads().cast<double>(), numeric_gradient(loss_of_params, params));
  }
  {
    INFO("input gradient");
    require_grad_close(flat(grad_x), numeric_gradient(loss_of_input, flat(x)));
  }
}

TEST_CASE("Mlp gradients match finite differences", "[nn]") {
  const std::vector<Case> cases = {
      {3, {5, 7}, 2, Activation::kTanh, 4},
      {3, {5, 7}, 2, Activation::kReLU, 4},
      {1, {1}, 1, Activation::kTanh, 1},
      {1, {3}, 1, Activation::kReLU, 1},
      {6, {}, 3, Activation::kTanh, 2},
      {4, {64, 64}, 2, Activation::kTanh, 3},
      {7, {9, 3, 11}, 5, Activation::kReLU, 13},
      {2, {33}, 1, Activation::kTanh, 17},
      // Batch 1 and 2 take the dot-product path for the input gradient of wide layers.
      {5, {16, 24}, 3, Activation::kTanh, 2},
      {4, {64, 64}, 2, Activation::kReLU, 1},
      // Every tile shape of the kernels: 2-packet, 1-packet and scalar rows, 6..1 columns.
      {20, {40, 17}, 9, Activation::kReLU, 37},
      {9, {8}, 12, Activation::kTanh, 11},
      // Widths off the packet size: the overlapping last packet in every product.
      {13, {300, 13}, 3, Activation::kReLU, 9},
      // ELU and LeakyReLU through the same tile shapes: packet and scalar rows, both paths of
      // the input gradient (batch 1 and 2 use dot products).
      {3, {5, 7}, 2, Activation::kELU, 4},
      {3, {5, 7}, 2, Activation::kLeakyReLU, 4},
      {20, {40, 17}, 9, Activation::kELU, 37},
      {20, {40, 17}, 9, Activation::kLeakyReLU, 37},
      {13, {300, 13}, 3, Activation::kELU, 9},
      {13, {300, 13}, 3, Activation::kLeakyReLU, 9},
      {4, {64, 64}, 2, Activation::kELU, 1},
      {5, {16, 24}, 3, Activation::kLeakyReLU, 2},
      {7, {9, 3, 11}, 5, Activation::kELU, 13},
      {1, {3}, 1, Activation::kLeakyReLU, 1},
      // GELU, whose derivative the backward reads off the stored pre-activation, through the
      // same shapes.
      {3, {5, 7}, 2, Activation::kGELU, 4},
      {20, {40, 17}, 9, Activation::kGELU, 37},
      {13, {300, 13}, 3, Activation::kGELU, 9},
      {4, {64, 64}, 2, Activation::kGELU, 1},
      {5, {16, 24}, 3, Activation::kGELU, 2},
      {7, {9, 3, 11}, 5, Activation::kGELU, 13},
      {1, {3}, 1, Activation::kGELU, 1},
  };
  uint64_t seed = 11;
  for (const Case& c : cases) {
    INFO("in " << c.in << " hidden " << c.hidden.size() << " out " << c.out << " act "
               << activation_name(c.act) << " batch " << c.batch);
    check_mlp_gradients(c, seed++);
  }
}

TEST_CASE("Mlp backward with grad_last_hidden matches finite differences for every activation",
          "[nn]") {
  // L = sum(weights .* y) + sum(v .* last_hidden()): the extra gradient enters before the last
  // hidden layer's activation derivative (Mlp::add_hidden_gradient; gSDE with learn_features).
  // Batch 2 and 17: the dot-product and the transposed-weight input gradient.
  uint64_t seed = 61;
  for (const auto& spelling : kActivationSpellings) {
    for (const int batch : {2, 17}) {
      INFO(spelling.name << " batch " << batch);
      Rng rng(seed++);
      Mlp net(4, {9, 20}, 3, spelling.act);
      net.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
      for (int l = 0; l < net.num_layers(); ++l)
        net.bias(l) = random_matrix(net.layer_out(l), 1, rng, 0.1);
      const Eigen::MatrixXf x = random_matrix(4, batch, rng);
      const Eigen::MatrixXf weights = random_matrix(3, batch, rng);
      const Eigen::MatrixXf v = random_matrix(20, batch, rng);
      net.forward(x);
      net.zero_grad();
      Eigen::MatrixXf grad_x;
      net.backward(weights, &grad_x, &v);
      const Eigen::VectorXd params = net.params().cast<double>();
      const Eigen::MatrixXd xd = x.cast<double>();
      const auto loss = [&](const Eigen::VectorXd& p, const Eigen::MatrixXd& input) {
        Eigen::MatrixXd hidden;
        const Eigen::MatrixXd y = test::mlp_forward(net, p, input, &hidden);
        return (y.array() * weights.cast<double>().array()).sum() +
               (hidden.array() * v.cast<double>().array()).sum();
      };
      {
        INFO("parameter gradient");
        require_grad_close(
            net.grads().cast<double>(),
            numeric_gradient([&](const Eigen::VectorXd& p) { return loss(p, xd); }, params));
      }
      {
        INFO("input gradient");
        const auto loss_of_input = [&](const Eigen::VectorXd& xv) {
          return loss(params, Eigen::Map<const Eigen::MatrixXd>(xv.data(), 4, batch));
        };
        require_grad_close(flat(grad_x), numeric_gradient(loss_of_input, flat(x)));
      }
    }
  }
}

TEST_CASE("Mlp backward accumulates into grads", "[nn]") {
  Rng rng(3);
  Mlp net(4, {8}, 2, Activation::kTanh);
  net.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
  const Eigen::MatrixXf x = random_matrix(4, 5, rng);
  const Eigen::MatrixXf g = random_matrix(2, 5, rng);
  net.forward(x);
  net.backward(g);
  const Eigen::VectorXf once = net.grads();
  net.backward(g);
  CHECK(net.grads().isApprox(2.0f * once, 1e-6f));
  net.zero_grad();
  CHECK(net.grads().isZero());
}

TEST_CASE("Mlp backward reads a strided grad_output and any batch size", "[nn]") {
  Rng rng(8);
  Mlp net(6, {32, 16}, 3, Activation::kTanh);
  net.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
  const Eigen::MatrixXf x = random_matrix(6, 10, rng);
  const Eigen::MatrixXf big = random_matrix(5, 10, rng);  // rows 1..3 are the gradient
  const Eigen::MatrixXf g = big.middleRows(1, 3);
  net.forward(x);
  Eigen::MatrixXf gx_strided, gx_plain;
  net.backward(big.middleRows(1, 3), &gx_strided);
  const Eigen::VectorXf strided = net.grads();
  net.zero_grad();
  net.backward(g, &gx_plain);
  CHECK(net.grads() == strided);
  CHECK(gx_plain == gx_strided);

  // Column by column (batch 1, other code paths) sums to the batched gradient.
  const Eigen::VectorXf batched = net.grads();
  net.zero_grad();
  Eigen::MatrixXf gx_col;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    net.forward(x.col(j));
    net.backward(g.col(j), &gx_col);
    CHECK(gx_col.isApprox(gx_plain.col(j), 1e-5f));
  }
  CHECK(net.grads().isApprox(batched, 1e-5f));
}

TEST_CASE("Mlp backward_input gives backward's input gradient and no parameter gradient", "[nn]") {
  // Widths off the packet size (TD3's 300-wide layer among them) and both input-gradient paths
  // (batch 2: dot products; larger: transposed weights).
  struct Shape {
    int in;
    std::vector<int> hidden;
    Activation act;
    int batch;
    int first;
  };
  const std::vector<Shape> shapes = {{4, {400, 300}, Activation::kReLU, 19, 3},
                                     {13, {13, 9}, Activation::kTanh, 2, 0},
                                     {20, {16}, Activation::kTanh, 40, 5},
                                     {11, {8, 8}, Activation::kReLU, 7, 10}};
  Rng rng(41);
  for (const Shape& sh : shapes) {
    INFO("in " << sh.in << " batch " << sh.batch << " first " << sh.first);
    Mlp net(sh.in, sh.hidden, 1, sh.act);
    net.init_torch_default(rng);
    const Eigen::MatrixXf x = random_matrix(sh.in, sh.batch, rng);
    const Eigen::MatrixXf g = random_matrix(1, sh.batch, rng);
    net.forward(x);
    Eigen::MatrixXf full, part;
    net.zero_grad();
    net.backward(g, &full);
    const Eigen::VectorXf grads = net.grads();
    net.backward_input(g, part, sh.first);
    CHECK(net.grads() == grads);  // unchanged
    REQUIRE(part.rows() == sh.in - sh.first);
    REQUIRE(part.cols() == sh.batch);
    CHECK(part.isApprox(full.bottomRows(sh.in - sh.first), 1e-5f));
  }
  Mlp net(3, {4}, 1, Activation::kReLU);
  net.forward(Eigen::MatrixXf::Ones(3, 2));
  Eigen::MatrixXf gx;
  CHECK_THROWS_AS(net.backward_input(Eigen::MatrixXf::Ones(1, 2), gx, 3), std::invalid_argument);
}

TEST_CASE("Mlp layout, copies and buffer reuse", "[nn]") {
  Mlp net(3, {4, 5}, 2, Activation::kReLU);
  CHECK(net.in_dim() == 3);
  CHECK(net.out_dim() == 2);
  CHECK(net.num_layers() == 3);
  CHECK(net.hidden() == std::vector<int>{4, 5});
  CHECK(net.activation() == Activation::kReLU);
  CHECK(net.num_params() == 4 * 3 + 4 + 5 * 4 + 5 + 2 * 5 + 2);
  CHECK(net.grads().size() == net.num_params());
  const ParamBlock block = net.block();
  CHECK(block.value == net.params().data());
  CHECK(block.grad == net.grads().data());
  CHECK(block.size == net.num_params());

  // weight(l) is an (out x in) column-major view at the documented offset.
  net.params().setLinSpaced(net.num_params(), 0.0f, static_cast<float>(net.num_params() - 1));
  CHECK(net.weight(0).rows() == 4);
  CHECK(net.weight(0).cols() == 3);
  CHECK(net.weight(0)(1, 2) == 2 * 4 + 1);
  CHECK(net.bias(0)(0) == 12);
  CHECK(net.weight(1)(0, 0) == 16);
  CHECK(net.bias(2)(1) == net.num_params() - 1);

  Rng rng(5);
  net.init_orthogonal(rng, std::sqrt(2.0f), 0.01f);
  Mlp copy = net;
  const Eigen::MatrixXf x = random_matrix(3, 6, rng);
  CHECK(copy.forward(x) == net.forward(x));
  copy.params().array() += 1.0f;  // the copy owns its parameters
  CHECK_FALSE(copy.forward(x) == net.forward(x));
  copy.params() = net.params();  // target.params() = online.params()
  CHECK(copy.forward(x) == net.forward(x));

  // Same batch size: the output buffer is reused. Batch-1 forward matches the batch columns.
  const float* data = net.forward(x).data();
  CHECK(net.forward(x).data() == data);
  const Eigen::MatrixXf batched = net.forward(x);
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    CHECK(net.forward(x.col(j)).isApprox(batched.col(j), 1e-5f));
  }
  CHECK_THROWS_AS(net.forward(Eigen::MatrixXf::Zero(2, 3)), std::invalid_argument);
  CHECK_THROWS_AS(Mlp(3, {0}, 2, Activation::kTanh), std::invalid_argument);
}

TEST_CASE("Mlp init_orthogonal gives (semi-)orthogonal weights and zero biases", "[nn]") {
  Rng rng(42);
  Mlp net(4, {64, 64}, 2, Activation::kTanh);
  net.bias(1).setOnes();
  const float hidden_gain = std::sqrt(2.0f);
  const float output_gain = 0.01f;
  net.init_orthogonal(rng, hidden_gain, output_gain);
  for (int l = 0; l < net.num_layers(); ++l) {
    const Eigen::MatrixXf w = net.weight(l);
    const float gain = l + 1 < net.num_layers() ? hidden_gain : output_gain;
    // rows <= cols: orthonormal rows (W W^T), else orthonormal columns (W^T W).
    const Eigen::MatrixXf gram = w.rows() <= w.cols() ? Eigen::MatrixXf(w * w.transpose())
                                                      : Eigen::MatrixXf(w.transpose() * w);
    const Eigen::MatrixXf expected =
        gain * gain * Eigen::MatrixXf::Identity(gram.rows(), gram.cols());
    INFO("layer " << l << " (" << w.rows() << " x " << w.cols() << ")");
    CHECK((gram - expected).cwiseAbs().maxCoeff() < 1e-4f * gain * gain);
    CHECK(net.bias(l).isZero());
  }
  // Square, wide and tall single layers; different draws from different seeds.
  for (const auto& [rows, cols] : std::vector<std::pair<int, int>>{{7, 7}, {3, 10}, {10, 3}}) {
    Mlp layer(cols, {}, rows, Activation::kTanh);
    layer.init_orthogonal(rng, 1.0f, 1.0f);
    const Eigen::MatrixXf w = layer.weight(0);
    const Eigen::MatrixXf gram =
        rows <= cols ? Eigen::MatrixXf(w * w.transpose()) : Eigen::MatrixXf(w.transpose() * w);
    CHECK(gram.isApprox(Eigen::MatrixXf::Identity(gram.rows(), gram.cols()), 1e-5f));
  }
  Rng a(1), b(1), c(2);
  Mlp na(3, {5}, 2, Activation::kTanh), nb = na, nc = na;
  na.init_orthogonal(a, 1.0f, 1.0f);
  nb.init_orthogonal(b, 1.0f, 1.0f);
  nc.init_orthogonal(c, 1.0f, 1.0f);
  CHECK(na.params() == nb.params());
  CHECK_FALSE(na.params() == nc.params());
}

TEST_CASE("Mlp init_torch_default draws U(-1/sqrt(fan_in), 1/sqrt(fan_in))", "[nn]") {
  Rng rng(77);
  Mlp net(16, {256}, 4, Activation::kReLU);
  net.init_torch_default(rng);
  for (int l = 0; l < net.num_layers(); ++l) {
    const double bound = 1.0 / std::sqrt(static_cast<double>(net.layer_in(l)));
    const Eigen::VectorXd w = flat(net.weight(l));
    INFO("layer " << l);
    CHECK(w.cwiseAbs().maxCoeff() <= bound);
    CHECK(net.bias(l).cwiseAbs().maxCoeff() <= bound);
    CHECK_FALSE(net.bias(l).isZero());
    // Uniform variance bound^2 / 3; 1024 or 4096 draws give a few percent accuracy.
    const double var = w.array().square().mean();
    CHECK(var == Approx(bound * bound / 3.0).epsilon(0.1));
    CHECK(std::abs(w.mean()) < 4.0 * bound / std::sqrt(3.0 * w.size()));
  }
}

TEST_CASE("parse_activation and activation_name", "[nn]") {
  CHECK(parse_activation("tanh") == Activation::kTanh);
  CHECK(parse_activation("relu") == Activation::kReLU);
  CHECK(parse_activation("elu") == Activation::kELU);
  CHECK(parse_activation("leaky_relu") == Activation::kLeakyReLU);
  CHECK(parse_activation("gelu") == Activation::kGELU);
  // rl-zoo's policy_kwargs spell the torch class.
  CHECK(parse_activation("nn.Tanh") == Activation::kTanh);
  CHECK(parse_activation("nn.ReLU") == Activation::kReLU);
  CHECK(parse_activation("nn.ELU") == Activation::kELU);
  CHECK(parse_activation("nn.LeakyReLU") == Activation::kLeakyReLU);
  CHECK(parse_activation("nn.GELU") == Activation::kGELU);
  CHECK(activation_name(Activation::kTanh) == "tanh");
  CHECK(activation_name(Activation::kReLU) == "relu");
  CHECK(activation_name(Activation::kELU) == "elu");
  CHECK(activation_name(Activation::kLeakyReLU) == "leaky_relu");
  CHECK(activation_name(Activation::kGELU) == "gelu");
  CHECK_THROWS_AS(parse_activation("Tanh"), std::invalid_argument);
  CHECK_THROWS_AS(parse_activation("nn.Gelu"), std::invalid_argument);
  CHECK_THROWS_WITH(parse_activation("swish"),
                    Catch::Contains("valid: tanh, relu, elu, leaky_relu, gelu (or torch's "
                                    "nn.Tanh, nn.ReLU, nn.ELU, nn.LeakyReLU, nn.GELU)"));
  CHECK_THROWS_AS(parse_activation("nn.relu"), std::invalid_argument);
  CHECK_THROWS_AS(parse_activation("sigmoid"), std::invalid_argument);
}

}  // namespace
}  // namespace rlrun
