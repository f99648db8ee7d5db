#pragma once
// Registration: how a plugin tells rlrun which envs it provides (Gymnasium's
// gymnasium.register). Inside RLRUN_PLUGIN (rlrun/plugin.hpp):
//
//   registrar.add_env<GoLeft>("GoLeft-v0", "walk left to the goal", /*max_episode_steps=*/100);
//
// max_episode_steps > 0 wraps the env in rlrun's TimeLimit, as gymnasium.make does (YAML
// `env.max_episode_steps` overrides it). An env class with a nested `Config`
// (rlrun/api/config.hpp) is constructed from it; one without is default-constructed.
#include <memory>
#include <span>
#include <string>
#include <type_traits>

#include "rlrun/config.hpp"
#include "rlrun/env.hpp"

namespace rlrun::api {

struct EnvSpec {
  std::string id;           // what YAML `env.id` names, e.g. "GoLeft-v0"
  std::string description;  // one line for `rlrun list`
  int max_episode_steps = 0;
};

// Builds envs of one registered type. Implemented for you by add_env<E>.
class EnvFactory {
 public:
  virtual ~EnvFactory() = default;
  // Makes a default Config, lets each visitor in turn read or write its fields, and returns
  // the env built from it, or nullptr when `construct` is false.
  virtual std::unique_ptr<rlrun::Env> make(std::span<FieldVisitor* const> visitors,
                                           bool construct) const = 0;
};

template <class E>
class EnvFactoryOf final : public EnvFactory {
 public:
  std::unique_ptr<rlrun::Env> make(std::span<FieldVisitor* const> visitors,
                                   bool construct) const override {
    if constexpr (requires { typename E::Config; }) {
      typename E::Config config{};
      for (FieldVisitor* v : visitors) config.visit(*v);
      if (!construct) return nullptr;
      return std::make_unique<E>(config);
    } else {
      if (!construct) return nullptr;
      return std::make_unique<E>();
    }
  }
};

// Implemented by rlrun; a plugin receives one in its RLRUN_PLUGIN function.
class Registrar {
 public:
  template <class E>
  void add_env(std::string id, std::string description, int max_episode_steps = 0) {
    static_assert(std::is_base_of_v<rlrun::Env, E>,
                  "add_env<E>: E must derive from rlrun::Env (rlrun/env.hpp)");
    add_env_factory(EnvSpec{std::move(id), std::move(description), max_episode_steps},
                    std::make_unique<EnvFactoryOf<E>>());
  }

  // Throws std::invalid_argument when the id is taken (by a built-in env or another plugin).
  virtual void add_env_factory(const EnvSpec& spec, std::unique_ptr<EnvFactory> factory) = 0;

 protected:
  ~Registrar() = default;
};

}  // namespace rlrun::api
