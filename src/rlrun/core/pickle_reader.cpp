#include "rlrun/core/pickle_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun {

namespace {

// Opcodes (CPython's Lib/pickletools.py names them; Lib/pickle.py defines them).
enum Op : uint8_t {
  kMark = '(',
  kStop = '.',
  kPop = '0',
  kPopMark = '1',
  kDup = '2',
  kBinFloat = 'G',
  kBinInt = 'J',
  kBinInt1 = 'K',
  kBinInt2 = 'M',
  kNone = 'N',
  kBinPersId = 'Q',
  kReduce = 'R',
  kBinUnicode = 'X',
  kBinBytes = 'B',
  kShortBinBytes = 'C',
  kEmptyList = ']',
  kAppend = 'a',
  kBuild = 'b',
  kGlobal = 'c',
  kDict = 'd',
  kAppends = 'e',
  kBinGet = 'h',
  kLongBinGet = 'j',
  kList = 'l',
  kBinPut = 'q',
  kLongBinPut = 'r',
  kSetItem = 's',
  kTuple = 't',
  kEmptyTuple = ')',
  kSetItems = 'u',
  kEmptyDict = '}',
  kProto = 0x80,
  kNewObj = 0x81,
  kTuple1 = 0x85,
  kTuple2 = 0x86,
  kTuple3 = 0x87,
  kNewTrue = 0x88,
  kNewFalse = 0x89,
  kLong1 = 0x8a,
  kLong4 = 0x8b,
  kShortBinUnicode = 0x8c,
  kBinUnicode8 = 0x8d,
  kBinBytes8 = 0x8e,
  kEmptySet = 0x8f,
  kAddItems = 0x90,
  kFrozenSet = 0x91,
  kStackGlobal = 0x93,
  kMemoize = 0x94,
  kFrame = 0x95,
  kByteArray8 = 0x96,
};

// Names of the opcodes this reader refuses, for the message (pickletools' names).
const char* refused_opcode_name(uint8_t op) {
  switch (op) {
    case 'I': return "INT";
    case 'L': return "LONG";
    case 'S': return "STRING";
    case 'T': return "BINSTRING";
    case 'U': return "SHORT_BINSTRING";
    case 'V': return "UNICODE";
    case 'F': return "FLOAT";
    case 'p': return "PUT";
    case 'g': return "GET";
    case 'i': return "INST";
    case 'o': return "OBJ";
    case 'P': return "PERSID";
    case 0x82: return "EXT1";
    case 0x83: return "EXT2";
    case 0x84: return "EXT4";
    case 0x92: return "NEWOBJ_EX";
    case 0x97: return "NEXT_BUFFER";
    case 0x98: return "READONLY_BUFFER";
    default: return nullptr;
  }
}

// Values and container items one pickle may make: a torch state dict of a few hundred tensors
// makes a few thousand, a gymnasium space a few hundred. Bounds memory whatever the input.
constexpr std::size_t kMaxPickleEntries = std::size_t{1} << 18;
// A GLOBAL's module or name: a dotted Python identifier.
constexpr std::size_t kMaxGlobalNameBytes = 200;

bool is_dotted_identifier(const std::string& text) {
  if (text.empty() || text.size() > kMaxGlobalNameBytes) return false;
  for (const char c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.')) return false;
  return true;
}

}  // namespace

// The stack machine (see the header). One instance per read_pickle call.
class PickleMachine {
 public:
  PickleMachine(const uint8_t* bytes, std::size_t size, const std::string& what,
                const PickleGlobalFilter& allowed, PickleDocument& document)
      : bytes_(bytes), size_(size), what_(what), allowed_(allowed), document_(document) {}

