#pragma once
// SUMO's tripinfo output (--tripinfo-output FILE): one <tripinfo .../> element per vehicle that
// arrived, written by SUMO's tripinfo device (sumo.dlr.de/docs/Simulation/Output/TripInfo.html).
// The traffic envs take their episode metrics from it, so they are SUMO's own numbers:
//   duration     seconds from departure to arrival (avg_travel_time)
//   waitingTime  seconds spent below 0.1 m/s (avg_waiting_time)
//   timeLoss     seconds lost against driving at the allowed speed (mean_delay, RESCO's delay)
#include <string>

namespace rlrun {

struct TripinfoSummary {
  int trips = 0;
  double mean_duration = 0;   // s
  double mean_waiting = 0;    // s
  double mean_time_loss = 0;  // s
};

// Reads a complete tripinfo file (SUMO writes it fully when the simulation closes). Throws
// RuntimeFailure when the file is missing or an element lacks one of the three attributes.
TripinfoSummary read_tripinfo(const std::string& path);

}  // namespace rlrun
