#include "rlrun/runtime/io/tensorboard/summaries.hpp"

#include <cstdlib>

namespace rlrun {

namespace {

// Event fields.
constexpr int kWallTime = 1, kStep = 2, kSummary = 5;
// Summary.value; Summary.Value fields.
constexpr int kSummaryValue = 1, kTag = 1, kSimpleValue = 2, kTensor = 8, kMetadata = 9;

ProtoWriter event(double wall_time, int64_t step, const ProtoWriter& summary) {
  ProtoWriter e;
  e.float64(kWallTime, wall_time);
  if (step != 0) e.int64(kStep, step);
  e.message(kSummary, summary);
  return e;
}

// A Summary with one value that carries HParamsPluginData `content` (summary_v2's form).
ProtoWriter hparams_summary(const std::string& tag, const ProtoWriter& plugin_data) {
  ProtoWriter plugin;  // SummaryMetadata.PluginData {plugin_name = 1, content = 2}
  plugin.bytes(1, "hparams").bytes(2, plugin_data.str());
  ProtoWriter metadata;  // SummaryMetadata {plugin_data = 1}
  metadata.message(1, plugin);
  // hparams' NULL_TENSOR: DT_FLOAT (1), shape [0] (TensorProto {dtype = 1, tensor_shape = 2};
  // TensorShapeProto {dim = 2}; a Dim of size 0 has no fields).
  ProtoWriter shape;
  shape.message(2, ProtoWriter());
  ProtoWriter tensor;
  tensor.varint(1, 1).message(2, shape);
  ProtoWriter value;
  value.bytes(kTag, tag).message(kMetadata, metadata).message(kTensor, tensor);
  ProtoWriter summary;
  summary.message(kSummaryValue, value);
  return summary;
}

// google.protobuf.Value {number_value = 2, string_value = 3, bool_value = 4}.
ProtoWriter protobuf_value(const HParamValue& v) {
  ProtoWriter out;
  if (const double* d = std::get_if<double>(&v)) out.float64(2, *d);
  if (const std::string* s = std::get_if<std::string>(&v)) out.bytes(3, *s);
  if (const bool* b = std::get_if<bool>(&v)) out.boolean(4, *b);
  return out;
}

std::string scalar_text(const YAML::Node& node) { return node.Scalar(); }

void flatten(const YAML::Node& node, const std::string& path, std::vector<HParam>& out) {
  constexpr size_t kMaxText = 250;  // TensorBoard's table shows short values
  if (node.IsMap()) {
    for (const auto& item : node)
      flatten(item.second, path.empty() ? item.first.Scalar() : path + "." + item.first.Scalar(),
              out);
    return;
  }
  if (node.IsSequence()) {
    std::string text = "[";
    for (size_t i = 0; i < node.size(); ++i) {
      if (!node[i].IsScalar()) return;  // a list of maps (wrappers) is left out
      text += (i ? ", " : "") + scalar_text(node[i]);
    }
    text += "]";
    if (text.size() <= kMaxText) out.push_back({path, text});
    return;
  }
  if (!node.IsScalar()) return;  // null
  const std::string text = node.Scalar();
  if (node.Tag() != "!") {  // not quoted: a number or a boolean may hide in the text
    if (text == "true" || text == "True") return out.push_back({path, true});
    if (text == "false" || text == "False") return out.push_back({path, false});
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (!text.empty() && end == text.c_str() + text.size()) return out.push_back({path, number});
  }
  if (text.size() <= kMaxText) out.push_back({path, text});
}

}  // namespace

ProtoWriter scalars_event(double wall_time, int64_t step, const LogRow& row) {
  ProtoWriter summary;
  for (const auto& [key, value] : row) {
    ProtoWriter v;
    v.bytes(kTag, key).float32(kSimpleValue, static_cast<float>(value));
    summary.message(kSummaryValue, v);
  }
  return event(wall_time, step, summary);
}

ProtoWriter image_event(double wall_time, int64_t step, const std::string& tag,
                        const std::string& png, int width, int height) {
  ProtoWriter image;
  image.int64(1, height).int64(2, width).int64(3, 3).bytes(4, png);
  ProtoWriter value;
  value.bytes(kTag, tag).message(4, image);  // Summary.Value.image = 4
  ProtoWriter summary;
  summary.message(kSummaryValue, value);
  return event(wall_time, step, summary);
}

std::vector<HParam> hparams_of_config(const YAML::Node& config) {
  std::vector<HParam> out;
  flatten(config, "", out);
  return out;
}

ProtoWriter session_start_event(double wall_time, const std::vector<HParam>& hparams) {
  ProtoWriter start;  // SessionStartInfo {hparams = 1 (map entries {key = 1, value = 2}),
                      //                   start_time_secs = 5}
  for (const HParam& h : hparams) {
    ProtoWriter entry;
    entry.bytes(1, h.name).message(2, protobuf_value(h.value));
    start.message(1, entry);
  }
  start.float64(5, wall_time);
  ProtoWriter data;  // HParamsPluginData {version = 1 (0), session_start_info = 3}
  data.message(3, start);
  return event(wall_time, 0, hparams_summary("_hparams_/session_start_info", data));
}

ProtoWriter session_end_event(double wall_time, int64_t step, bool success) {
  ProtoWriter end;  // SessionEndInfo {status = 1 (STATUS_SUCCESS 1, STATUS_FAILURE 2),
                    //                 end_time_secs = 2}
  end.varint(1, success ? 1 : 2).float64(2, wall_time);
  ProtoWriter data;  // HParamsPluginData {session_end_info = 4}
  data.message(4, end);
  return event(wall_time, step, hparams_summary("_hparams_/session_end_info", data));
}

}  // namespace rlrun
