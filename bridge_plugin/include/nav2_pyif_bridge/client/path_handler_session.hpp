// A path handler's calls (the reference client's PathHandlerClient; PROTOCOL.md section 19):
// the plan once per new plan, then a segment of it every control cycle.
#pragma once

#include <functional>
#include <optional>
#include <utility>

#include "nav2_pyif_bridge/client/plugin_session.hpp"

namespace nav2_pyif_bridge::client
{

class PathHandlerSession : public KindSession<PluginKind::PathHandler>
{
public:
  using KindSession::KindSession;

  // The plan, in its own frame (Nav2's global plan frame). When the host failed the call (none alive, no
  // reply in time), the plan is kept as owed and that failure returned, not thrown: the next
  // segment sends it first, as does a re-established session (as ControllerSession::set_plan).
  std::optional<CallError> set_plan(const protocol::Path & path);
  // The poses [start, end) of that plan the controller follows this cycle, for the robot at
  // `pose` (the plan's frame), checked to be a segment of it (else InvalidPath). An owed plan
  // is sent first.
  std::pair<std::size_t, std::size_t> find_plan_segment(const protocol::PoseStamped & pose);
  // How the carried cycle's robot pose (the costmap's global frame) becomes the segment's (the
  // plan's frame); std::nullopt when it cannot be now. Unset: the pose as it is.
  using PoseInPlanFrame =
    std::function<std::optional<protocol::PoseStamped>(const protocol::PoseStamped &)>;
  void set_pose_in_plan_frame(PoseInPlanFrame convert);
  // The request for the goal check's (or the check's) query to carry, for the robot at
  // `robot` (the costmap's global frame); std::nullopt while the plan is owed (it would run on
  // the host's old plan) or the pose cannot be put in the plan's frame.
  std::optional<Carried> prepare_segment(const protocol::PoseStamped & robot);
  // The segment a carried request brought back, when Nav2's call (`pose`: the plan's frame)
  // is the prepared one.
  std::optional<std::pair<std::size_t, std::size_t>> take_segment(
    Carried prepared, const std::optional<protocol::Bytes> & reply,
    const protocol::PoseStamped & pose);
  // The plan's length (0 before the first).
  std::size_t plan_size() const;

protected:
  std::optional<protocol::RequestBody> restored(protocol::Op op) override;
  void forget_state() override;

private:
  std::pair<std::size_t, std::size_t> checked(const protocol::FindPlanSegmentReply & reply) const;

  PoseInPlanFrame pose_in_plan_frame_;
  std::optional<protocol::Path> plan_;
  std::size_t plan_size_{0};
  bool plan_owed_{false};
};

}  // namespace nav2_pyif_bridge::client
