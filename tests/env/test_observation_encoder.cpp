// ObservationEncoder: SB3's preprocess_obs + Flatten/CombinedExtractor on rlrun's flat
// observations, for every space kind.
#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/env/observation_encoder.hpp"

using namespace rlrun;

namespace {

std::vector<float> encode(const ObservationEncoder& encoder, std::vector<float> obs) {
  std::vector<float> out(static_cast<size_t>(encoder.features_dim()));
  encoder.encode_sample(obs, out);
  return out;
}

}  // namespace

TEST_CASE("observation encoder: Box and MultiBinary are the identity, without a copy",
          "[env][space]") {
  for (const Space& space :
       {Space::box(-1.0f, 1.0f, {3}), Space::multi_binary(4),
        Space::dict({{"b", Space::box(0.0f, 1.0f, {2})}, {"a", Space::multi_binary(2)}})}) {
    INFO(space.describe());
    ObservationEncoder encoder(space);
    CHECK(encoder.identity());
    CHECK(encoder.input_dim() == space.flat_dim());
    CHECK(encoder.features_dim() == space.flat_dim());
    const Eigen::MatrixXf obs = Eigen::MatrixXf::Random(space.flat_dim(), 5);
    const Eigen::Ref<const Eigen::MatrixXf> features = encoder(obs);
    CHECK(features.data() == obs.data());
    CHECK(features == obs);
  }
}

TEST_CASE("observation encoder: Discrete and MultiDiscrete become one-hots (SB3 preprocess_obs)",
          "[env][space]") {
  const ObservationEncoder discrete(Space::discrete(3, 1));  // values 1, 2, 3
  CHECK_FALSE(discrete.identity());
  CHECK(discrete.input_dim() == 1);
  CHECK(discrete.features_dim() == 3);
  CHECK(encode(discrete, {1}) == std::vector<float>{1, 0, 0});
  CHECK(encode(discrete, {3}) == std::vector<float>{0, 0, 1});
  CHECK_THROWS_AS(encode(discrete, {0}), std::out_of_range);
  CHECK_THROWS_AS(encode(discrete, {4}), std::out_of_range);

  const ObservationEncoder multi(Space::multi_discrete({2, 3}));
  CHECK(multi.features_dim() == 5);
  CHECK(encode(multi, {1, 0}) == std::vector<float>{0, 1, 1, 0, 0});
  CHECK(encode(multi, {0, 2}) == std::vector<float>{1, 0, 0, 0, 1});
  CHECK_THROWS_AS(encode(multi, {0, 3}), std::out_of_range);
}

TEST_CASE("observation encoder: a Dict is each key encoded, in sorted key order, concatenated",
          "[env][space]") {
  // Keys sorted: a (Discrete 3), b (Box 2), c (MultiDiscrete [2 2]), d (MultiBinary 2).
  const Space space = Space::dict({{"d", Space::multi_binary(2)},
                                   {"b", Space::box(-5.0f, 5.0f, {2})},
                                   {"c", Space::multi_discrete({2, 2})},
                                   {"a", Space::discrete(3)}});
  ObservationEncoder encoder(space);
  CHECK_FALSE(encoder.identity());
  CHECK(encoder.input_dim() == 7);
  CHECK(encoder.features_dim() == 3 + 2 + 4 + 2);
  const std::vector<float> obs{2, -1.5f, 4.0f, 1, 0, 1, 1};
  REQUIRE(space.contains(obs));
  const std::vector<float> expected{0, 0, 1, -1.5f, 4.0f, 0, 1, 1, 0, 1, 1};
  CHECK(encode(encoder, obs) == expected);

  std::vector<float> decoded(obs.size());
  encoder.decode_sample(expected, decoded);
  CHECK(decoded == obs);

  // The batch forms agree with the sample form, for any batch size (the workspace grows).
  for (int batch : {3, 1, 4}) {
    Eigen::MatrixXf many(7, batch);
    for (int j = 0; j < batch; ++j) many.col(j) = Eigen::Map<const Eigen::VectorXf>(obs.data(), 7);
    many(0, batch - 1) = 0;
    const Eigen::Ref<const Eigen::MatrixXf> features = encoder(many);
    Eigen::MatrixXf copy;
    encoder.encode(many, copy);
    REQUIRE(features.cols() == batch);
    CHECK(features == copy);
    // Into the top rows of a (features; action) critic input.
    Eigen::MatrixXf critic_input = Eigen::MatrixXf::Constant(11 + 2, batch, 7.0f);
    encoder.encode_into(many, critic_input.topRows(11));
    CHECK(critic_input.topRows(11) == copy);
    CHECK((critic_input.bottomRows(2).array() == 7.0f).all());
    CHECK(features(2, 0) == (batch > 1 ? 1.0f : 0.0f));
    CHECK(features(0, batch - 1) == 1.0f);
  }

  // The message names the key and its space.
  std::vector<float> bad = obs;
  bad[3] = 2;  // c[0] in MultiDiscrete([2 2])
  try {
    encode(encoder, bad);
    FAIL("no exception");
  } catch (const std::out_of_range& e) {
    const std::string what = e.what();
    CHECK(what.find("key 'c'") != std::string::npos);
    CHECK(what.find("MultiDiscrete([2 2])") != std::string::npos);
  }
}

TEST_CASE("observation encoder: normalize_images divides images by 255 (SB3 preprocess_obs)",
          "[env][space][image]") {
  // SB3: `obs.float() / 255.0` for a Box that is_image_space (3 dimensions, uint8, bounds 0-255), for
  // every policy; other Boxes, and every Box without normalize_images, pass as they are.
  const Space image = Space::image({2, 3, 1});
  ObservationEncoder encoder(image, true);
  CHECK_FALSE(encoder.identity());
  const std::vector<float> pixels{0, 1, 17, 128, 254, 255};
  const std::vector<float> features = encode(encoder, pixels);
  for (size_t k = 0; k < pixels.size(); ++k) CHECK(features[k] == pixels[k] / 255.0f);
  std::vector<float> back(pixels.size());
  encoder.decode_sample(features, back);
  for (size_t k = 0; k < pixels.size(); ++k) CHECK(back[k] == Approx(pixels[k]));
  CHECK(ObservationEncoder(image, false).identity());
  // Not images: two dimensions (a gray frame without keep_dim), other bounds, float32 pixels
  // (SB3 asks for dtype uint8).
  CHECK(ObservationEncoder(Space::image({4, 4}), true).identity());
  CHECK(ObservationEncoder(Space::box(0.0f, 1.0f, {2, 3, 1}), true).identity());
  CHECK(ObservationEncoder(Space::box(0.0f, 1.0f, {2, 3, 1}, BoxDtype::kUint8), true).identity());
  CHECK(ObservationEncoder(Space::box(0.0f, 255.0f, {2, 3, 1}), true).identity());
  // A Dict: the image key divided, the vector key (sorted after it) as it is.
  const Space dict = Space::dict({{"state", Space::box(-5.0f, 5.0f, {2})}, {"pixels", image}});
  const std::vector<float> both =
      encode(ObservationEncoder(dict, true), {10, 20, 30, 40, 50, 255, -3, 4});
  CHECK(both == std::vector<float>{10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 40 / 255.0f, 50 / 255.0f,
                                   1.0f, -3, 4});
}
