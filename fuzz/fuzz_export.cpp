// Fuzz target: `rlrun export` of a model file built from arbitrary bytes (deploy/: the C and
// ONNX writers, runtime/io/model_graph.hpp). A model file is untrusted and its meta.json strings
// reach the generated files: the C header's comment, ONNX metadata_props (docs/security.md).
// Refusing is fine (RuntimeFailure, ConfigError, UsageError, ExportError); a crash, sanitizer
// report or hang is a bug, and so is output that breaks an invariant below (the target aborts):
//   C:    policy.h is the writer's comment, then only the writer's own lines; the comment's
//         text is printable ASCII with `*` only as the ` * ` that starts a line; no backslash
//         and no `??` anywhere in policy.h or policy.c (no line splice, no trigraph); policy.c
//         has one comment, printable ASCII, and no `nan` or `inf` (every number a C literal);
//   ONNX: every string field the writer fills (metadata_props, producer, names) is valid
//         UTF-8, and there is one metadata entry per metadata key of the graph.
//
// Input: the model file's members, each `@@ <name>\n<data>`, separated by `\n@@ ` (so that
// inserting or removing bytes in meta.json keeps the structure: fuzz_model.cpp covers zip
// framing). They are stored uncompressed in a zip, loaded as `rlrun export` loads them
// (load_model), and the graph (with and without the value output) goes through both writers.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "../tests/core/crafted_zip.hpp"
#include "fuzz_limits.hpp"
#include "private_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/deploy/c_writer.hpp"
#include "rlrun/deploy/onnx_writer.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

using namespace rlrun;
using rlrun::testing::CraftedMember;