  void run() {
    while (true) {
      opcode_at_ = position_;
      const uint8_t op = next_byte();
      if (op == kStop) break;
      if (!(stack_op(op) || scalar_op(op) || text_op(op) || container_op(op) || memo_op(op) ||
            object_op(op)))
        refuse_opcode(op);
    }
    if (position_ != size_) fail("data continues after STOP");
    if (!marks_.empty()) fail("a MARK is never closed");
    if (stack_.size() != 1) fail("STOP leaves " + std::to_string(stack_.size()) + " values");
    document_.root_ = stack_.back();
    check_shape(*document_.root_, 0);
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeFailure(what_ + ": pickle byte " + std::to_string(opcode_at_) + ": " + why);
  }
  [[noreturn]] void refuse_opcode(uint8_t op) const {
    const char* name = refused_opcode_name(op);
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02x", op);
    if (name)
      fail(std::string("opcode ") + name + " (" + hex +
           ") is refused: rlrun reads only the binary opcodes of pickle protocols 2-5 that "
           "build data (docs/security.md)");
    fail(std::string("byte ") + hex + " is not a pickle opcode");
  }

  // --- reading the input ---
  uint8_t next_byte() {
    if (position_ >= size_) fail("the pickle ends without STOP");
    return bytes_[position_++];
  }
  uint64_t little_endian(int count) {
    uint64_t value = 0;
    for (int i = 0; i < count; ++i) value |= uint64_t{next_byte()} << (8 * i);
    return value;
  }
  std::string take(uint64_t count) {
    if (count > size_ - position_)
      fail("a value of " + std::to_string(count) + " bytes runs past the end of the pickle");
    std::string out(reinterpret_cast<const char*>(bytes_ + position_), count);
    position_ += count;
    return out;
  }
  std::string line() {
    std::string out;
    while (true) {
      const uint8_t c = next_byte();
      if (c == '\n') return out;
      if (out.size() >= kMaxGlobalNameBytes) fail("a GLOBAL's name is too long");
      out += static_cast<char>(c);
    }
  }

  // --- values and the stack ---
  PickleValue* make(PickleKind kind) {
    charge(1);
    PickleValue& value = document_.arena_.emplace_back();
    value.kind = kind;
    return &value;
  }
  void charge(std::size_t entries) {
    entries_ += entries;
    if (entries_ > kMaxPickleEntries)
      fail("more than " + std::to_string(kMaxPickleEntries) + " values: not a file rlrun reads");
  }
  // The stack, the marks and the memo hold pointers, not values, but a pickle of DUPs, MARKs or
  // BINPUTs grows them by a word per input byte: they share the values' bound.
  void push(PickleValue* value) {
    grow_check();
    stack_.push_back(value);
  }
  void grow_check() const {
    if (stack_.size() + marks_.size() + memo_.size() >= kMaxPickleEntries)
      fail("more than " + std::to_string(kMaxPickleEntries) +
           " values on the stack and in the memo: not a file rlrun reads");
  }
  void memoize(uint64_t key) {
    grow_check();
    memo_[key] = top();
  }
  PickleValue* pop() {
    if (stack_.size() <= floor()) fail("the stack is empty");
    PickleValue* value = stack_.back();
    stack_.pop_back();
    return value;
  }
  PickleValue* top() {
    if (stack_.size() <= floor()) fail("the stack is empty");
    return stack_.back();
  }
  // Values above the innermost MARK are all an opcode may pop.
  std::size_t floor() const { return marks_.empty() ? 0 : marks_.back(); }
  std::vector<PickleValue*> pop_mark() {
    if (marks_.empty()) fail("no MARK to pop to");
    const std::size_t mark = marks_.back();
    marks_.pop_back();
    std::vector<PickleValue*> items(stack_.begin() + static_cast<std::ptrdiff_t>(mark),
                                    stack_.end());
    stack_.resize(mark);
    return items;
  }
  PickleValue* sequence(PickleKind kind, const std::vector<PickleValue*>& items) {
    PickleValue* value = make(kind);
    charge(items.size());
    value->items.assign(items.begin(), items.end());
    return value;
  }
  void add_items(PickleValue* container, const std::vector<PickleValue*>& items, bool pairs) {
    if (pairs && items.size() % 2 != 0) fail("SETITEMS with a key and no value");
    charge(items.size());
    std::vector<const PickleValue*>* into = &container->items;
    const bool fits =
        pairs ? container->kind == PickleKind::kDict
              : container->kind == PickleKind::kList || container->kind == PickleKind::kSet;
    if (container->kind == PickleKind::kCall) {
      into = &container->added_items;
      if (!into->empty() && container->added_pairs != pairs)
        fail("both items and pairs added to a call");
      container->added_pairs = pairs;
    } else if (!fits) {
      fail("items added to " + describe_pickle_value(*container));
    }
    into->insert(into->end(), items.begin(), items.end());
  }

