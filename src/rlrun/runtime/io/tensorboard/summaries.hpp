#pragma once
// The Event messages rlrun writes into TensorBoard event files (field numbers from
// tensorboard/compat/proto/event.proto and summary.proto, and the HParams plugin's
// tensorboard/plugins/hparams/plugin_data.proto and api.proto):
//   * scalars: one Event per progress.csv row, step = num_timesteps, one Summary.Value
//     {tag, simple_value} per key, as SB3's TensorBoardOutputFormat writes them through
//     PyTorch's SummaryWriter.add_scalar (simple_value, no metadata);
//   * the HParams plugin's session start (the run's hyperparameters) and session end (its
//     status), each a Summary.Value with plugin_data "hparams" and an empty float tensor,
//     as tensorboard.plugins.hparams.summary_v2 writes them. No experiment summary: TensorBoard
//     then takes the union of the runs' hyperparameters and lists every scalar tag as a metric,
//     so runs of different algorithms in one log directory all show.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/protobuf_writer.hpp"

namespace rlrun {

ProtoWriter scalars_event(double wall_time, int64_t step, const LogRow& row);

using HParamValue = std::variant<double, bool, std::string>;
struct HParam {
  std::string name;  // dotted config path, "algo.learning_rate"
  HParamValue value;
};

// The resolved config's values as hyperparameters: every scalar by its dotted path, numbers
// as numbers, true/false as booleans, other text as strings, short lists of scalars as their
// text ("[64, 64]"); nulls and nested lists are left out.
std::vector<HParam> hparams_of_config(const YAML::Node& config);

// A PNG image (Summary.Image {height = 1, width = 2, colorspace = 3, encoded_image_string = 4};
// colorspace 3 = RGB), for TensorBoard's Images tab.
ProtoWriter image_event(double wall_time, int64_t step, const std::string& tag,
                        const std::string& png, int width, int height);

ProtoWriter session_start_event(double wall_time, const std::vector<HParam>& hparams);
// `success`: the run trained to its end (STATUS_SUCCESS); else STATUS_FAILURE.
ProtoWriter session_end_event(double wall_time, int64_t step, bool success);

}  // namespace rlrun
