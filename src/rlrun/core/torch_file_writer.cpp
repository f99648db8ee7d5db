#include "rlrun/core/torch_file_writer.hpp"

#include <bit>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/stored_zip.hpp"

namespace rlrun {

namespace {

// torch's PyTorchStreamWriter aligns every record's data to 64 bytes (kFieldAlignment).
constexpr std::size_t kRecordAlignment = 64;
constexpr const char* kArchive = "archive/";

const char* storage_class(DType dtype) {
  switch (dtype) {
    case DType::kFloat32: return "FloatStorage";
    case DType::kFloat64: return "DoubleStorage";
    case DType::kInt64: return "LongStorage";
    case DType::kUInt8: return "ByteStorage";
    case DType::kUInt64: break;  // torch has no uint64 storage torch 1.13 reads
  }
  throw RuntimeFailure("a tensor of a dtype torch 1.13 has no storage for (uint64)");
}

// collections.OrderedDict(): what torch writes for a tensor's (empty) backward hooks and what
// a state_dict() is.
void empty_ordered_dict(PickleWriter& p) {
  p.global_ref("collections", "OrderedDict");
  p.empty_tuple();
  p.reduce();
}

}  // namespace

void TorchFileWriter::tensor(const Tensor& tensor) {
  const char* storage = storage_class(tensor.dtype);
  if (tensor.bytes.size() != static_cast<std::size_t>(tensor.numel()) * dtype_size(tensor.dtype))
    throw RuntimeFailure("a tensor whose bytes do not match its shape");
  // C-order strides, in elements.
  std::vector<int64_t> stride(tensor.shape.size(), 1);
  for (std::size_t i = tensor.shape.size(); i-- > 1;) stride[i - 1] = stride[i] * tensor.shape[i];
  const std::string key = std::to_string(storages_.size());
  storages_.push_back(tensor.bytes);

  PickleWriter& p = pickle_;
  p.global_ref("torch._utils", "_rebuild_tensor_v2");
  p.mark();
  {  // the storage, as a persistent id the loader resolves to archive/data/<key>
    p.mark();
    p.text("storage");
    p.global_ref("torch", storage);
    p.text(key);
    p.text("cpu");
    p.integer(tensor.numel());
    p.tuple_from_mark();
    p.persistent_id();
  }
  p.integer(0);  // storage offset
  p.int_tuple(tensor.shape);
  p.int_tuple(stride);
  p.boolean(false);  // requires_grad
  empty_ordered_dict(p);
  p.tuple_from_mark();
  p.reduce();
}

std::vector<uint8_t> TorchFileWriter::finish() {
  std::vector<StoredZipMember> records;
  const std::string archive = kArchive;
  records.emplace_back(archive + "data.pkl", pickle_.finish());
  const std::string order = std::endian::native == std::endian::little ? "little" : "big";
  records.emplace_back(archive + "byteorder", std::vector<uint8_t>(order.begin(), order.end()));
  for (std::size_t i = 0; i < storages_.size(); ++i)
    records.emplace_back(archive + "data/" + std::to_string(i), std::move(storages_[i]));
  records.emplace_back(archive + "version", std::vector<uint8_t>{'3', '\n'});
  storages_.clear();
  return stored_zip(records, kRecordAlignment);
}

std::vector<uint8_t> torch_save_state_dict(
    const std::vector<std::pair<std::string, const Tensor*>>& tensors) {
  TorchFileWriter writer;
  PickleWriter& p = writer.pickle();
  empty_ordered_dict(p);
  if (!tensors.empty()) {
    p.mark();
    for (const auto& [name, tensor] : tensors) {
      p.text(name);
      writer.tensor(*tensor);
    }
    p.set_items();
  }
  return writer.finish();
}

}  // namespace rlrun
