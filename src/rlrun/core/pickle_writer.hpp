#pragma once
// Writing Python pickles without Python: the few opcodes SB3's and torch's files need to
// describe data (numbers, strings, bytes, tuples, lists, dicts, references to classes and the
// calls that rebuild objects from data), for `rlrun export --format sb3`
// (runtime/io/sb3/sb3_model_writer.hpp). The reader is core/pickle_reader.hpp.
//
// The writer is a stack machine like the reader: each call appends one opcode (pickletools'
// names in the comments, Python's Lib/pickletools.py documents them), so a writer builds a
// value bottom-up exactly as the unpickler will. No memo is written (no PUT/GET): every value
// is written where it is used, which keeps the file free of shared references.
//
// Text written here is data to the unpickler: strings and bytes are length-prefixed, module
// and class names come only from this program's own constants (global_ref refuses a newline,
// the one character that would end a GLOBAL opcode's argument).
#include <cstdint>
#include <string>
#include <vector>

namespace rlrun {

class PickleWriter {
 public:
  // PROTO `protocol`: 2 (torch.save writes 2) or higher (3 adds bytes; 4 what SB3's cloudpickle
  // entries are read with by every Python 3).
  explicit PickleWriter(int protocol);

  void none();                                        // NONE
  void boolean(bool value);                           // NEWTRUE / NEWFALSE
  void integer(int64_t value);                        // BININT1 / BININT2 / BININT / LONG1
  void real(double value);                            // BINFLOAT (big-endian IEEE 754 double)
  void text(const std::string& s);                    // BINUNICODE (UTF-8 as given)
  void bytes(const uint8_t* data, std::size_t size);  // BINBYTES (protocol >= 3)
  // GLOBAL "module\nname\n": the class or function `module.name`.
  void global_ref(const std::string& module, const std::string& name);
  void mark();             // MARK
  void tuple_from_mark();  // TUPLE: the values since the mark
  void empty_tuple();      // EMPTY_TUPLE
  void empty_list();       // EMPTY_LIST
  void appends();          // APPENDS: the values since the mark onto the list below
  void empty_dict();       // EMPTY_DICT
  void set_items();        // SETITEMS: key, value pairs since the mark into the dict
  void reduce();           // REDUCE: callable(*args)
  void new_object();       // NEWOBJ: cls.__new__(cls, *args)
  void build();            // BUILD: obj.__setstate__(state) or __dict__ update
  void persistent_id();    // BINPERSID: the value is an id the loader resolves

  // The pickle with STOP appended; the writer is spent.
  std::vector<uint8_t> finish();

  // Common shapes: a tuple of ints, a list of ints.
  void int_tuple(const std::vector<int64_t>& values);
  void int_list(const std::vector<int64_t>& values);

 private:
  void op(uint8_t code) { out_.push_back(code); }
  void u32(uint32_t v);

  int protocol_;
  std::vector<uint8_t> out_;
};

}  // namespace rlrun
