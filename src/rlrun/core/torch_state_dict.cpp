#include "rlrun/core/torch_state_dict.hpp"

#include <bit>
#include <cstring>
#include <map>
#include <optional>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/zip_reader.hpp"

namespace rlrun {

namespace {

static_assert(std::endian::native == std::endian::little,
              "storages are copied as stored: little-endian bytes");

// data.pkl of a policy is a few KiB (tensors live in their own members).
constexpr uint64_t kMaxDataPickleBytes = uint64_t{16} << 20;
// torch/serialization.py: _save writes `version` 3 since torch 1.6 (1 and 2 are older layouts
// of the same members).
constexpr int kMaxTorchFormatVersion = 3;

// The storage classes torch 1.x and 2.x name in persistent ids, and the dtypes rlrun holds.
std::optional<DType> storage_dtype(const std::string& name) {
  if (name == "FloatStorage") return DType::kFloat32;
  if (name == "DoubleStorage") return DType::kFloat64;
  if (name == "LongStorage") return DType::kInt64;
  if (name == "ByteStorage") return DType::kUInt8;
  return std::nullopt;
}

bool torch_global(const std::string& module, const std::string& name) {
  if (module == "collections") return name == "OrderedDict";
  if (module == "torch._utils") return name == "_rebuild_tensor_v2" || name == "_rebuild_parameter";
  if (module == "torch") return storage_dtype(name).has_value();
  return false;
}

// Reads one torch file: its members, then the tensors its pickle describes.
class TorchFileReader {
 public:
  TorchFileReader(std::vector<uint8_t> bytes, const std::string& what, uint64_t budget_bytes)
      : what_(what), archive_(std::move(bytes), what), budget_(budget_bytes) {}

  TensorMap read() {
    find_top_folder();
    check_version();
    const ZipEntry& pickle_entry = member("data.pkl");
    const std::vector<uint8_t> pickle = archive_.read(pickle_entry, kMaxDataPickleBytes);
    const PickleDocument document =
        read_pickle(pickle.data(), pickle.size(), archive_.describe(pickle_entry), torch_global);
    TensorMap tensors;
    const std::vector<const PickleValue*>& pairs = root_pairs(document.root());
    for (std::size_t i = 0; i < pairs.size(); i += 2) {
      if (pairs[i]->kind != PickleKind::kString) fail("a key that is not a string");
      const std::string& name = pairs[i]->text;
      if (name.empty() || name.size() > 256)
        fail("a tensor name of " + std::to_string(name.size()) + " bytes");
      if (tensors.count(name)) fail("tensor '" + quoted_text(name) + "' appears twice");
      // SB3's pytorch_variables.pth may hold None (SAC's log_ent_coef with a fixed ent_coef).
      if (pairs[i + 1]->kind == PickleKind::kNone) continue;
      tensors[name] = tensor(*pairs[i + 1], name, 0);
    }
    return tensors;
  }

 private:
  struct StorageRef {
    DType dtype;
    std::string key;
    int64_t numel;
  };
  struct Storage {
    DType dtype = DType::kFloat32;
    int64_t numel = 0;
    std::vector<uint8_t> bytes;
  };

  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeFailure(what_ + ": " + why + " (rlrun reads torch.save() files of tensor dicts)");
  }

  void find_top_folder() {
    for (const ZipEntry& entry : archive_.entries()) {
      const std::size_t slash = entry.name.find('/');
      if (slash == std::string::npos || slash == 0)
        fail("member '" + quoted_text(entry.name) + "' outside a top folder");
      const std::string top = entry.name.substr(0, slash + 1);
      if (top_.empty()) top_ = top;
      if (top != top_) fail("members in two top folders");
    }
    if (top_.empty()) fail("an empty archive");
  }
  const ZipEntry* find(const std::string& name) const { return archive_.find(top_ + name); }
  const ZipEntry& member(const std::string& name) const {
    const ZipEntry* entry = find(name);
    if (!entry) fail("no member " + top_ + name);
    return *entry;
  }

  void check_version() {
    if (const ZipEntry* entry = find("version")) {
      const std::vector<uint8_t> text = archive_.read(*entry, 16);
      int version = 0;
      for (const uint8_t c : text) {
        if (c == '\n') break;
        if (c < '0' || c > '9' || version > 1000) fail("a version that is not a small number");
        version = version * 10 + (c - '0');
      }
      if (version < 1 || version > kMaxTorchFormatVersion)
        fail("format version " + std::to_string(version) + " (rlrun reads 1 to " +
             std::to_string(kMaxTorchFormatVersion) + ")");
    }
    if (const ZipEntry* entry = find("byteorder")) {
      const std::vector<uint8_t> text = archive_.read(*entry, 16);
      if (std::string(text.begin(), text.end()) != "little")
        fail("storages that are not little-endian");
    }
  }

  // The dict's (key, value, ...) list: a plain dict, or an OrderedDict (what state_dict()
  // returns) whose items SETITEMS added; its state (`_metadata`, module versions) is unused.
  const std::vector<const PickleValue*>& root_pairs(const PickleValue& root) const {
    const std::vector<const PickleValue*>* pairs = pickle_dict_items(root);
    if (!pairs) fail("holds " + describe_pickle_value(root) + ", not a dict of tensors");
    return *pairs;
  }

