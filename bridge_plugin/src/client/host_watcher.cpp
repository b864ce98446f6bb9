#include "nav2_pyif_bridge/client/host_watcher.hpp"

#include <utility>

namespace nav2_pyif_bridge::client
{

HostWatcher::HostWatcher(Clock & clock, OnChange on_change)
: clock_(clock), on_change_(std::move(on_change))
{
}

void HostWatcher::on_token(std::string_view host_id, bool alive)
{
  bool changed = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (alive) {
      changed = alive_.emplace(host_id).second;
    } else {
      const auto it = alive_.find(host_id);
      if (it != alive_.end()) {
        alive_.erase(it);
        changed = true;
      }
    }
    if (changed) {
      ++changes_;
    }
  }
  if (changed) {
    changed_.notify_all();
    if (on_change_) {
      on_change_(std::string(host_id), alive);
    }
  }
}

bool HostWatcher::any_alive() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return !alive_.empty();
}

HostWatcher::Hosts HostWatcher::alive() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return alive_;
}

std::size_t HostWatcher::changes() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return changes_;
}

bool HostWatcher::wait_for_any(Duration timeout)
{
  return wait_until([](const Hosts & hosts) {return !hosts.empty();}, timeout);
}

bool HostWatcher::wait_until(
  const std::function<bool(const Hosts &)> & predicate, Duration timeout)
{
  const TimePoint deadline = clock_.now() + timeout;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!predicate(alive_)) {
    const TimePoint now = clock_.now();
    if (now >= deadline) {
      return false;
    }
    clock_.wait_for(changed_, lock, deadline - now);
  }
  return true;
}

}  // namespace nav2_pyif_bridge::client