namespace {

[[noreturn]] void violated(const std::string& what, std::string_view output) {
  std::fprintf(stderr, "fuzz_export: invariant violated: %s\n--- output ---\n%.*s\n", what.c_str(),
               static_cast<int>(std::min<size_t>(output.size(), 4000)), output.data());
  std::abort();
}

std::vector<CraftedMember> members_from(std::string_view input) {
  std::vector<CraftedMember> members;
  std::string text = "\n";  // (appended: GCC 12 warns -Wrestrict on "literal" + string)
  text += input;
  const std::string separator = "\n@@ ";
  for (size_t at = text.find(separator); at != std::string::npos;) {
    const size_t begin = at + separator.size();
    const size_t next = text.find(separator, begin);
    const std::string_view part = std::string_view(text).substr(
        begin, next == std::string::npos ? std::string::npos : next - begin);
    const size_t newline = part.find('\n');
    if (newline != std::string_view::npos && newline > 0) {
      CraftedMember m{std::string(part.substr(0, newline)), {}};
      m.data.assign(part.begin() + static_cast<std::ptrdiff_t>(newline) + 1, part.end());
      m.deflate = false;
      members.push_back(std::move(m));
    }
    at = next;
  }
  return members;
}

bool printable_ascii(char c) { return c == '\n' || (c >= 0x20 && c < 0x7F); }

size_t count(std::string_view text, std::string_view what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string_view::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

void check_c(const CSource& c) {
  for (const std::string* file : {&c.header, &c.source}) {
    if (file->find('\\') != std::string::npos) violated("a backslash in generated C", *file);
    if (file->find("?\?") != std::string::npos)
      violated("a '?\?' (trigraph) in generated C", *file);
    for (char ch : *file)
      if (!printable_ascii(ch))
        violated("a byte that is not printable ASCII in generated C", *file);
  }
  const std::string& h = c.header;
  if (h.rfind("/* Policy exported by `rlrun export --format c`", 0) != 0)
    violated("policy.h does not start with the writer's comment", h);
  const size_t end = h.find("*/");
  if (end == std::string::npos) violated("policy.h's comment does not end", h);
  // Inside the comment: `*` only as the ` * ` that starts a continuation line.
  const std::string_view comment = std::string_view(h).substr(2, end - 2);
  for (size_t at = comment.find('*'); at != std::string_view::npos; at = comment.find('*', at + 1))
    if (at < 2 || comment.substr(at - 2, 2) != "\n ")
      violated("a '*' inside policy.h's comment", h);
  // After it: only the writer's own lines.
  static const std::regex allowed(
      "|#ifndef RLRUN_POLICY_H|#define RLRUN_POLICY_H|#define POLICY_(OBS|ACTION)_DIM [0-9]+|"
      "#ifdef __cplusplus|extern \"C\" \\{|#endif|\\}|#endif /\\* RLRUN_POLICY_H \\*/|"
      "void policy_act\\(const float \\*obs, float \\*action\\);");
  const std::string rest = h.substr(end + 2);
  size_t line_start = 0;
  for (size_t nl = rest.find('\n'); nl != std::string::npos; nl = rest.find('\n', line_start)) {
    if (!std::regex_match(rest.substr(line_start, nl - line_start), allowed))
      violated("a line in policy.h the writer does not write", h);
    line_start = nl + 1;
  }
  const std::string& s = c.source;
  if (count(s, "/*") != 1 || count(s, "*/") != 1) violated("policy.c has another comment", s);
  if (s.find("nan") != std::string::npos || s.find("inf") != std::string::npos)
    violated("policy.c holds a NaN or infinite literal", s);
}

// A minimal protobuf reader: each field of `message` (field number, wire type, payload).
struct Field {
  int number;
  int type;
  std::string_view bytes;  // wire type 2
};
bool read_varint(std::string_view& in, uint64_t& v) {
  v = 0;
  for (int shift = 0; shift < 64 && !in.empty(); shift += 7) {
    const auto b = static_cast<uint8_t>(in.front());
    in.remove_prefix(1);
    v |= static_cast<uint64_t>(b & 0x7F) << shift;
    if (!(b & 0x80)) return true;
  }
  return false;
}
std::vector<Field> fields(std::string_view message) {
  std::vector<Field> out;
  while (!message.empty()) {
    uint64_t key = 0, value = 0;
    if (!read_varint(message, key)) violated("an unreadable protobuf key", message);
    Field f{static_cast<int>(key >> 3), static_cast<int>(key & 7), {}};
    if (f.type == 0 && !read_varint(message, value)) violated("an unreadable varint", message);
    if (f.type == 1 || f.type == 5) {
      const size_t n = f.type == 1 ? 8 : 4;
      if (message.size() < n) violated("a truncated protobuf field", message);
      message.remove_prefix(n);
    }
    if (f.type == 2) {
      if (!read_varint(message, value) || value > message.size())
        violated("a truncated protobuf field", message);
      f.bytes = message.substr(0, value);
      message.remove_prefix(value);
    }
    if (f.type != 0 && f.type != 1 && f.type != 2 && f.type != 5)
      violated("a protobuf wire type the writer does not use", message);
    out.push_back(f);
  }
  return out;
}
void check_text(const Field& f, const char* what) {
  if (f.type != 2 || !valid_utf8(f.bytes))
    violated(std::string(what) + " is not UTF-8 text", f.bytes);
}

// onnx/onnx.proto: ModelProto 2 producer_name, 3 producer_version, 6 doc_string, 7 graph,
// 14 metadata_props (StringStringEntryProto 1 key, 2 value); GraphProto 1 node (NodeProto 1
// input, 2 output, 3 name, 4 op_type), 2 name, 5 initializer (TensorProto 8 name), 11 input
// and 12 output (ValueInfoProto 1 name).
void check_onnx(const std::string& bytes, const PolicyGraph& graph) {
  size_t metadata = 0;
  for (const Field& m : fields(bytes)) {
    if (m.number == 2 || m.number == 3 || m.number == 6) check_text(m, "a ModelProto string");
    if (m.number == 14) {
      ++metadata;
      for (const Field& e : fields(m.bytes)) check_text(e, "a metadata_props entry");
    }
    if (m.number != 7) continue;
    for (const Field& g : fields(m.bytes)) {
      if (g.number == 2) check_text(g, "the graph's name");
      for (const Field& x : g.number == 1 || g.number == 5 || g.number == 11 || g.number == 12
                                ? fields(g.bytes)
                                : std::vector<Field>{}) {
        if (g.number == 1 && x.number >= 1 && x.number <= 4) check_text(x, "a node's name");
        if (g.number == 5 && x.number == 8) check_text(x, "an initializer's name");
        if ((g.number == 11 || g.number == 12) && x.number == 1)
          check_text(x, "an input or output name");
      }
    }
  }
  if (metadata != graph.metadata.size()) violated("metadata_props lost or added an entry", bytes);
}

void export_like_the_cli(const std::string& path) {
  try {
    const ModelFile header = read_model_header(path);
    if (!fuzz::fuzzable_config(ConfigNode::load_string(header.config_yaml, "config.yaml"))) return;
    const LoadedModel loaded = load_model(path, builtin_registry(), {}, {}, ModelEnv::kSpacesOnly);
    for (const bool with_value : {false, true}) {
      const PolicyGraph graph = build_model_graph(loaded, with_value);
      check_c(c_policy_source(graph));
      check_onnx(onnx_model_bytes(graph), graph);
    }
  } catch (const RuntimeFailure&) {
  } catch (const ConfigError&) {
  } catch (const UsageError&) {
  } catch (const ExportError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<CraftedMember> members =
      members_from(std::string_view(reinterpret_cast<const char*>(data), size));
  if (members.empty()) return 0;
  const std::string& path = fuzz::private_file("export", "model.zip");
  try {
    rlrun::testing::write_crafted_zip(path, members);
  } catch (const std::runtime_error&) {
    return 0;  // a name libzip will not write (duplicates, NUL)
  }
  export_like_the_cli(path);
  return 0;
}
