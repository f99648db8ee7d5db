// Fuzz target: reading a model file or checkpoint from arbitrary bytes, as `rlrun eval`,
// `rlrun train --init-from` and `--resume` do (core/zip_reader.hpp, core/npy.hpp,
// runtime/io/model_file.hpp, runtime/io/model_budget.hpp). Refusing is fine (RuntimeFailure,
// ConfigError, UsageError); any other exception, a crash, a sanitizer report, a hang or a large
// allocation is a bug.
//
// Input: byte 0 chooses the form of the rest —
//   even: the zip file itself (libzip's parsing, the member checks, lying headers);
//   odd:  a list of members the harness zips with libzip (so mutations reach meta.json,
//         config.yaml and the npy headers instead of breaking CRCs):
//           [name length: 1][name][flags: 1][data length: 2, LE][data]...
//         flags bit 0: deflate (else store); bit 1: written as a raw deflate stream whose
//         declared size is off by the signed byte that follows the data length (a lie).
// Each zip then goes through: read_zip + decode_npy of every .npy member; load_model (the
// eval path: config -> env + algorithm -> budgeted tensors -> weights, statistics) and one
// predict(), the exports (runtime/io/model_graph.hpp, deploy/); read_checkpoint with the file's own config as the run's, then the trainer's
// load / load_training_state / VecEnv::read_state on fresh objects.

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "../tests/core/crafted_zip.hpp"
#include "fuzz_limits.hpp"
#include "private_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/deploy/c_writer.hpp"
#include "rlrun/deploy/onnx_writer.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/model_budget.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

using namespace rlrun;
using rlrun::testing::CraftedMember;

namespace {

// The odd form (see the top of this file); false when the list is malformed.
bool members_from(const uint8_t* data, size_t size, std::vector<CraftedMember>& members) {
  size_t at = 0;
  const auto take = [&](size_t n) {
    const bool ok = at + n <= size;
    at += n;
    return ok;
  };
  while (at < size) {
    const size_t name_len = data[at++];
    if (name_len == 0 || !take(name_len)) return false;
    CraftedMember m{std::string(reinterpret_cast<const char*>(data + at - name_len), name_len), {}};
    if (!take(3)) return false;
    const uint8_t flags = data[at - 3];
    const size_t length = data[at - 2] | (data[at - 1] << 8);
    int lie = 0;
    if (flags & 2) {
      if (!take(1)) return false;
      lie = static_cast<int8_t>(data[at - 1]);
    }
    if (!take(length)) return false;
    const std::vector<uint8_t> payload(data + at - length, data + at);
    if (m.name.find('\0') != std::string::npos) return false;  // libzip takes C strings
    for (const CraftedMember& other : members)
      if (other.name == m.name) return false;  // libzip refuses duplicates
    if (flags & 2) {
      m.raw = true;
      m.data = rlrun::testing::raw_deflate(payload);
      m.declared_size =
          static_cast<uint64_t>(std::max<int64_t>(0, static_cast<int64_t>(length) + lie));
      m.crc = static_cast<uint32_t>(crc32(0, payload.data(), static_cast<uInt>(payload.size())));
    } else {
      m.data = payload;
      m.deflate = flags & 1;
    }
    members.push_back(std::move(m));
  }
  return true;
}

void read_everything(const std::string& path) {
  try {
    for (const auto& [name, bytes] : read_zip(path, 8 << 20))
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".npy") == 0) {
        try {
          decode_npy(bytes, name);
        } catch (const std::runtime_error&) {
        }
      }
  } catch (const RuntimeFailure&) {
  }
}

// The trainer's resume steps on fresh objects of the file's own configuration.
void resume_like(const std::string& path, const Experiment& experiment, const Registry& registry) {
  const ModelFile checkpoint = read_checkpoint(path, experiment, registry);
  if (!checkpoint.holds_training_state) return;
  const int n_envs = experiment.env.section.n_envs;
  VecEnv env = make_vec_env(experiment.env, registry, n_envs, "");
  share_model_statistics(env);
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), n_envs,
                             experiment.run.seed};
  auto algorithm = make_algorithm(experiment, registry, setup);
  try {  // trainer.cpp reports any of these as "cannot resume from ...: <what>"
    algorithm->load(checkpoint.tensors);
    algorithm->load_training_state(StateReader(checkpoint.training_state, "training/algo/"));
    env.read_state(StateReader(checkpoint.training_state, "training/env/"));
  } catch (const std::exception&) {
  }
}

// `rlrun export` and rlrun::Policy: the policy graph of the loaded model, both writers, and
// the graph run once. Refusing (ExportError: a wrapper or env that cannot be exported) is fine.
void export_like_the_cli(const LoadedModel& loaded) {
  try {
    const PolicyGraph graph = build_model_graph(loaded, /*with_value=*/true);
    (void)onnx_model_bytes(graph);
    (void)c_policy_source(graph);
    std::vector<Eigen::MatrixXf> inputs;
    for (const GraphInput& in : graph.inputs())
      inputs.push_back(Eigen::MatrixXf::Zero(in.width, 1));
    // A recurrent policy (RecurrentPPO) also reads its state: zeros, an episode's start.
    if (graph.state_width() > 0) inputs.push_back(Eigen::MatrixXf::Zero(graph.state_width(), 1));
    (void)evaluate_graph(graph, inputs);
  } catch (const ExportError&) {
  }
}

void load_like_the_cli(const std::string& path) {
  const Registry& registry = builtin_registry();
  try {
    const ModelFile header = read_model_header(path);
    if (!fuzz::fuzzable_config(ConfigNode::load_string(header.config_yaml, "config.yaml"))) return;
    LoadedModel loaded = load_model(path, registry);
    const Eigen::MatrixXf obs =
        Eigen::MatrixXf::Zero(loaded.env->observation_space().flat_dim(), 1);
    Eigen::MatrixXf actions;
    loaded.algorithm->predict(obs, true, actions);
    export_like_the_cli(loaded);
    resume_like(path, loaded.experiment, registry);
  } catch (const RuntimeFailure&) {
  } catch (const ConfigError&) {
  } catch (const UsageError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string& path = fuzz::private_file("model", "model.zip");
  if (data[0] % 2 == 0) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  } else {
    std::vector<CraftedMember> members;
    if (!members_from(data + 1, size - 1, members)) return 0;
    try {
      rlrun::testing::write_crafted_zip(path, members);
    } catch (const std::runtime_error&) {
      return 0;  // a name libzip will not write
    }
  }
  read_everything(path);
  load_like_the_cli(path);
  return 0;
}
