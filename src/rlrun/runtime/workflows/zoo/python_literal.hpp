#pragma once
// A reader for the Python expressions rl-zoo keeps in strings (`policy_kwargs: "dict(...)"`,
// `normalize: "{'norm_obs': True}"`), which the zoo passes to eval() (rl_zoo3/exp_manager.py
// _preprocess_hyperparams). rlrun never evaluates them: this parser accepts only the literal
// subset the zoo's files use and refuses everything else with the offset of the problem:
//   numbers (int, float, signed, 1e-3), True / False / None, 'strings' / "strings",
//   [lists], (tuples), {'key': value} dicts, dict(key=value, ...) calls,
//   and dotted names (nn.ReLU, th.nn.Tanh) as values, which the caller interprets.
// Any other call (e.g. `__import__('os')`), operator, subscript or keyword is an error.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rlrun::zoo {

struct PyValue {
  enum class Kind { kNone, kBool, kNumber, kString, kList, kDict, kName };
  Kind kind = Kind::kNone;
  bool boolean = false;
  double number = 0.0;
  bool integral = false;       // a number written without '.', 'e' (an int in Python)
  std::string text;            // kString: the string; kName: the dotted name; kNumber: as written
  std::vector<PyValue> items;  // kList
  std::vector<std::pair<std::string, PyValue>> entries;  // kDict, in written order
  std::size_t offset = 0;                                // where it starts in the source

  // Defined in the .cpp, where PyValue is complete: `entries` holds pairs with a PyValue,
  // which clang (before 16) refuses to destroy or copy inside the class's own definition.
  PyValue();
  PyValue(const PyValue&);
  PyValue(PyValue&&) noexcept;
  PyValue& operator=(const PyValue&);
  PyValue& operator=(PyValue&&) noexcept;
  ~PyValue();

  const PyValue* find(const std::string& key) const {
    for (const auto& e : entries)
      if (e.first == key) return &e.second;
    return nullptr;
  }
  // "a list", "the name nn.ReLU", ... for messages.
  std::string describe() const;
};

// A refused expression: what is wrong and at which character (0-based) of the source.
class PythonLiteralError : public std::runtime_error {
 public:
  PythonLiteralError(const std::string& message, std::size_t offset)
      : std::runtime_error(message), offset_(offset) {}
  std::size_t offset() const { return offset_; }

 private:
  std::size_t offset_;
};

// Parses one whole expression. Throws PythonLiteralError.
PyValue parse_python_literal(const std::string& source);

}  // namespace rlrun::zoo
