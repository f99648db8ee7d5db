#include "rlrun/envs/sumo/sumo_xml_guard.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <pugixml.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <string_view>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

constexpr uint64_t kMaxInputBytes = uint64_t{4} << 30;  // uncompressed, per file
constexpr int kMaxIncludeDepth = 16;
constexpr size_t kMaxIncludeTagBytes = 64 << 10;
constexpr size_t kMaxConfigBytes = 16 << 20;  // a .sumocfg is a few hundred bytes
constexpr unsigned kChunkBytes = 1 << 16;

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw ConfigError(path + ": " + why);
}

// The bytes of a SUMO input, inflated when it is gzip-compressed (zlib reads plain files as
// they are), in chunks, at most kMaxInputBytes of them.
class XmlBytes {
 public:
  explicit XmlBytes(const std::string& path) : path_(path) {
    // O_NONBLOCK: a FIFO must not block the open; it is refused below.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) refuse(path, "cannot read this SUMO input: " + describe_errno(errno));
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      refuse(path, "is not a regular file (a SUMO input must be one)");
    }
    file_ = gzdopen(fd, "rb");
    if (!file_) {
      ::close(fd);
      refuse(path, "cannot read this SUMO input (out of memory)");
    }
    gzbuffer(file_, kChunkBytes);
  }
  ~XmlBytes() { gzclose(file_); }
  XmlBytes(const XmlBytes&) = delete;
  XmlBytes& operator=(const XmlBytes&) = delete;

  // The next chunk; empty at the end.
  std::string_view next() {
    const int n = gzread(file_, buffer_.data(), kChunkBytes);
    if (n < 0) {
      int code = 0;
      const char* message = gzerror(file_, &code);
      refuse(path_,
             std::string("cannot read this SUMO input (") +
                 (code == Z_ERRNO ? describe_errno(errno) : quoted_text(message ? message : "?")) +
                 ")");
    }
    total_ += static_cast<uint64_t>(n);
    if (total_ > kMaxInputBytes)
      refuse(path_, "is larger than 4 GiB" + std::string(gzdirect(file_) ? "" : " uncompressed") +
                        "; rlrun does not check SUMO inputs that large");
    return {buffer_.data(), static_cast<size_t>(n)};
  }

 private:
  std::string path_;
  gzFile file_ = nullptr;
  std::string buffer_ = std::string(kChunkBytes, '\0');
  uint64_t total_ = 0;
};

// The encodings whose bytes the scanner below reads correctly (ASCII-compatible, one byte per
// ASCII character); others could hide a declaration from it.
bool ascii_compatible(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  static const char* const known[] = {"utf-8",  "utf8",        "us-ascii",     "ascii",
                                      "latin1", "iso-latin-1", "windows-1252", "cp1252"};
  if (std::find(std::begin(known), std::end(known), name) != std::end(known)) return true;
  return name.rfind("iso-8859-", 0) == 0 || name.rfind("iso8859-", 0) == 0;
}

// Decodes the five predefined entities and character references of an attribute value (what
// an XML parser hands SUMO as the value).
std::string decode_attribute(std::string_view raw) {
  std::string out;
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out.push_back(raw[i]);
      continue;
    }
    const size_t end = raw.find(';', i);
    if (end == std::string_view::npos) break;
    const std::string_view name = raw.substr(i + 1, end - i - 1);
    i = end;
    if (name == "amp")
      out.push_back('&');
    else if (name == "lt")
      out.push_back('<');
    else if (name == "gt")
      out.push_back('>');
    else if (name == "quot")
      out.push_back('"');
    else if (name == "apos")
      out.push_back('\'');
    else if (name.size() > 1 && name[0] == '#') {
      const bool hex = name[1] == 'x' || name[1] == 'X';
      const std::string digits(name.substr(hex ? 2 : 1));
      const unsigned long code = std::strtoul(digits.c_str(), nullptr, hex ? 16 : 10);
      if (code < 0x80) {
        out.push_back(static_cast<char>(code));
      } else if (code < 0x800) {
        out.push_back(static_cast<char>(0xC0 | (code >> 6)));
        out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
      } else if (code < 0x10000) {
        out.push_back(static_cast<char>(0xE0 | (code >> 12)));
        out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
        out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
      } else {
        out.push_back(static_cast<char>(0xF0 | ((code >> 18) & 0x07)));
        out.push_back(static_cast<char>(0x80 | ((code >> 12) & 0x3F)));
        out.push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
        out.push_back(static_cast<char>(0x80 | (code & 0x3F)));
      }
    }
  }
  return out;
}

