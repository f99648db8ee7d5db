// The summary line a training session ends with (runtime/io/session_summary.hpp): this session's
// steps and rate, the run's count before and after for a resumed run, read back by `report`.
#include <catch2/catch.hpp>

#include "rlrun/runtime/io/session_summary.hpp"

using namespace rlrun;

TEST_CASE("session summary: a resumed session says its own steps and rate", "[session_summary]") {
  SessionSummary fresh{false, 0, 5000, 8.35};
  CHECK(format_session_summary(fresh) == "trained 5000 steps in 8.35 s (599 steps/s)");
  SessionSummary resumed{false, 4000, 4500, 0.93};
  CHECK(format_session_summary(resumed) ==
        "trained 500 steps (4000 -> 4500) in 0.93 s (538 steps/s)");
  SessionSummary stopped{true, 0, 1, 0.5};
  CHECK(format_session_summary(stopped) == "interrupted after 1 step in 0.50 s (2 steps/s)");

  for (const SessionSummary& s : {fresh, resumed, stopped}) {
    const auto back = parse_session_summary(format_session_summary(s) + "; model saved to x.zip");
    REQUIRE(back);
    CHECK(back->interrupted == s.interrupted);
    CHECK(back->start_timesteps == s.start_timesteps);
    CHECK(back->end_timesteps == s.end_timesteps);
    CHECK(back->wall_seconds == Approx(s.wall_seconds));
  }
  // The form log.txt files of earlier versions hold.
  const auto old =
      parse_session_summary("trained 4500 steps in 8.35 s (539 steps/s); model saved to m");
  REQUIRE(old);
  CHECK(old->steps() == 4500);
  CHECK(old->wall_seconds == Approx(8.35));
  for (const char* other : {"rlrun 0.1: training PPO on CartPole-v1 for 5000 steps", "trained",
                            "trained x steps in 1 s", "eval at 2000 steps: return 1",
                            "sweep: run 0 (a/seed1) trained 10 steps in 1.0 s"})
    CHECK_FALSE(parse_session_summary(other));
}
