// ConfigTrust::kAccepted (`--trust`, issue 41): text the user accepted as a whole may name what
// the user's own text may; each value a --set would otherwise vouch for is printed on stderr
// first, with control characters escaped so the line shows exactly what will be used.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/trusted_values.hpp"

using namespace rlrun;

namespace {

// What `call` writes to file descriptor 2.
template <class F>
std::string stderr_of(F&& call) {
  std::fflush(stderr);
  FILE* captured = std::tmpfile();
  const int saved = dup(2);
  dup2(fileno(captured), 2);
  call();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  std::rewind(captured);
  std::string text;
  for (int c; (c = std::fgetc(captured)) != EOF;) text += static_cast<char>(c);
  std::fclose(captured);
  return text;
}

ConfigNode model_config(const std::string& yaml, ConfigTrust trust) {
  const ConfigNode root = ConfigNode::load_string(yaml, "m.zip:config.yaml", trust);
  root.set_trust_option("--trust");
  return root;
}

}  // namespace

TEST_CASE("trusted values: --trust accepts a program and prints it first", "[config][security]") {
  const std::string yaml = "sumo_binary: \"/opt/evil\\e[2K\\nsumo\"\n";
  ProgramPath program{"sumo"};
  const ConfigNode refused = model_config(yaml, ConfigTrust::kUntrusted);
  try {
    decode(refused.child("sumo_binary"), program);
    FAIL("an untrusted program was accepted");
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    CHECK(message.find("pass --set sumo_binary=") != std::string::npos);
    CHECK(message.find("Or pass --trust to accept everything m.zip:config.yaml names") !=
          std::string::npos);
  }
  CHECK(program.value == "sumo");

  const ConfigNode accepted = model_config(yaml, ConfigTrust::kAccepted);
  const std::string said = stderr_of([&] { decode(accepted.child("sumo_binary"), program); });
  CHECK(program.value == "/opt/evil\x1b[2K\nsumo");
  CHECK(said ==
        "trusting m.zip:config.yaml (--trust): sumo_binary = /opt/evil\\x1b[2K\\x0asumo: "
        "a program to run\n");
  // The default needs no word, and a --set over accepted text is the user's own: silent.
  ConfigNode defaulted = model_config("sumo_binary: sumo\n", ConfigTrust::kAccepted);
  program = ProgramPath{"sumo"};
  CHECK(stderr_of([&] { decode(defaulted.child("sumo_binary"), program); }).empty());
  defaulted.apply_override("sumo_binary=/usr/bin/sumo");
  program = ProgramPath{"sumo"};
  CHECK(stderr_of([&] { decode(defaulted.child("sumo_binary"), program); }).empty());
  CHECK(program.value == "/usr/bin/sumo");
}