// The value of attribute `name` in the text of a start tag ("include href='x.xml'/"), or "".
std::string attribute_value(std::string_view tag, std::string_view name) {
  for (size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    const bool starts = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
    size_t i = at + name.size();
    while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
    if (!starts || i >= tag.size() || tag[i] != '=') continue;
    ++i;
    while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
    if (i >= tag.size() || (tag[i] != '"' && tag[i] != '\'')) continue;
    const size_t end = tag.find(tag[i], i + 1);
    if (end == std::string_view::npos) continue;
    return decode_attribute(tag.substr(i + 1, end - i - 1));
  }
  return "";
}

// A byte-level reader of the XML structure that matters here: declarations (refused), the XML
// declaration's encoding, and <include> elements (collected). Comments, CDATA sections and
// attribute values are skipped as such, so a "<!" inside them is not mistaken for one.
class Scanner {
 public:
  explicit Scanner(std::string path) : path_(std::move(path)) {}

  void feed(std::string_view chunk) {
    size_t i = 0;
    if (!started_) i = check_start(chunk);
    for (; i < chunk.size(); ++i) {
      const char c = chunk[i];
      if (state_ == State::kText) {
        const void* lt = std::memchr(chunk.data() + i, '<', chunk.size() - i);
        const size_t stop =
            lt ? static_cast<size_t>(static_cast<const char*>(lt) - chunk.data()) : chunk.size();
        line_ += static_cast<int>(std::count(chunk.begin() + i, chunk.begin() + stop, '\n'));
        i = stop;
        if (lt) state_ = State::kOpen;
        continue;
      }
      if (c == '\n') ++line_;
      step(c);
    }
  }

  const std::vector<std::string>& includes() const { return includes_; }

 private:
  enum class State { kText, kOpen, kBang, kComment, kCdata, kPi, kName, kTag, kInclude };

  // The first bytes: a UTF-8 byte order mark is skipped; UTF-16/32 and EBCDIC are refused.
  size_t check_start(std::string_view chunk) {
    started_ = true;
    const auto byte = [&](size_t k) {
      return k < chunk.size() ? static_cast<unsigned char>(chunk[k]) : 0x100u;
    };
    if (byte(0) == 0xEF && byte(1) == 0xBB && byte(2) == 0xBF) return 3;
    if ((byte(0) == 0xFE && byte(1) == 0xFF) || (byte(0) == 0xFF && byte(1) == 0xFE) ||
        std::memchr(chunk.data(), '\0', std::min<size_t>(chunk.size(), 4)))
      refuse(path_,
             "is UTF-16 or UTF-32 encoded; rlrun checks SUMO inputs byte by byte and takes "
             "them in UTF-8 (or another ASCII-compatible encoding)");
    if (byte(0) == 0x4C && byte(1) == 0x6F && byte(2) == 0xA7 && byte(3) == 0x94)
      refuse(path_, "is EBCDIC encoded; rlrun takes SUMO inputs in UTF-8");
    return 0;
  }

  [[noreturn]] void refuse_declaration() const {
    refuse(path_ + ":" + std::to_string(line_),
           "a markup declaration (<!" + quoted_text(bang_, 16) +
               "...): rlrun refuses DOCTYPE and ENTITY declarations in SUMO inputs (an entity "
               "can expand to gigabytes or read another file; SUMO's formats need none). Remove "
               "the <!DOCTYPE ...> part");
  }