  Tensor tensor(const PickleValue& value, const std::string& name, int depth) {
    const PickleValue* callee = value.callee();
    const std::vector<const PickleValue*>* args = callee ? &value.arguments().items : nullptr;
    if (callee && callee->is_global("torch._utils", "_rebuild_parameter") && depth == 0 &&
        args->size() == 3)
      return tensor(*(*args)[0], name, depth + 1);
    if (!callee || !callee->is_global("torch._utils", "_rebuild_tensor_v2") ||
        (args->size() != 6 && args->size() != 7) || value.via_newobj || value.state)
      fail("'" + quoted_text(name) + "' is " + describe_pickle_value(value) + ", not a tensor");
    const auto& a = *args;
    const StorageRef storage = storage_ref(*a[0], name);
    const int64_t offset = integer(*a[1], name);
    const std::vector<int64_t> shape = integers(*a[2], name);
    const std::vector<int64_t> stride = integers(*a[3], name);
    if (shape.size() != stride.size())
      fail("'" + quoted_text(name) + "' has a stride per dimension missing");
    int64_t numel = 1;
    int64_t expected_stride = 1;
    for (std::size_t d = shape.size(); d-- > 0;) {
      if (shape[d] > 1 && stride[d] != expected_stride)
        fail("'" + quoted_text(name) + "' is not C-contiguous");
      if (__builtin_mul_overflow(numel, shape[d], &numel) ||
          __builtin_mul_overflow(expected_stride, std::max<int64_t>(shape[d], 1), &expected_stride))
        fail("'" + quoted_text(name) + "' has too many elements");
    }
    int64_t end = 0;
    if (__builtin_add_overflow(offset, numel, &end) || (numel > 0 && end > storage.numel))
      fail("'" + quoted_text(name) + "' reaches past its storage");
    const std::vector<uint8_t>& data = storage_bytes(storage);
    Tensor out;
    out.dtype = storage.dtype;
    out.shape = shape;
    const std::size_t item = dtype_size(storage.dtype);
    out.bytes.assign(data.begin() + static_cast<std::ptrdiff_t>(offset * item),
                     data.begin() + static_cast<std::ptrdiff_t>((offset + numel) * item));
    if (numel == 0) out.bytes.clear();
    return out;
  }

  // ('storage', torch.<Type>Storage, key, location, numel): torch/serialization.py's
  // persistent_id for a storage; location ("cpu", "cuda:0") does not matter to a copy.
  StorageRef storage_ref(const PickleValue& value, const std::string& name) const {
    const PickleValue* id = value.kind == PickleKind::kPersistentId ? value.items[0] : nullptr;
    if (!id || id->kind != PickleKind::kTuple || id->items.size() != 5 ||
        id->items[0]->kind != PickleKind::kString || id->items[0]->text != "storage" ||
        id->items[1]->kind != PickleKind::kGlobal || id->items[1]->module != "torch" ||
        !storage_dtype(id->items[1]->text) || id->items[2]->kind != PickleKind::kString ||
        id->items[4]->kind != PickleKind::kInt)
      fail("'" + quoted_text(name) + "' has no storage of the form torch writes");
    StorageRef ref{*storage_dtype(id->items[1]->text), id->items[2]->text, id->items[4]->integer};
    if (ref.key.empty() || ref.key.size() > 20 ||
        ref.key.find_first_not_of("0123456789") != std::string::npos)
      fail("'" + quoted_text(name) + "' names storage '" + quoted_text(ref.key) + "'");
    if (ref.numel < 0) fail("'" + quoted_text(name) + "' has a storage of negative size");
    return ref;
  }

  const std::vector<uint8_t>& storage_bytes(const StorageRef& ref) {
    auto found = storages_.find(ref.key);
    if (found != storages_.end()) {
      if (found->second.dtype != ref.dtype || found->second.numel != ref.numel)
        fail("storage " + ref.key + " is named with two types or sizes");
      return found->second.bytes;
    }
    const ZipEntry& entry = member("data/" + ref.key);
    const uint64_t item = dtype_size(ref.dtype);
    if (static_cast<uint64_t>(ref.numel) > UINT64_MAX / item ||
        entry.size != static_cast<uint64_t>(ref.numel) * item)
      fail("storage " + ref.key + " holds " + std::to_string(entry.size) + " bytes, not " +
           std::to_string(ref.numel) + " elements of " + std::to_string(item) + " bytes");
    if (entry.size > budget_ - spent_)
      fail("storages of more than " + std::to_string(budget_) + " bytes");
    spent_ += entry.size;
    Storage& storage = storages_[ref.key];
    storage.dtype = ref.dtype;
    storage.numel = ref.numel;
    storage.bytes = archive_.read(entry, entry.size);
    return storage.bytes;
  }

  int64_t integer(const PickleValue& value, const std::string& name) const {
    if (value.kind != PickleKind::kInt || value.integer < 0)
      fail("'" + quoted_text(name) + "' has a size, stride or offset that is not a count");
    return value.integer;
  }
  std::vector<int64_t> integers(const PickleValue& value, const std::string& name) const {
    if (value.kind != PickleKind::kTuple || value.items.size() > 32)
      fail("'" + quoted_text(name) + "' has a shape that is not a tuple of at most 32 sizes");
    std::vector<int64_t> out;
    for (const PickleValue* item : value.items) out.push_back(integer(*item, name));
    return out;
  }

  std::string what_;
  ZipReader archive_;
  uint64_t budget_;
  uint64_t spent_ = 0;
  std::string top_;
  std::map<std::string, Storage> storages_;
};

}  // namespace

TensorMap read_torch_tensors(std::vector<uint8_t> bytes, const std::string& what,
                             uint64_t budget_bytes) {
  return TorchFileReader(std::move(bytes), what, budget_bytes).read();
}

}  // namespace rlrun
