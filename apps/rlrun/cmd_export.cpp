// rlrun export --model FILE --format onnx --output policy.onnx [--with-value] [--set k=v]... [--trust]
// rlrun export --model FILE --format c --output DIR        (DIR/policy.c, DIR/policy.h)
// rlrun export --model FILE --format sb3 --output model.zip (Stable-Baselines3's model file)
// The model's deterministic policy as a file that runs without rlrun (deploy/): the env's
// observation in, the env's action out, as `rlrun eval` acts (docs/deploy.md).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "model_player.hpp"
#include "plugin_option.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/deploy/c_writer.hpp"
#include "rlrun/deploy/onnx_writer.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/io/sb3/sb3_model_writer.hpp"
#include "trust_option.hpp"

namespace rlrun::cli {

namespace {

struct ExportOptions {
  std::string model;
  std::string env_id;  // --env: the env of an SB3 model file (it does not record one)
  std::string format = "onnx";
  std::string output;
  bool with_value = false;
  std::vector<std::string> plugins;
  std::vector<std::string> overrides;  // --set: the user's values over the model's config
  bool trust = false;                  // --trust: run what the model file names
};

// The output's directory must exist: exporting never creates directories (a typo in a path
// should not leave a tree behind).
void check_output_directory(const std::string& output) {
  const std::filesystem::path parent = std::filesystem::path(output).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw RuntimeFailure("cannot write " + output + ": the directory " + parent.string() +
                         " does not exist");
}

// The model as SB3's model file (runtime/io/sb3/sb3_model_writer.hpp).
int export_sb3(const LoadedModel& model, const std::string& path, const std::string& output) {
  const Sb3ModelExport sb3 = sb3_model_export(model);
  write_zip_atomic(output, sb3.members);
  const std::string algorithm = quoted_text(model.file.meta.algorithm);
  std::printf(
      "exported %s (%s on %s) to %s: a Stable-Baselines3 %s model file; in Python: "
      "%s.load(\"%s\")\n",
      path.c_str(), algorithm.c_str(), quoted_text(model.file.meta.env_id).c_str(), output.c_str(),
      kSb3FormatVersion, sb3.load_class.c_str(), output.c_str());
  for (const std::string& note : sb3.notes) std::printf("note: %s\n", note.c_str());
  return 0;
}

}  // namespace

Action add_export(CLI::App& app, Registry& registry) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export",
                                     "write a trained model's deterministic policy as an ONNX file "
                                     "or C99 source (docs/deploy.md)");
  sub->add_option("--model", o->model, "the model file (model.zip, best_model.zip, a checkpoint)")
      ->required();
  sub->add_option("--format", o->format,
                  "onnx (one file), c (a directory with policy.c and policy.h, C99) or sb3 (a "
                  "Stable-Baselines3 model.zip that PPO.load(...) etc. open: docs/sb3_models.md)")
      ->check(CLI::IsMember({"onnx", "c", "sb3"}));
  sub->add_option(
         "-o,--output", o->output,
         "the file to write (onnx: e.g. policy.onnx; sb3: e.g. model.zip) or the directory (c; "
         "created if its parent exists)")
      ->required();
  sub->add_flag(
      "--with-value", o->with_value,
      "onnx: add a second output `value`: V(s) for PPO/A2C, every Q-value for DQN, the first "
      "critic's Q(s, action) for SAC/TD3/DDPG, mean quantile for TQC");
  sub->add_option("--env", o->env_id,
                  "the env the model acts in: needed for an SB3 model file, which does not "
                  "record it (docs/sb3_models.md)");
  add_plugin_option(sub, o->plugins);
  sub->add_option("--set", o->overrides,
                  "override a value of the model's config (a model file is untrusted: this is "
                  "how you vouch for a program or file it names; repeatable)")
      ->allow_extra_args(false);
  add_trust_option(sub, o->trust);
  return [o, &registry]() {
    load_plugin_options(o->plugins, registry);
    check_output_directory(o->output);
    add_model_env_override(o->env_id, o->overrides);
    // The policy graph is built on the model's env stack (its wrappers' exports) over the env's
    // spaces as the file records them: no env is built, so none of its code runs.
    const LoadedModel model =
        load_model(o->model, registry, o->overrides, model_trust(o->trust, o->model, registry),
                   ModelEnv::kSpacesOnly);
    if (o->format == "sb3") return export_sb3(model, o->model, o->output);
    // The whole output is made before anything is written: a refusal leaves nothing behind.
    PolicyGraph graph;
    CSource c;
    std::string onnx;
    try {
      graph = build_model_graph(model, o->with_value);
      if (o->format == "c")
        c = c_policy_source(graph);
      else
        onnx = onnx_model_bytes(graph);
    } catch (const ExportError& e) {
      throw RuntimeFailure("cannot export " + o->model + ": " + e.what());
    }
    // A pixel policy's graph starts at the wrapper that renders or stacks frames.
    const auto input = graph.metadata.find("observation_input");
    if (input != graph.metadata.end())
      std::printf("note: the exported policy reads %s\n", input->second.c_str());
    // MaskablePPO: the graph has no mask input (docs/maskable_ppo.md).
    if (model.algorithm->action_mask_size() > 0)
      std::printf(
          "note: the exported policy takes no action masks: it returns the argmax over all "
          "actions, as predict() without action_masks\n");
    // meta.json's text is the model file's: quoted (one printable line) when printed.
    const std::string algorithm = quoted_text(model.file.meta.algorithm);
    const std::string env_id = quoted_text(model.file.meta.env_id);
    if (o->format == "c") {
      std::error_code ec;
      std::filesystem::create_directory(o->output, ec);
      if (!std::filesystem::is_directory(o->output, ec))
        throw RuntimeFailure("cannot write " + o->output + ": not a directory");
      write_text_atomic((std::filesystem::path(o->output) / "policy.h").string(), c.header);
      write_text_atomic((std::filesystem::path(o->output) / "policy.c").string(), c.source);
      const std::string state =
          graph.state_width() > 0 ? "state[" + std::to_string(graph.state_width()) + "], " : "";
      std::printf(
          "exported %s (%s on %s) to %s/policy.c and policy.h: policy_act(obs[%d], %saction[%d])\n",
          o->model.c_str(), algorithm.c_str(), env_id.c_str(), o->output.c_str(),
          graph.observation_width(), state.c_str(), graph.width(graph.action()));
      return 0;
    } else {
      write_text_atomic(o->output, onnx);
    }
    std::string inputs;  // Dict keys come from the model file: quoted
    for (const GraphInput& in : graph.inputs())
      inputs += (inputs.empty() ? "" : ", ") + quoted_text(in.name) + " [batch, " +
                std::to_string(in.width) + "]";
    std::string outputs = "action [batch, " + std::to_string(graph.width(graph.action())) + "]";
    if (!graph.value().empty())
      outputs += ", value [batch, " + std::to_string(graph.width(graph.value())) + "]";
    if (graph.state_width() > 0) {
      const std::string state = " [batch, " + std::to_string(graph.state_width()) + "]";
      inputs += std::string(", ") + PolicyGraph::kStateInput + state;
      outputs += std::string(", ") + PolicyGraph::kStateOutput + state;
    }
    std::printf("exported %s (%s on %s) to %s: inputs %s; outputs %s\n", o->model.c_str(),
                algorithm.c_str(), env_id.c_str(), o->output.c_str(), inputs.c_str(),
                outputs.c_str());
    if (graph.state_width() > 0)
      std::printf(
          "note: the policy is recurrent: feed %s back as %s at the next step, zeros at the "
          "start of every episode\n",
          PolicyGraph::kStateOutput, PolicyGraph::kStateInput);
    return 0;
  };
}

}  // namespace rlrun::cli