  void step(char c) {
    switch (state_) {
      case State::kText: break;  // handled in feed()
      case State::kOpen:
        if (c == '!') {
          bang_.clear();
          state_ = State::kBang;
        } else if (c == '?') {
          pi_.clear();
          before_[1] = 0;
          state_ = State::kPi;
        } else {
          name_.assign(1, c);
          state_ = c == '/' ? State::kTag : State::kName;
        }
        break;
      case State::kBang:
        bang_.push_back(c);
        if (bang_ == "--" || bang_ == "[CDATA[") {
          state_ = bang_ == "--" ? State::kComment : State::kCdata;
          before_[0] = before_[1] = 0;
        } else if (std::string_view("--").substr(0, bang_.size()) != bang_ &&
                   std::string_view("[CDATA[").substr(0, bang_.size()) != bang_) {
          // Its keyword (DOCTYPE, ENTITY) is read first, for the message.
          if (std::isalpha(static_cast<unsigned char>(c)) && bang_.size() < 12) break;
          refuse_declaration();
        }
        break;
      case State::kComment: end_after(c, "-->"); break;
      case State::kCdata: end_after(c, "]]>"); break;
      case State::kPi:
        if (c == '>' && before_[1] == '?') {
          check_xml_declaration();
          state_ = State::kText;
        }
        before_[1] = c;
        if (pi_.size() < 4096) pi_.push_back(c);  // enough of an XML declaration
        break;
      case State::kName:
        if (std::isspace(static_cast<unsigned char>(c)) || c == '/' || c == '>') {
          const bool include =
              name_ == "include" ||
              (name_.size() > 8 && name_.compare(name_.size() - 8, 8, ":include") == 0);
          tag_.clear();
          quote_ = 0;
          state_ = include ? State::kInclude : State::kTag;
          step(c);
        } else {
          name_.push_back(c);
        }
        break;
      case State::kTag:
      case State::kInclude:
        if (state_ == State::kInclude) {
          tag_.push_back(c);
          if (tag_.size() > kMaxIncludeTagBytes)
            refuse(path_ + ":" + std::to_string(line_), "an <include> element longer than 64 KiB");
        }
        if (quote_) {
          if (c == quote_) quote_ = 0;
        } else if (c == '"' || c == '\'') {
          quote_ = c;
        } else if (c == '>') {
          if (state_ == State::kInclude) {
            const std::string href = attribute_value(tag_, "href");
            if (!href.empty()) includes_.push_back(href);
          }
          state_ = State::kText;
        }
        break;
    }
  }

  // Ends a comment ("-->") or CDATA section ("]]>") at its three-character terminator.
  void end_after(char c, const char* terminator) {
    if (c == terminator[2] && before_[0] == terminator[0] && before_[1] == terminator[1]) {
      state_ = State::kText;
      return;
    }
    before_[0] = before_[1];
    before_[1] = c;
  }

  // <?xml version="1.0" encoding="..."?>: the encoding must be one whose bytes the scanner reads.
  void check_xml_declaration() {
    if (pi_.rfind("xml", 0) != 0 || pi_.size() < 4 ||
        !std::isspace(static_cast<unsigned char>(pi_[3])))
      return;
    std::string attributes(1, ' ');  // appended, not " " + ...: GCC 12 warns -Wrestrict, falsely
    attributes.append(pi_, 3);
    const std::string encoding = attribute_value(attributes, "encoding");
    if (!encoding.empty() && !ascii_compatible(encoding))
      refuse(path_,
             "declares encoding '" + quoted_text(encoding, 40) +
                 "'; rlrun takes SUMO inputs in UTF-8, US-ASCII, ISO-8859-* or windows-1252");
  }

  std::string path_;
  State state_ = State::kText;
  bool started_ = false;
  int line_ = 1;
  char before_[2] = {0, 0};  // the two characters before, inside a comment, CDATA, PI
  char quote_ = 0;           // inside an attribute value delimited by this quote
  std::string bang_, pi_, name_, tag_;
  std::vector<std::string> includes_;
};

// Checks `path` and, recursively, what it includes. `chain` holds the including files (for
// cycles and messages), `done` the files checked already.
void check_file(const std::string& path, std::vector<std::string>& chain,
                std::set<std::string>& done) {
  std::error_code ec;
  const std::string key = fs::weakly_canonical(path, ec).string();
  if (std::find(chain.begin(), chain.end(), key) != chain.end())
    refuse(path, "includes itself (<include href> in a cycle: " + chain.front() + " -> ...)");
  if (!done.insert(key).second) return;
  if (chain.size() >= static_cast<size_t>(kMaxIncludeDepth))
    refuse(path, "is included more than 16 levels deep (from " + chain.front() + ")");
  Scanner scanner(path);
  XmlBytes bytes(path);
  for (std::string_view chunk = bytes.next(); !chunk.empty(); chunk = bytes.next())
    scanner.feed(chunk);
  chain.push_back(key);
  const fs::path base = fs::path(path).parent_path();
  for (const std::string& href : scanner.includes()) {
    const fs::path target = fs::path(href).is_absolute() ? fs::path(href) : base / href;
    if (!fs::exists(target, ec)) continue;  // SUMO reports a missing file
    try {
      check_file(target.string(), chain, done);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string(e.what()) + " (included by " + path + ")");
    }
  }
  chain.pop_back();
}

// ${NAME} replaced by the environment's value, as SUMO does in configuration values.
std::string substitute_environment(const std::string& text) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    const size_t open = text.find("${", i);
    const size_t close = open == std::string::npos ? open : text.find('}', open);
    if (close == std::string::npos) break;
    out += text.substr(i, open - i);
    const char* value = std::getenv(text.substr(open + 2, close - open - 2).c_str());
    out += value ? value : "";
    i = close + 1;
  }
  return out + text.substr(std::min(i, text.size()));
}

