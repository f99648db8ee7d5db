#pragma once
// Reading a tensor dict that torch.save() wrote (a `state_dict()`: SB3's `policy.pth`,
// `pytorch_variables.pth`), without torch and without running its pickle (docs/security.md).
// torch's file format since 1.6 (torch/serialization.py: _save, _load; caffe2/serialize/
// inline_container.h) is a zip whose members sit under one top folder (`archive/` when written
// to a stream, as SB3 does):
//   <top>/data.pkl     the pickled object (protocol 2); each tensor is a call of
//                      torch._utils._rebuild_tensor_v2(storage, offset, size, stride,
//                      requires_grad, backward_hooks[, metadata]) whose storage is a persistent
//                      id ('storage', torch.<Type>Storage, key, location, numel)
//   <top>/data/<key>   each storage's raw bytes, in the byte order of <top>/byteorder
//                      ("little" when absent: files before torch 2.1 were written so)
//   <top>/version      the format version (torch 1.13 and 2.x write 3)
// read_torch_tensors() accepts exactly that: a dict or collections.OrderedDict from names to
// tensors (or nn.Parameters: torch._utils._rebuild_parameter; None values are left out), each a C-contiguous view inside
// its storage, of the dtypes rlrun's Tensor holds (float32, float64, int64, uint8); the pickle
// may name no other global. Every size it declares is checked before anything is allocated.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/tensor.hpp"

namespace rlrun {

// `bytes` is the whole torch file; `what` names it in messages ("model.zip: policy.pth").
// Storages together may hold at most `budget_bytes`. Throws RuntimeFailure.
TensorMap read_torch_tensors(std::vector<uint8_t> bytes, const std::string& what,
                             uint64_t budget_bytes);

}  // namespace rlrun
