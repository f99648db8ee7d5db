#include "rlrun/env/wrapper.hpp"

#include <cxxabi.h>

#include <cstdlib>
#include <memory>
#include <typeinfo>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

std::string wrapper_class_name(const Wrapper& w) {
  const char* mangled = typeid(w).name();
  int status = 0;
  std::unique_ptr<char, void (*)(void*)> demangled(
      abi::__cxa_demangle(mangled, nullptr, nullptr, &status), std::free);
  std::string name = status == 0 && demangled ? demangled.get() : mangled;
  const size_t colon = name.rfind("::");
  return colon == std::string::npos ? name : name.substr(colon + 2);
}

namespace {

[[noreturn]] void refuse(const Wrapper& w) {
  throw ExportError("the wrapper " + wrapper_class_name(w) + " of " + w.id() +
                    " cannot be exported: it keeps state between steps or has no export; train "
                    "without it to deploy the policy");
}

}  // namespace

std::string Wrapper::export_observation(PolicyGraph& /*graph*/, const std::string& obs) const {
  if (!exports_unchanged()) refuse(*this);
  return obs;
}

std::string Wrapper::export_action(PolicyGraph& /*graph*/, const std::string& action) const {
  if (!exports_action_unchanged()) refuse(*this);
  return action;
}

}  // namespace rlrun
