#include "rlrun/runtime/workflows/zoo/python_literal.hpp"

#include <cctype>
#include <cstdlib>

#include "rlrun/core/quoted_text.hpp"

namespace rlrun::zoo {

PyValue::PyValue() = default;
PyValue::PyValue(const PyValue&) = default;
PyValue::PyValue(PyValue&&) noexcept = default;
PyValue& PyValue::operator=(const PyValue&) = default;
PyValue& PyValue::operator=(PyValue&&) noexcept = default;
PyValue::~PyValue() = default;

std::string PyValue::describe() const {
  switch (kind) {
    case Kind::kNone: return "None";
    case Kind::kBool: return boolean ? "True" : "False";
    case Kind::kNumber: return "the number " + quoted_text(text);
    case Kind::kString: return "the string '" + quoted_text(text) + "'";
    case Kind::kList: return "a list";
    case Kind::kDict: return "a dict";
    case Kind::kName: return "the name " + quoted_text(text);
  }
  return "a value";
}

namespace {

// Nesting beyond this is not a zoo file (and would recurse without bound).
constexpr int kMaxDepth = 32;

class Parser {
 public:
  explicit Parser(const std::string& source) : s_(source) {}

  PyValue whole() {
    PyValue v = value(0);
    skip_space();
    if (pos_ != s_.size())
      fail("unexpected '" + quoted_text(s_.substr(pos_, 1)) + "' after the expression");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw PythonLiteralError(message, pos_);
  }

  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool peek(char c) {
    skip_space();
    return pos_ < s_.size() && s_[pos_] == c;
  }
  void expect(char c) {
    if (!peek(c)) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  static bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
  static bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

  PyValue value(int depth) {
    if (depth > kMaxDepth)
      fail("nested too deeply (more than " + std::to_string(kMaxDepth) + " levels)");
    skip_space();
    if (pos_ >= s_.size()) fail("expected a value, found the end of the text");
    const char c = s_[pos_];
    if (c == '[' || c == '(') return sequence(depth, c == '[' ? ']' : ')');
    if (c == '{') return braces(depth);
    if (c == '\'' || c == '"') return string();
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.')
      return number();
    if (name_start(c)) return named(depth);
    // (built with append, not "'" + std::string: GCC 12 warns -Wrestrict on that spelling)
    std::string message = "'";
    message.append(quoted_text(std::string(1, c))).append("' is not part of a literal rlrun reads");
    fail(message);
  }

  PyValue sequence(int depth, char close) {
    PyValue v;
    v.kind = PyValue::Kind::kList;
    v.offset = pos_++;
    while (!peek(close)) {
      v.items.push_back(value(depth + 1));
      if (!peek(close)) expect(',');
    }
    ++pos_;
    return v;
  }

  PyValue braces(int depth) {
    PyValue v;
    v.kind = PyValue::Kind::kDict;
    v.offset = pos_++;
    while (!peek('}')) {
      skip_space();
      const std::size_t key_at = pos_;
      const PyValue key = value(depth + 1);
      if (key.kind != PyValue::Kind::kString) {
        pos_ = key_at;
        fail("dict keys must be strings, found " + key.describe());
      }
      expect(':');
      add_entry(v, key.text, value(depth + 1), key_at);
      if (!peek('}')) expect(',');
    }
    ++pos_;
    return v;
  }

  void add_entry(PyValue& dict, const std::string& key, PyValue value, std::size_t at) {
    if (dict.find(key)) {
      pos_ = at;
      fail("key '" + quoted_text(key) + "' given twice");
    }
    dict.entries.emplace_back(key, std::move(value));
  }

  PyValue string() {
    PyValue v;
    v.kind = PyValue::Kind::kString;
    v.offset = pos_;
    const char quote = s_[pos_++];
    while (pos_ < s_.size() && s_[pos_] != quote) {
      if (s_[pos_] == '\\') fail("escapes in strings are not read");
      v.text += s_[pos_++];
    }
    if (pos_ >= s_.size()) fail("unterminated string");
    ++pos_;
    return v;
  }

  PyValue number() {
    PyValue v;
    v.kind = PyValue::Kind::kNumber;
    v.offset = pos_;
    std::size_t end = pos_;
    if (s_[end] == '-' || s_[end] == '+') ++end;
    bool integral = true;
    while (end < s_.size() &&
           (std::isdigit(static_cast<unsigned char>(s_[end])) || s_[end] == '.' || s_[end] == 'e' ||
            s_[end] == 'E' || s_[end] == '_' ||
            ((s_[end] == '-' || s_[end] == '+') && (s_[end - 1] == 'e' || s_[end - 1] == 'E')))) {
      if (s_[end] == '.' || s_[end] == 'e' || s_[end] == 'E') integral = false;
      ++end;
    }
    std::string text;
    for (std::size_t i = pos_; i < end; ++i)
      if (s_[i] != '_') text += s_[i];
    char* parsed_end = nullptr;
    const double number = std::strtod(text.c_str(), &parsed_end);
    if (text.empty() || parsed_end != text.c_str() + text.size())
      fail("'" + text + "' is not a number");
    v.number = number;
    v.integral = integral;
    v.text = text;
    pos_ = end;
    return v;
  }

  PyValue named(int depth) {
    PyValue v;
    v.offset = pos_;
    std::string name;
    while (true) {
      const std::size_t start = pos_;
      while (pos_ < s_.size() && name_char(s_[pos_])) ++pos_;
      name += s_.substr(start, pos_ - start);
      if (pos_ < s_.size() && s_[pos_] == '.' && pos_ + 1 < s_.size() && name_start(s_[pos_ + 1])) {
        name += '.';
        ++pos_;
        continue;
      }
      break;
    }
    if (name == "True" || name == "False") {
      v.kind = PyValue::Kind::kBool;
      v.boolean = name == "True";
      return v;
    }
    if (name == "None") return v;
    if (peek('(')) {
      if (name != "dict") {
        pos_ = v.offset;
        fail("calls other than dict(...) are not read (found " + name +
             "(...)); rlrun never "
             "evaluates Python");
      }
      return call_dict(depth, v.offset);
    }
    skip_space();
    if (pos_ < s_.size() && (s_[pos_] == '[' || s_[pos_] == '.'))
      fail("subscripts and attributes of values are not read");
    v.kind = PyValue::Kind::kName;
    v.text = name;
    return v;
  }

  PyValue call_dict(int depth, std::size_t offset) {
    PyValue v;
    v.kind = PyValue::Kind::kDict;
    v.offset = offset;
    expect('(');
    while (!peek(')')) {
      skip_space();
      const std::size_t key_at = pos_;
      std::string key;
      while (pos_ < s_.size() && name_char(s_[pos_])) key += s_[pos_++];
      if (key.empty() || !name_start(key[0])) {
        pos_ = key_at;
        fail("dict(...) takes keyword arguments only (key=value)");
      }
      expect('=');
      add_entry(v, key, value(depth + 1), key_at);
      if (!peek(')')) expect(',');
    }
    ++pos_;
    return v;
  }

  const std::string& s_;
  std::size_t pos_ = 0;
};

}  // namespace

PyValue parse_python_literal(const std::string& source) { return Parser(source).whole(); }

}  // namespace rlrun::zoo
