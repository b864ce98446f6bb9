// One timed call of a benchmark row, and the clock it is timed with.
#pragma once

#include <chrono>
#include <cstdint>

namespace nav2_pyif_bench
{

using BenchClock = std::chrono::steady_clock;

inline std::int64_t elapsed_ns(BenchClock::time_point start)
{
  return std::chrono::duration_cast<std::chrono::nanoseconds>(BenchClock::now() - start).count();
}

struct Sample
{
  std::int64_t total_ns{0};
  // Parts of total_ns, where the row can tell them (-1: not measured):
  std::int64_t query_ns{-1};    // the Zenoh get inside the call, reply received
  std::int64_t handler_ns{-1};  // the host's handler (decode -> planner -> encode), as it reports
};

}  // namespace nav2_pyif_bench