  bool stack_op(uint8_t op) {
    switch (op) {
      case kProto: {
        const uint8_t protocol = next_byte();
        if (protocol < 2 || protocol > 5)
          fail("pickle protocol " + std::to_string(protocol) + " (rlrun reads protocols 2-5)");
        return true;
      }
      case kFrame:  // a hint for buffering readers: the whole input is in memory already
        if (little_endian(8) > size_ - position_) fail("a FRAME runs past the end");
        return true;
      case kMark: grow_check(), marks_.push_back(stack_.size()); return true;
      case kPop: pop(); return true;
      case kPopMark: pop_mark(); return true;
      case kDup: push(top()); return true;
      default: return false;
    }
  }

  bool scalar_op(uint8_t op) {
    PickleValue* value = nullptr;
    switch (op) {
      case kNone: value = make(PickleKind::kNone); break;
      case kNewTrue:
      case kNewFalse:
        value = make(PickleKind::kBool);
        value->boolean = op == kNewTrue;
        break;
      case kBinInt:
        value = make(PickleKind::kInt);
        value->integer = static_cast<int32_t>(static_cast<uint32_t>(little_endian(4)));
        break;
      case kBinInt1:
      case kBinInt2:
        value = make(PickleKind::kInt);
        value->integer = static_cast<int64_t>(little_endian(op == kBinInt1 ? 1 : 2));
        break;
      case kLong1:
      case kLong4: value = long_integer(op == kLong1 ? next_byte() : little_endian(4)); break;
      case kBinFloat: {
        uint64_t bits = 0;  // big-endian IEEE 754 double
        for (int i = 0; i < 8; ++i) bits = (bits << 8) | next_byte();
        value = make(PickleKind::kFloat);
        std::memcpy(&value->number, &bits, sizeof bits);
        break;
      }
      default: return false;
    }
    push(value);
    return true;
  }
  // LONG1 / LONG4: `count` bytes of little-endian two's complement. Python ints of any size;
  // those that fit in 64 bits (sizes, shapes, seeds) are kInt, larger ones (a random
  // generator's 128-bit state) kBigInt without a value.
  PickleValue* long_integer(uint64_t count) {
    if (count > kMaxPickleIntBytes)
      fail("an integer of " + std::to_string(count) + " bytes (rlrun reads at most " +
           std::to_string(kMaxPickleIntBytes) + ")");
    if (count > 8) {
      PickleValue* value = make(PickleKind::kBigInt);
      value->text = take(count);
      return value;
    }
    uint64_t bits = count == 0 ? 0 : little_endian(static_cast<int>(count));
    if (count > 0 && count < 8 && (bits >> (8 * count - 1)) & 1)
      bits |= ~uint64_t{0} << (8 * count);  // sign-extend
    PickleValue* value = make(PickleKind::kInt);
    value->integer = static_cast<int64_t>(bits);
    return value;
  }

  bool text_op(uint8_t op) {
    uint64_t count = 0;
    PickleKind kind = PickleKind::kString;
    switch (op) {
      case kShortBinUnicode: count = next_byte(); break;
      case kBinUnicode: count = little_endian(4); break;
      case kBinUnicode8: count = little_endian(8); break;
      case kShortBinBytes: count = next_byte(), kind = PickleKind::kBytes; break;
      case kBinBytes: count = little_endian(4), kind = PickleKind::kBytes; break;
      case kBinBytes8:
      case kByteArray8: count = little_endian(8), kind = PickleKind::kBytes; break;
      default: return false;
    }
    std::string text = take(count);
    if (kind == PickleKind::kString && !valid_utf8(text)) fail("a str that is not UTF-8");
    PickleValue* value = make(kind);
    value->text = std::move(text);
    push(value);
    return true;
  }

