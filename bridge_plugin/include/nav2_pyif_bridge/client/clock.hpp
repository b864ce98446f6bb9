// Time, behind an interface where a unit waits (for a host's liveliness token), so the tests
// can run those waits on a fake clock in no time.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace nav2_pyif_bridge::client
{

using Duration = std::chrono::nanoseconds;
using TimePoint = std::chrono::steady_clock::time_point;

class Clock
{
public:
  virtual ~Clock() = default;

  virtual TimePoint now() const = 0;

  // Wait on `cv`, `lock` held, until notified or `timeout` has passed. May return early
  // (spurious wake-ups, a fake clock): callers re-check their condition and the time.
  virtual void wait_for(
    std::condition_variable & cv, std::unique_lock<std::mutex> & lock, Duration timeout) = 0;
};

// std::chrono::steady_clock.
class SteadyClock final : public Clock
{
public:
  static SteadyClock & instance()
  {
    static SteadyClock clock;
    return clock;
  }

  TimePoint now() const override {return std::chrono::steady_clock::now();}
  void wait_for(
    std::condition_variable & cv, std::unique_lock<std::mutex> & lock,
    Duration timeout) override
  {
    cv.wait_for(lock, timeout);
  }
};

// Milliseconds as a double, for messages ("within 40 ms").
inline double to_ms(Duration d) {return std::chrono::duration<double, std::milli>(d).count();}

}  // namespace nav2_pyif_bridge::client