// The files a configuration value may name: the whole value, its comma-separated items (SUMO's
// file lists) and its space-separated words, each trimmed.
std::set<std::string> candidate_files(const std::string& value) {
  std::set<std::string> out;
  const auto add_split = [&](const std::string& text, char separator) {
    size_t start = 0;
    while (start <= text.size()) {
      const size_t end = std::min(text.find(separator, start), text.size());
      std::string item = text.substr(start, end - start);
      const size_t first = item.find_first_not_of(" \t\r\n");
      const size_t last = item.find_last_not_of(" \t\r\n");
      if (first != std::string::npos) out.insert(item.substr(first, last - first + 1));
      start = end + 1;
    }
  };
  for (const std::string& text : {value, substitute_environment(value)}) {
    add_split(text, '\n');
    add_split(text, ',');
    add_split(text, ' ');
  }
  return out;
}

// Options that name files SUMO writes (tripinfo-output, output-prefix, log, error-log, ...).
bool names_an_output(const std::string& option, const std::string& section) {
  const auto ends_with = [&](const char* suffix) {
    const size_t n = std::strlen(suffix);
    return option.size() >= n && option.compare(option.size() - n, n, suffix) == 0;
  };
  return section == "output" || section == "report" || ends_with("output") || ends_with("log") ||
         ends_with("prefix");
}

}  // namespace

void check_sumo_xml(const std::string& path) {
  std::vector<std::string> chain;
  std::set<std::string> done;
  check_file(path, chain, done);
}

std::string read_sumo_xml(const std::string& path, size_t max_bytes) {
  check_sumo_xml(path);
  XmlBytes bytes(path);
  std::string text;
  for (std::string_view chunk = bytes.next(); !chunk.empty(); chunk = bytes.next()) {
    if (text.size() + chunk.size() > max_bytes)
      refuse(path, "is larger than " + std::to_string(max_bytes >> 20) + " MiB");
    text.append(chunk);
  }
  return text;
}

void check_sumo_config(const std::string& sumocfg) {
  const std::string text = read_sumo_xml(sumocfg, kMaxConfigBytes);
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
  if (!parsed)
    refuse(sumocfg,
           std::string("not a readable SUMO configuration (") + parsed.description() + ")");
  // Every option's value (SUMO's OptionsLoader reads `value` or `v` of any element).
  struct Option {
    std::string name, section, value;
  };
  struct Walker : pugi::xml_tree_walker {
    std::vector<Option> options;
    bool for_each(pugi::xml_node& node) override {
      for (const char* key : {"value", "v"})
        if (const pugi::xml_attribute a = node.attribute(key))
          options.push_back({node.name(), node.parent().name(), a.as_string()});
      return true;
    }
  } walker;
  doc.traverse(walker);
  const fs::path base = fs::path(sumocfg).parent_path();
  for (const Option& option : walker.options) {
    if (names_an_output(option.name, option.section)) continue;
    for (const std::string& candidate : candidate_files(option.value)) {
      const fs::path file =
          fs::path(candidate).is_absolute() ? fs::path(candidate) : base / candidate;
      std::error_code ec;
      const fs::file_status status = fs::status(file, ec);
      if (ec || !fs::exists(status) || fs::is_directory(status)) continue;
      const std::string where =
          " (named by " + sumocfg + ", <" + quoted_text(option.name, 60) + ">)";
      if (!fs::is_regular_file(status))
        refuse(file.string(), "is not a regular file (a SUMO input must be one)" + where);
      try {
        check_sumo_xml(file.string());
      } catch (const ConfigError& e) {
        throw ConfigError(e.what() + where);
      }
    }
  }
}

void check_sumo_command_inputs(const std::vector<std::string>& args) {
  static const char* const file_lists[] = {"-n", "--net-file",         "-r", "--route-files",
                                           "-a", "--additional-files", "-w", "--weight-files"};
  for (size_t i = 0; i + 1 < args.size(); ++i) {
    const std::string& option = args[i];
    if (option == "-c" || option == "--configuration-file") {
      check_sumo_config(args[i + 1]);
    } else if (std::find(std::begin(file_lists), std::end(file_lists), option) !=
               std::end(file_lists)) {
      std::error_code ec;
      for (const std::string& file : candidate_files(args[i + 1]))
        if (fs::exists(file, ec)) check_sumo_xml(file);
    }
  }
}

}  // namespace rlrun