  bool container_op(uint8_t op) {
    switch (op) {
      case kEmptyTuple: push(make(PickleKind::kTuple)); return true;
      case kEmptyList: push(make(PickleKind::kList)); return true;
      case kEmptyDict: push(make(PickleKind::kDict)); return true;
      case kEmptySet: push(make(PickleKind::kSet)); return true;
      case kTuple: push(sequence(PickleKind::kTuple, pop_mark())); return true;
      case kList: push(sequence(PickleKind::kList, pop_mark())); return true;
      case kFrozenSet: push(sequence(PickleKind::kSet, pop_mark())); return true;
      case kDict: {
        const std::vector<PickleValue*> items = pop_mark();
        if (items.size() % 2 != 0) fail("DICT with a key and no value");
        push(sequence(PickleKind::kDict, items));
        return true;
      }
      case kTuple1:
      case kTuple2:
      case kTuple3: {
        std::vector<PickleValue*> items(op - kTuple1 + 1);
        for (auto it = items.rbegin(); it != items.rend(); ++it) *it = pop();
        push(sequence(PickleKind::kTuple, items));
        return true;
      }
      case kAppend:
      case kSetItem: {
        std::vector<PickleValue*> items(op == kAppend ? 1 : 2);
        for (auto it = items.rbegin(); it != items.rend(); ++it) *it = pop();
        add_items(top(), items, op == kSetItem);
        return true;
      }
      case kAppends:
      case kSetItems:
      case kAddItems: {
        const std::vector<PickleValue*> items = pop_mark();
        add_items(top(), items, op == kSetItems);
        return true;
      }
      default: return false;
    }
  }

  bool memo_op(uint8_t op) {
    switch (op) {
      case kBinPut: memoize(next_byte()); return true;
      case kLongBinPut: memoize(little_endian(4)); return true;
      case kMemoize: memoize(memo_.size()); return true;
      case kBinGet:
      case kLongBinGet: {
        const uint64_t key = op == kBinGet ? next_byte() : little_endian(4);
        const auto found = memo_.find(key);
        if (found == memo_.end()) fail("memo entry " + std::to_string(key) + " was never stored");
        push(found->second);
        return true;
      }
      default: return false;
    }
  }

  bool object_op(uint8_t op) {
    switch (op) {
      case kGlobal: {
        std::string module = line();
        std::string name = line();
        push(global(std::move(module), std::move(name)));
        return true;
      }
      case kStackGlobal: {
        const PickleValue* name = pop();
        const PickleValue* module = pop();
        if (module->kind != PickleKind::kString || name->kind != PickleKind::kString)
          fail("STACK_GLOBAL of something other than two strings");
        push(global(module->text, name->text));
        return true;
      }
      case kReduce:
      case kNewObj: {
        PickleValue* arguments = pop();
        PickleValue* callable = pop();
        if (arguments->kind != PickleKind::kTuple)
          fail("a call whose arguments are " + describe_pickle_value(*arguments));
        PickleValue* call = sequence(PickleKind::kCall, {callable, arguments});
        call->via_newobj = op == kNewObj;
        push(call);
        return true;
      }
      case kBuild: {
        PickleValue* state = pop();
        PickleValue* object = top();
        if (object->kind != PickleKind::kCall || object->state)
          fail("BUILD of " + describe_pickle_value(*object));
        object->state = state;
        return true;
      }
      case kBinPersId: push(sequence(PickleKind::kPersistentId, {pop()})); return true;
      default: return false;
    }
  }
  PickleValue* global(std::string module, std::string name) {
    if (!is_dotted_identifier(module) || !is_dotted_identifier(name))
      fail("a global whose name is not a Python identifier: '" + quoted_text(module + "." + name) +
           "'");
    if (!allowed_(module, name))
      fail("refers to " + module + "." + name +
           ", which rlrun does not read: a pickle may name only the classes and functions of "
           "tensors, spaces and numbers (pickle is code: docs/security.md)");
    PickleValue* value = make(PickleKind::kGlobal);
    value->module = std::move(module);
    value->text = std::move(name);
    return value;
  }

