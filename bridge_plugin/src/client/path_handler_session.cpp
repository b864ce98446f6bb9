#include "nav2_pyif_bridge/client/path_handler_session.hpp"

#include <string>

namespace nav2_pyif_bridge::client
{
namespace proto = protocol;

std::optional<CallError> PathHandlerSession::set_plan(const proto::Path & path)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  plan_ = path;
  plan_size_ = path.pose_count();
  plan_owed_ = true;
  try {
    call(proto::SetPlanRequest{*plan_, std::nullopt});
    plan_owed_ = false;
  } catch (const CallError & error) {
    if (!error.host_failed()) {
      plan_owed_ = false;
      throw;
    }
    return error;
  }
  return std::nullopt;
}

std::pair<std::size_t, std::size_t> PathHandlerSession::find_plan_segment(
  const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_ && plan_) {
    call(proto::SetPlanRequest{*plan_, std::nullopt});  // fails as the host does
    plan_owed_ = false;
  }
  return checked(call(proto::FindPlanSegmentRequest{pose}));
}

void PathHandlerSession::set_pose_in_plan_frame(PoseInPlanFrame convert)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  pose_in_plan_frame_ = std::move(convert);
}

std::optional<Carried> PathHandlerSession::prepare_segment(const proto::PoseStamped & robot)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_ || !plan_) {
    return std::nullopt;
  }
  std::optional<proto::PoseStamped> pose = robot;
  if (pose_in_plan_frame_) {
    pose = pose_in_plan_frame_(robot);
  }
  if (!pose) {
    return std::nullopt;
  }
  return prepare(proto::FindPlanSegmentRequest{*pose});
}

std::optional<std::pair<std::size_t, std::size_t>> PathHandlerSession::take_segment(
  Carried prepared, const std::optional<proto::Bytes> & reply, const proto::PoseStamped & pose)
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  if (plan_owed_) {
    return std::nullopt;
  }
  auto answer = take(std::move(prepared), reply, proto::FindPlanSegmentRequest{pose});
  if (!answer) {
    return std::nullopt;
  }
  return checked(*answer);
}

std::size_t PathHandlerSession::plan_size() const
{
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return plan_size_;
}

std::pair<std::size_t, std::size_t> PathHandlerSession::checked(
  const proto::FindPlanSegmentReply & reply) const
{
  // The host checks the same; a reply that breaks it must not become iterators past the plan.
  if (!(reply.start < reply.end && reply.end <= plan_size_)) {
    throw CallError(
            ErrorKind::InvalidPath, Cause::BadReply,
            "find_plan_segment reply (" + std::to_string(reply.start) + ", " +
            std::to_string(reply.end) + ") is not a segment of the plan's " +
            std::to_string(plan_size_) + " poses");
  }
  return {static_cast<std::size_t>(reply.start), static_cast<std::size_t>(reply.end)};
}

std::optional<proto::RequestBody> PathHandlerSession::restored(proto::Op op)
{
  if (op == proto::Op::SetPlan && plan_ && !plan_owed_) {  // an owed one: its call sends it
    return proto::SetPlanRequest{*plan_, std::nullopt};
  }
  return std::nullopt;
}

void PathHandlerSession::forget_state()
{
  plan_.reset();
  plan_size_ = 0;
  plan_owed_ = false;
}

}  // namespace nav2_pyif_bridge::client
