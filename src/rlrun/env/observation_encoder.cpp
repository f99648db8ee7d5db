#include "rlrun/env/observation_encoder.hpp"

#include "rlrun/env/image_space.hpp"
#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rlrun {

namespace {
// A network input wider than this is a configuration mistake (Discrete(10^9) observations),
// not something to allocate.
constexpr int64_t kMaxFeatures = int64_t{1} << 24;
}  // namespace

ObservationEncoder::ObservationEncoder(const Space& observation_space, bool normalize_images) {
  if (observation_space.is_dict()) {
    for (size_t i = 0; i < observation_space.keys().size(); ++i)
      add_space(observation_space.subspaces()[i], observation_space.keys()[i], normalize_images);
  } else {
    add_space(observation_space, "", normalize_images);
  }
}

void ObservationEncoder::add_space(const Space& space, const std::string& key,
                                   bool normalize_images) {
  const int index = static_cast<int>(spaces_.size());
  spaces_.emplace_back(key, space.describe());
  const auto add = [&](int width, bool one_hot, bool image, int64_t start, int entry) {
    if (features_dim_ + static_cast<int64_t>(width) > kMaxFeatures)
      throw std::invalid_argument("observation space " + space.describe() +
                                  " encodes to more than " + std::to_string(kMaxFeatures) +
                                  " network inputs");
    // Consecutive floats copied alike form one run.
    const bool plain = !one_hot && !image;
    if (plain && !pieces_.empty() && !pieces_.back().one_hot && !pieces_.back().image &&
        pieces_.back().in + pieces_.back().width == input_dim_) {
      pieces_.back().width += width;
    } else {
      pieces_.push_back({input_dim_, features_dim_, width, one_hot, image, start, entry, index});
    }
    input_dim_ += one_hot ? 1 : width;
    features_dim_ += width;
    identity_ = identity_ && plain;
  };
  switch (space.kind()) {
    case SpaceKind::kBox:
      if (space.flat_dim() > 0)
        add(space.flat_dim(), false, normalize_images && image_input(space, true).has_value(), 0,
            0);
      break;
    case SpaceKind::kMultiBinary:
      if (space.flat_dim() > 0) add(space.flat_dim(), false, false, 0, 0);
      break;
    case SpaceKind::kDiscrete:
      if (space.n() > kMaxFeatures)
        throw std::invalid_argument("observation space " + space.describe() +
                                    " is too large for a one-hot network input");
      add(static_cast<int>(space.n()), true, false, space.start(), 0);
      break;
    case SpaceKind::kMultiDiscrete:
      for (size_t i = 0; i < space.nvec().size(); ++i) {
        if (space.nvec()[i] > kMaxFeatures)
          throw std::invalid_argument("observation space " + space.describe() +
                                      " is too large for a one-hot network input");
        add(static_cast<int>(space.nvec()[i]), true, false, 0, static_cast<int>(i));
      }
      break;
    case SpaceKind::kDict:
      throw std::invalid_argument("observation space: a Dict inside a Dict is not supported");
  }
}

void ObservationEncoder::fail(const Piece& piece, float value) const {
  const auto& [key, text] = spaces_[static_cast<size_t>(piece.space)];
  std::string where = key.empty() ? "" : "key '" + key + "' ";
  throw std::out_of_range("observation " + where + "entry " + std::to_string(piece.entry) + " is " +
                          std::to_string(value) + ", not a value of " + text);
}

void ObservationEncoder::encode_sample(std::span<const float> obs, std::span<float> out) const {
  if (static_cast<int>(obs.size()) != input_dim_ || static_cast<int>(out.size()) != features_dim_)
    throw std::invalid_argument(
        "ObservationEncoder: " + std::to_string(obs.size()) + " -> " + std::to_string(out.size()) +
        " floats, expected " + std::to_string(input_dim_) + " -> " + std::to_string(features_dim_));
  for (const Piece& p : pieces_) {
    float* dst = out.data() + p.out;
    if (p.image) {  // SB3 preprocess_obs: obs.float() / 255.0, a float32 division
      for (int k = 0; k < p.width; ++k) dst[k] = obs[static_cast<size_t>(p.in + k)] / 255.0f;
      continue;
    }
    if (!p.one_hot) {
      std::copy_n(obs.data() + p.in, p.width, dst);
      continue;
    }
    const float value = obs[static_cast<size_t>(p.in)];
    // SB3 casts with obs.long(); values are integers, lround forgives float noise.
    const double slot = std::round(static_cast<double>(value)) - static_cast<double>(p.start);
    if (!(slot >= 0.0 && slot < p.width)) fail(p, value);
    std::fill_n(dst, p.width, 0.0f);
    dst[static_cast<int64_t>(slot)] = 1.0f;
  }
}

std::string ObservationEncoder::export_to(PolicyGraph& graph, const std::string& obs) const {
  if (identity_) return obs;
  std::vector<std::string> parts;
  for (const Piece& p : pieces_) {
    if (p.image) {
      parts.push_back(graph.affine(graph.slice(obs, p.in, p.width), Eigen::VectorXf::Zero(p.width),
                                   Eigen::VectorXf::Constant(p.width, 1.0f / 255.0f),
                                   Eigen::VectorXf::Zero(p.width)));
      continue;
    }
    if (!p.one_hot) {
      parts.push_back(graph.slice(obs, p.in, p.width));
      continue;
    }
    parts.push_back(graph.one_hot(graph.slice(obs, p.in, 1), static_cast<float>(p.start), p.width));
  }
  return graph.concat(parts);
}

void ObservationEncoder::decode_sample(std::span<const float> features,
                                       std::span<float> obs) const {
  for (const Piece& p : pieces_) {
    const float* src = features.data() + p.out;
    if (p.image) {
      for (int k = 0; k < p.width; ++k) obs[static_cast<size_t>(p.in + k)] = src[k] * 255.0f;
      continue;
    }
    if (!p.one_hot) {
      std::copy_n(src, p.width, obs.data() + p.in);
      continue;
    }
    const int64_t hot = std::max_element(src, src + p.width) - src;
    obs[static_cast<size_t>(p.in)] = static_cast<float>(p.start + hot);
  }
}

void ObservationEncoder::encode(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                Eigen::MatrixXf& out) const {
  out.resize(features_dim_, obs.cols());
  encode_into(obs, out);
}

void ObservationEncoder::encode_into(const Eigen::Ref<const Eigen::MatrixXf>& obs,
                                     Eigen::Ref<Eigen::MatrixXf> out) const {
  if (obs.rows() != input_dim_ || out.rows() != features_dim_ || out.cols() != obs.cols())
    throw std::invalid_argument(
        "ObservationEncoder: " + std::to_string(obs.rows()) + " x " + std::to_string(obs.cols()) +
        " observations into " + std::to_string(out.rows()) + " x " + std::to_string(out.cols()) +
        ", expected " + std::to_string(input_dim_) + " rows into " + std::to_string(features_dim_));
  for (Eigen::Index j = 0; j < obs.cols(); ++j)
    encode_sample({obs.col(j).data(), static_cast<size_t>(input_dim_)},
                  {out.col(j).data(), static_cast<size_t>(features_dim_)});
}

Eigen::Ref<const Eigen::MatrixXf> ObservationEncoder::operator()(
    const Eigen::Ref<const Eigen::MatrixXf>& obs) {
  if (identity_) return obs;
  if (workspace_.cols() < obs.cols()) workspace_.resize(features_dim_, obs.cols());
  encode_into(obs, workspace_.leftCols(obs.cols()));
  return workspace_.leftCols(obs.cols());
}

}  // namespace rlrun
