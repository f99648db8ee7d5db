#pragma once
// The line a training session ends with, in the console and log.txt:
//
//   trained 5000 steps in 8.35 s (599 steps/s); model saved to runs/x/seed1/model.zip
//   trained 500 steps (4000 -> 4500) in 0.93 s (538 steps/s); model saved to ...   (resumed)
//   interrupted after 1200 steps in 2.10 s (571 steps/s); model saved to ...
//
// The steps and the rate are this session's: a resumed run that trains 500 more steps says
// 500, not the run's total (which the arrow shows). `rlrun report` adds up these lines of
// log.txt for a run's training time, so the writer and the reader live here together.
#include <cstdint>
#include <optional>
#include <string>

namespace rlrun {

struct SessionSummary {
  bool interrupted = false;
  int64_t start_timesteps = 0;  // the run's step count when the session began (0: a new run)
  int64_t end_timesteps = 0;    // ... and when it ended
  double wall_seconds = 0;
  int64_t steps() const { return end_timesteps - start_timesteps; }
};

// The line without its "; model saved to ..." tail.
std::string format_session_summary(const SessionSummary& s);

// A line written by format_session_summary (also the form before resumed sessions showed the
// arrow, "trained N steps in S s", where N was the run's total); nullopt for any other line.
// Only `steps()` and `wall_seconds` are meaningful for the old form.
std::optional<SessionSummary> parse_session_summary(const std::string& line);

}  // namespace rlrun
