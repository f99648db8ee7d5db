#include "rlrun/envs/sumo/sumo_connection.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/process_settings.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/envs/sumo/sumo_xml_guard.hpp"

namespace rlrun {

std::vector<std::string> sumo_arguments(const SumoLaunch& launch) {
  std::vector<std::string> args = launch.inputs;
  if (args.empty()) args = {"-c", launch.config, "--end", std::to_string(launch.end_time)};
  args.insert(args.end(), {"--seed", std::to_string(launch.seed % 2147483647ULL), "--scale",
                           std::to_string(launch.scale), "--no-step-log", "true", "--no-warnings",
                           "true", "--duration-log.disable", "true"});
  // No XML Schema is loaded: a scenario file may name any local .xsd, which Xerces reads with
  // its entities (docs/security.md, "SUMO scenarios"); the command line outranks the .sumocfg.
  // Nor is SUMO_HOME needed then (SUMO looks for its own schemas there, or on the web).
  args.insert(args.end(), {"--xml-validation", "never", "--xml-validation.net", "never",
                           "--xml-validation.routes", "never"});
  args.insert(args.end(), launch.extra_args.begin(), launch.extra_args.end());
  return args;
}

void check_sumo_launch(const SumoLaunch& launch) {
  check_sumo_command_inputs(sumo_arguments(launch));
}

namespace {

using StartFunction = traffic::SumoConnection* (*)(const std::vector<std::string>*, std::string*);

}  // namespace

// A file built and installed beside rlrun (the libsumo module, the SUMO worker program):
// `chosen` when not empty, else found relative to the binary holding this
// code (core/shipped_data.hpp; no build path is compiled in): beside it (build/rlrun), in
// <prefix>/lib of an install (P/bin/rlrun), or one or two levels up in a build tree
// (build/tests/rlrun_tests, build/python/rlrun/_core*.so). The last candidate names the file
// in the error when none exists.
std::string rlrun_helper_path(const char* name, const std::string& chosen) {
  if (!chosen.empty()) return chosen;
  const std::filesystem::path dir = running_binary_dir();
  const std::filesystem::path places[] = {dir, dir.parent_path() / RLRUN_INSTALL_LIBDIR,
                                          dir.parent_path(), dir.parent_path().parent_path()};
  std::error_code ec;
  for (const auto& place : places)
    if (std::filesystem::exists(place / name, ec)) return (place / name).string();
  return (places[1] / name).string();
}

namespace {

std::string libsumo_module_path() {
  return rlrun_helper_path("librlrun_libsumo.so", process_settings().libsumo_module);
}

void* libsumo_module() {
  static std::mutex mutex;
  static void* handle = nullptr;
  std::lock_guard lock(mutex);
  if (handle) return handle;
  const std::string path = libsumo_module_path();
  // Loaded once and never unloaded: SUMO's globals live as long as rlrun.
  handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = dlerror();
    throw RuntimeFailure(std::string("backend: libsumo needs ") + path + ", which did not load (" +
                         (error ? error : "unknown error") +
                         "); it is built with rlrun and needs SUMO's libsumocpp (Debian package "
                         "'sumo'). backend: traci needs only the sumo program");
  }
  return handle;
}

}  // namespace

void* libsumo_module_symbol(const char* name) {
  void* symbol = dlsym(libsumo_module(), name);
  if (!symbol)
    throw RuntimeFailure(libsumo_module_path() + " has no " + name +
                         ": not rlrun's libsumo module");
  return symbol;
}

std::unique_ptr<traffic::SumoConnection> start_sumo(const std::string& backend,
                                                    const SumoLaunch& launch) {
  check_sumo_launch(launch);
  if (backend == "traci") return start_traci_connection(launch);
  if (backend != "libsumo")
    throw RuntimeFailure("unknown SUMO backend '" + backend + "' (traci or libsumo)");
  if (launch.inputs.empty() && !std::filesystem::exists(launch.config))
    throw RuntimeFailure("SUMO scenario " + launch.config + " does not exist");
  std::vector<std::string> command{"sumo"};
  for (std::string& a : sumo_arguments(launch)) command.push_back(std::move(a));
  std::string error;
  const auto entry =
      reinterpret_cast<StartFunction>(libsumo_module_symbol("rlrun_start_libsumo_connection"));
  traffic::SumoConnection* connection = entry(&command, &error);
  if (!connection) throw RuntimeFailure(error);
  return std::unique_ptr<traffic::SumoConnection>(connection);
}

}  // namespace rlrun
