#include "rlrun/runtime/run/training_state_io.hpp"

#include <string>

namespace rlrun {

void write_callback_states(StateWriter out,
                           const std::vector<std::unique_ptr<Callback>>& callbacks) {
  out.put_int("count", static_cast<int64_t>(callbacks.size()));
  for (size_t i = 0; i < callbacks.size(); ++i) {
    StateWriter one = out.sub(std::to_string(i));
    callbacks[i]->write_state(one);
    callbacks[i]->flush();  // their files end where the checkpoint's state does
  }
}

void read_callback_states(const StateReader& in,
                          std::vector<std::unique_ptr<Callback>>& callbacks) {
  if (in.get_int("count") != static_cast<int64_t>(callbacks.size()))
    throw StateMismatch(
        "it was written with other callbacks (eval/checkpoint/obs_log/video sections) than the "
        "run's config.yaml turns on");
  for (size_t i = 0; i < callbacks.size(); ++i) callbacks[i]->read_state(in.sub(std::to_string(i)));
}

void write_pending_log(StateWriter out, const LogRow& row) {
  out.put_int("count", static_cast<int64_t>(row.size()));
  int i = 0;
  for (const auto& [key, value] : row) {
    StateWriter entry = out.sub(std::to_string(i++));
    entry.put_string("key", key);
    entry.put_double("value", value);
  }
}

LogRow read_pending_log(const StateReader& in) {
  LogRow row;
  // A logger holds a few dozen keys; the bound keeps a crafted count from looping for long.
  const int64_t count = in.get_int_in("count", 0, 10000);
  for (int64_t i = 0; i < count; ++i) {
    const StateReader entry = in.sub(std::to_string(i));
    row[entry.get_string("key")] = entry.get_double("value");
  }
  return row;
}

}  // namespace rlrun
