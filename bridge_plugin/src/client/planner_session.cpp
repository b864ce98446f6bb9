#include "nav2_pyif_bridge/client/planner_session.hpp"

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

proto::Path PlannerSession::create_plan(
  const proto::CreatePlanRequest & request, const std::function<bool()> & cancel_checker)
{
  CallOptions options;
  if (cancel_checker) {
    // One cancel_plan per create_plan request (a retry after SessionUnknown is a new one).
    std::uint64_t cancelled_seq = 0;
    options.while_waiting = [this, &cancel_checker, cancelled_seq](std::uint64_t seq) mutable {
        if (cancelled_seq != seq && cancel_checker()) {
          cancelled_seq = seq;
          send_cancel(seq);
        }
      };
  }
  return call(request, options).path;
}

void PlannerSession::send_cancel(std::uint64_t target_seq)
{
  proto::Request request;
  request.sid = sid();
  request.epoch = current().epoch;
  request.seq = next_seq();
  request.body = proto::CancelPlanRequest{target_seq};
  // Fire and forget: the planner's own answer to create_plan (PlannerCancelled) is what counts.
  try {
    transport().send(target(keys().cancel()), proto::encode_request(request), timeouts().lifecycle);
  } catch (const std::exception & error) {
    log(logger(), LogLevel::Warn, keys().prefix() + ": cancel_plan not sent: " + error.what());
    return;
  }
  ++cancels_sent_;
  log(
    logger(), LogLevel::Info,
    keys().prefix() + ": create_plan (seq " + std::to_string(target_seq) +
    ") cancelled by Nav2; cancel_plan sent");
}

std::uint64_t PlannerSession::cancels_sent() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return cancels_sent_;
}

}  // namespace nav2_pyif_bridge::client
