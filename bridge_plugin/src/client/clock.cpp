#include "nav2_pyif_bridge/client/clock.hpp"

#include <thread>

namespace nav2_pyif_bridge::client
{

SteadyClock & SteadyClock::instance()
{
  static SteadyClock clock;
  return clock;
}

void SteadyClock::wait_for(
  std::condition_variable & cv, std::unique_lock<std::mutex> & lock, Duration timeout)
{
  cv.wait_for(lock, timeout);
}

void SteadyClock::sleep_for(Duration duration)
{
  std::this_thread::sleep_for(duration);
}

}  // namespace nav2_pyif_bridge::client