  // The result must be a tree of bounded depth, possibly sharing subtrees (the memo), never
  // containing itself. Each value is walked once: its height (the longest chain of values below
  // it) is kept, so sharing costs nothing and a shared subtree met again deeper down is
  // measured by depth + height. Returns the height of `value`.
  std::size_t check_shape(const PickleValue& value, std::size_t depth) {
    if (depth > kMaxPickleDepth)
      fail("values nested deeper than " + std::to_string(kMaxPickleDepth) + " levels");
    const auto [it, fresh] = height_of_.try_emplace(&value, kWalking);
    if (!fresh) {
      if (it->second == kWalking) fail("a value that contains itself");
      if (depth + it->second > kMaxPickleDepth)
        fail("values nested deeper than " + std::to_string(kMaxPickleDepth) + " levels");
      return it->second;
    }
    std::size_t height = 0;
    for (const auto* list : {&value.items, &value.added_items})
      for (const PickleValue* item : *list)
        height = std::max(height, 1 + check_shape(*item, depth + 1));
    if (value.state) height = std::max(height, 1 + check_shape(*value.state, depth + 1));
    height_of_[&value] = height;  // `it` may be invalidated by the walk below it
    return height;
  }

  static constexpr std::size_t kWalking = SIZE_MAX;
  const uint8_t* bytes_;
  std::size_t size_;
  const std::string& what_;
  const PickleGlobalFilter& allowed_;
  PickleDocument& document_;
  std::size_t position_ = 0;
  std::size_t opcode_at_ = 0;
  std::size_t entries_ = 0;
  std::vector<PickleValue*> stack_;
  std::vector<std::size_t> marks_;
  std::unordered_map<uint64_t, PickleValue*> memo_;
  std::unordered_map<const PickleValue*, std::size_t> height_of_;
};

PickleDocument read_pickle(const uint8_t* bytes, std::size_t size, const std::string& what,
                           const PickleGlobalFilter& allowed) {
  PickleDocument document;
  PickleMachine machine(bytes, size, what, allowed, document);
  machine.run();
  return document;
}

const std::vector<const PickleValue*>* pickle_dict_items(const PickleValue& value) {
  if (value.kind == PickleKind::kDict) return &value.items;
  const PickleValue* callee = value.callee();
  if (callee && callee->is_global("collections", "OrderedDict") && !value.via_newobj &&
      value.arguments().items.empty() && (value.added_pairs || value.added_items.empty()))
    return &value.added_items;
  return nullptr;
}

const PickleValue* pickle_dict_get(const PickleValue& dict, std::string_view key) {
  const std::vector<const PickleValue*>* items = pickle_dict_items(dict);
  const PickleValue* found = nullptr;
  for (std::size_t i = 0; items && i + 1 < items->size(); i += 2)
    if ((*items)[i]->kind == PickleKind::kString && (*items)[i]->text == key)
      found = (*items)[i + 1];
  return found;
}

std::string describe_pickle_value(const PickleValue& value) {
  switch (value.kind) {
    case PickleKind::kNone: return "None";
    case PickleKind::kBool: return "bool";
    case PickleKind::kInt: return "int";
    case PickleKind::kBigInt: return "int";
    case PickleKind::kFloat: return "float";
    case PickleKind::kString: return "str";
    case PickleKind::kBytes: return "bytes";
    case PickleKind::kTuple: return "tuple";
    case PickleKind::kList: return "list";
    case PickleKind::kDict: return "dict";
    case PickleKind::kSet: return "set";
    case PickleKind::kGlobal: return "global " + value.module + "." + value.text;
    case PickleKind::kCall:
      return value.callee() ? "a call of " + value.callee()->module + "." + value.callee()->text
                            : "a call";
    case PickleKind::kPersistentId: return "a persistent id";
  }
  return "a value";
}

}  // namespace rlrun
