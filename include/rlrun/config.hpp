#pragma once
// Parameters of plugin envs, written in YAML under `env.kwargs` and listed by `rlrun list ID`.
// An env with parameters declares a nested `Config` whose fields own their defaults and are
// listed once, with a one-line doc each, exactly like rlrun's built-in envs:
//
//   struct Config {
//     int grid_size = 10;
//     template <class V>
//     void visit(V& v) { v("grid_size", grid_size, "number of cells"); }
//   };
//   explicit GoLeft(const Config& config);
//
// rlrun calls visit() with a FieldVisitor that reads the YAML strictly (an unknown key or a
// wrong type is an error with file:line:column and a did-you-mean), writes the resolved
// config, or prints the documentation. Field types: bool, int, int64_t, float, double,
// std::string, std::vector<double>, std::vector<int64_t>.
#include <cstdint>
#include <string>
#include <vector>

namespace rlrun::api {

class FieldVisitor {
 public:
  template <class T>
  void operator()(const char* key, T& value, const char* doc) {
    field(key, value, doc);
  }

  virtual void field(const char* key, bool& value, const char* doc) = 0;
  virtual void field(const char* key, int& value, const char* doc) = 0;
  virtual void field(const char* key, int64_t& value, const char* doc) = 0;
  virtual void field(const char* key, float& value, const char* doc) = 0;
  virtual void field(const char* key, double& value, const char* doc) = 0;
  virtual void field(const char* key, std::string& value, const char* doc) = 0;
  virtual void field(const char* key, std::vector<double>& value, const char* doc) = 0;
  virtual void field(const char* key, std::vector<int64_t>& value, const char* doc) = 0;

 protected:
  ~FieldVisitor() = default;
};

}  // namespace rlrun::api
