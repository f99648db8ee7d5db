#pragma once
// A component's decoded Config (an env's kwargs, a wrapper's or an algorithm's parameters)
// behind one type, so the registry can hand it from the parser to the factory: a section is
// decoded and checked once, when the experiment is parsed, and every env copy, evaluation env
// or model reload is built from the same typed value. `resolved()` is the Config written back
// with every default filled in (the run's config.yaml).
#include <yaml-cpp/yaml.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>

#include "rlrun/core/config_fields.hpp"

namespace rlrun {

class AnyConfig {
 public:
  AnyConfig() = default;

  template <class C>
  static AnyConfig of(C config) {
    AnyConfig any;
    any.resolved_ = write_config(config);
    any.value_ = std::make_shared<const C>(std::move(config));
    any.type_ = &typeid(C);
    return any;
  }
  // A value whose type is not known here (a plugin's Config lives in its library): the
  // checked YAML itself, re-read by the plugin's factory.
  static AnyConfig of_yaml(YAML::Node checked, YAML::Node resolved) {
    AnyConfig any;
    any.resolved_ = std::move(resolved);
    any.value_ = std::make_shared<const YAML::Node>(std::move(checked));
    any.type_ = &typeid(YAML::Node);
    return any;
  }

  template <class C>
  const C& get() const {
    if (!type_ || *type_ != typeid(C))
      throw std::logic_error(std::string("AnyConfig: holds ") +
                             (type_ ? type_->name() : "nothing") + ", not " + typeid(C).name());
    return *static_cast<const C*>(value_.get());
  }
  bool empty() const { return !value_; }
  const YAML::Node& resolved() const { return resolved_; }

 private:
  std::shared_ptr<const void> value_;
  const std::type_info* type_ = nullptr;
  YAML::Node resolved_;
};

}  // namespace rlrun
