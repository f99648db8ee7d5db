// Fuzz target: SB3 model files' pickles and torch files from arbitrary bytes, read as
// `rlrun eval --model sb3.zip` reads them (core/pickle_reader.hpp, core/numpy_pickle.hpp,
// core/torch_state_dict.hpp, runtime/io/sb3/sb3_spaces.hpp). Refusing is fine
// (RuntimeFailure); any other exception, a crash, a sanitizer report, a hang or a large
// allocation is a bug.
//
// Input: byte 0 chooses what the rest is —
//   0: a pickle of a Gymnasium space (the allowlist of sb3_spaces.hpp), turned into a Space;
//   1: a torch.save() file (a zip) of a tensor dict, read into tensors;
//   2: a pickle read with every global allowed (the machine itself: stack, memo, marks,
//      the shape checks), whose tree is then walked to its leaves.
// The whole-file path (zip -> data JSON -> pickles -> tensors -> policy) is fuzz_model's
// job for rlrun files; the seeds here come from real SB3 files (fuzz/make_corpus.sh).
#include <cstdint>
#include <cstdlib>
#include <unordered_set>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/torch_state_dict.hpp"
#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"

using namespace rlrun;

namespace {

// Visits every value once (values may be shared through the memo); the reader promised a
// bounded depth and no cycles, so the walk must end within the depth bound.
void walk(const PickleValue& value, std::size_t depth,
          std::unordered_set<const PickleValue*>& seen) {
  if (depth > kMaxPickleDepth) std::abort();
  if (!seen.insert(&value).second) return;
  for (const auto* list : {&value.items, &value.added_items})
    for (const PickleValue* item : *list) walk(*item, depth + 1, seen);
  if (value.state) walk(*value.state, depth + 1, seen);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t* rest = data + 1;
  const size_t rest_size = size - 1;
  try {
    switch (data[0] % 3) {
      case 0: {
        const PickleDocument document =
            read_pickle(rest, rest_size, "fuzz.pkl", is_sb3_space_global);
        const Space space = sb3_space(document.root(), "fuzz.pkl");
        if (space.describe().empty()) std::abort();
        break;
      }
      case 1: {
        const TensorMap tensors =
            read_torch_tensors(std::vector<uint8_t>(rest, rest + rest_size), "fuzz.pth", 1 << 24);
        for (const auto& [name, tensor] : tensors)
          if (tensor.bytes.size() != static_cast<size_t>(tensor.numel()) * dtype_size(tensor.dtype))
            std::abort();
        break;
      }
      default: {
        const PickleDocument document =
            read_pickle(rest, rest_size, "fuzz.pkl", [](const auto&, const auto&) { return true; });
        std::unordered_set<const PickleValue*> seen;
        walk(document.root(), 0, seen);
        break;
      }
    }
  } catch (const RuntimeFailure&) {
  }
  return 0;
}
