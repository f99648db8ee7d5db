#include "rlrun/envs/sumo/tripinfo.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

// Reads `name="<number>"` within text[begin, end); false when absent.
bool attribute(const std::string& text, size_t begin, size_t end, const std::string& name,
               double& value) {
  const std::string key = " " + name + "=\"";
  const size_t at = text.find(key, begin);
  if (at == std::string::npos || at >= end) return false;
  value = std::strtod(text.c_str() + at + key.size(), nullptr);
  return true;
}

}  // namespace

TripinfoSummary read_tripinfo(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RuntimeFailure("SUMO's tripinfo output " + path + " is missing");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  TripinfoSummary summary;
  double duration_sum = 0, waiting_sum = 0, loss_sum = 0;
  for (size_t at = text.find("<tripinfo "); at != std::string::npos;
       at = text.find("<tripinfo ", at + 1)) {
    const size_t end = text.find('>', at);
    double duration = 0, waiting = 0, loss = 0;
    if (end == std::string::npos || !attribute(text, at, end, "duration", duration) ||
        !attribute(text, at, end, "waitingTime", waiting) ||
        !attribute(text, at, end, "timeLoss", loss))
      throw RuntimeFailure("SUMO's tripinfo output " + path +
                           " has a <tripinfo> element without duration, waitingTime and timeLoss");
    ++summary.trips;
    duration_sum += duration;
    waiting_sum += waiting;
    loss_sum += loss;
  }
  if (summary.trips > 0) {
    summary.mean_duration = duration_sum / summary.trips;
    summary.mean_waiting = waiting_sum / summary.trips;
    summary.mean_time_loss = loss_sum / summary.trips;
  }
  return summary;
}

}  // namespace rlrun
