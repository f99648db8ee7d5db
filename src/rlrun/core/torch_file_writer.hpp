#pragma once
// Writing files that torch.load() reads, without torch: the format core/torch_state_dict.hpp
// describes and reads (torch/serialization.py _save; caffe2/serialize/inline_container.cc),
// as torch 1.13 and 2.x write it when saving to a stream — a stored zip
// (core/stored_zip.hpp) whose records sit under `archive/`, 64-byte aligned:
//   archive/data.pkl    the pickled object (protocol 2); a tensor is
//                       torch._utils._rebuild_tensor_v2(storage, 0, size, stride, False,
//                       OrderedDict()) with the storage a persistent id
//                       ('storage', torch.<Type>Storage, '<key>', 'cpu', numel)
//   archive/byteorder   "little" (torch >= 2.1 reads it; older versions ignore it)
//   archive/data/<key>  each tensor's bytes, C order
//   archive/version     "3\n"
// Each tensor gets its own storage (no views), so what is written is what a state_dict() of
// contiguous parameters looks like.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/core/pickle_writer.hpp"
#include "rlrun/tensor.hpp"

namespace rlrun {

class TorchFileWriter {
 public:
  TorchFileWriter() : pickle_(2) {}

  // The object is written here: numbers, strings, dicts, ..., and tensor() for each tensor.
  PickleWriter& pickle() { return pickle_; }
  // Pushes the tensor onto the pickle's stack (float32, float64, int64 or uint8; other dtypes
  // throw RuntimeFailure).
  void tensor(const Tensor& tensor);

  // The file's bytes; the writer is spent.
  std::vector<uint8_t> finish();

 private:
  PickleWriter pickle_;
  std::vector<std::vector<uint8_t>> storages_;
};

// torch.save(OrderedDict(tensors)), the names in the given order: a module's state_dict().
std::vector<uint8_t> torch_save_state_dict(
    const std::vector<std::pair<std::string, const Tensor*>>& tensors);

}  // namespace rlrun
