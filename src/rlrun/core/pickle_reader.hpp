#pragma once
// Reading Python pickles that may come from anyone (SB3 model files: torch's `data.pkl` inside
// `policy.pth`, the cloudpickled entries of SB3's `data` JSON; docs/security.md) WITHOUT
// running them. A pickle is a program for a stack machine whose instructions may import any
// global and call it (`os.system` is two opcodes away), so Python's unpickler on an untrusted
// file is remote code execution. This reader is a different machine: it executes the opcodes
// that BUILD DATA and turns the ones that would import or call into inert tree nodes —
//  * GLOBAL / STACK_GLOBAL become a kGlobal node, and only when the caller's allowlist accepts
//    the (module, name) pair; any other global refuses the whole pickle, naming it;
//  * REDUCE / NEWOBJ become a kCall node (callable, arguments); BUILD records a state on it and
//    SETITEMS / APPENDS the items added to it: nothing is ever called; the caller interprets the few calls it knows
//    (core/torch_state_dict.hpp: torch._utils._rebuild_tensor_v2, collections.OrderedDict);
//  * BINPERSID becomes a kPersistentId node (torch names its tensor storages this way).
// Accepted: protocols 2 to 5, binary opcodes only (pickletools' names): PROTO FRAME STOP MARK
// POP POP_MARK DUP NONE NEWTRUE NEWFALSE BININT BININT1 BININT2 LONG1 LONG4 (of at most
// kMaxPickleIntBytes bytes; kBigInt beyond 64 bits) BINFLOAT BINUNICODE SHORT_BINUNICODE BINUNICODE8 BINBYTES SHORT_BINBYTES BINBYTES8
// BYTEARRAY8 EMPTY_TUPLE TUPLE TUPLE1-3 EMPTY_LIST LIST APPEND APPENDS EMPTY_DICT DICT SETITEM
// SETITEMS EMPTY_SET ADDITEMS FROZENSET BINPUT LONG_BINPUT MEMOIZE BINGET LONG_BINGET GLOBAL
// STACK_GLOBAL REDUCE NEWOBJ BUILD BINPERSID. Refused, with the opcode's name: the text
// opcodes of protocols 0-1, INST, OBJ, NEWOBJ_EX, EXT1/2/4, PERSID, NEXT_BUFFER and
// READONLY_BUFFER (out-of-band buffers), and any byte that is no opcode.
// Bounds: whatever the input's size, at most 2^18 values and container items, and at most 2^18
// pointers on the stack, marks and memo together; the result's nesting is at most
// kMaxPickleDepth and a structure that contains itself (a list appended to itself through the
// memo) is refused, so code that walks the result needs no cycle checks of its own.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rlrun {

inline constexpr std::size_t kMaxPickleDepth = 64;
inline constexpr std::size_t kMaxPickleIntBytes = 64;

enum class PickleKind {
  kNone,
  kBool,
  kInt,
  kBigInt,  // an int that needs more than 64 bits (a PCG64 state): text holds its bytes
  kFloat,
  kString,  // str (UTF-8 bytes as written)
  kBytes,   // bytes or bytearray
  kTuple,
  kList,
  kDict,  // items: key, value, key, value, ...
  kSet,   // set or frozenset
  kGlobal,
  kCall,          // REDUCE or NEWOBJ: items[0] the callable, items[1] the argument tuple
  kPersistentId,  // BINPERSID: items[0] the id
};

struct PickleValue {
  PickleKind kind = PickleKind::kNone;
  bool boolean = false;
  int64_t integer = 0;
  double number = 0.0;
  std::string text;                       // kString, kBytes; kGlobal: the name
  std::string module;                     // kGlobal
  std::vector<const PickleValue*> items;  // see PickleKind
  const PickleValue* state = nullptr;     // kCall: what BUILD set (nullptr if none)
  // kCall: what SETITEM(S) (key, value, ...) or APPEND(S) added to the object made by the call
  // (pickle stores a dict or list subclass, such as collections.OrderedDict, this way).
  std::vector<const PickleValue*> added_items;
  bool added_pairs = false;  // added_items are key, value pairs (SETITEMS), not APPENDS
  bool via_newobj = false;   // kCall made by NEWOBJ (cls.__new__(cls, *args))

  bool is_global(const char* module_name, const char* name) const {
    return kind == PickleKind::kGlobal && module == module_name && text == name;
  }
  // The callable of a kCall node when it is a global, else nullptr.
  const PickleValue* callee() const {
    return kind == PickleKind::kCall && items[0]->kind == PickleKind::kGlobal ? items[0] : nullptr;
  }
  const PickleValue& arguments() const { return *items[1]; }  // kCall: a tuple
};

// Whether a global may appear in the pickle (module, name as written).
using PickleGlobalFilter = std::function<bool(const std::string& module, const std::string& name)>;

// The unpickled tree; values live as long as the PickleDocument.
class PickleDocument {
 public:
  const PickleValue& root() const { return *root_; }

 private:
  friend class PickleMachine;
  std::deque<PickleValue> arena_;
  const PickleValue* root_ = nullptr;
};

// Runs the data-building part of `bytes` (see the top of this file). Throws RuntimeFailure
// naming `what`, the byte offset and the reason for anything refused or malformed.
PickleDocument read_pickle(const uint8_t* bytes, std::size_t size, const std::string& what,
                           const PickleGlobalFilter& allowed);

// A value's kind as Python would name it, for messages ("int", "tuple", "global os.system").
std::string describe_pickle_value(const PickleValue& value);

// The (key, value, key, value, ...) items of a dict, or of a collections.OrderedDict (a call
// with no arguments whose items SETITEMS added: how state_dict() and spaces' dicts pickle);
// nullptr for any other value.
const std::vector<const PickleValue*>* pickle_dict_items(const PickleValue& value);
// The value of the str key `key` in such a dict (the last one set, as Python keeps), or
// nullptr: an attribute of an object's pickled __dict__.
const PickleValue* pickle_dict_get(const PickleValue& dict, std::string_view key);

}  // namespace rlrun
