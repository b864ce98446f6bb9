#include "fakes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <variant>

namespace nav2_pyif_bridge::client::test
{
namespace proto = protocol;

// --- FakeClock ------------------------------------------------------------------------------

TimePoint FakeClock::now() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return TimePoint{} + std::chrono::duration_cast<TimePoint::duration>(now_);
}

Duration FakeClock::elapsed() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return now_;
}

std::optional<Duration> FakeClock::next_event() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (events_.empty()) {
    return std::nullopt;
  }
  return events_.begin()->first;
}

void FakeClock::at(Duration at, std::function<void()> event)
{
  std::lock_guard<std::mutex> lock(mutex_);
  events_.emplace(at, std::move(event));
}

void FakeClock::advance(Duration duration)
{
  Duration target;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    target = now_ + duration;
  }
  for (;;) {
    std::function<void()> event;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (events_.empty() || events_.begin()->first > target) {
        now_ = target;
        return;
      }
      auto it = events_.begin();
      now_ = std::max(now_, it->first);
      event = std::move(it->second);
      events_.erase(it);
    }
    event();  // without the clock's lock: events may use the clock
  }
}

void FakeClock::wait_for(
  std::condition_variable &, std::unique_lock<std::mutex> & lock, Duration timeout)
{
  Duration step = timeout;
  if (const auto next = next_event()) {
    step = std::min(step, std::max(Duration{0}, *next - elapsed()));
  }
  lock.unlock();
  advance(step);
  lock.lock();
}

// --- GridCostmap ----------------------------------------------------------------------------

GridCostmap::GridCostmap(std::uint32_t sx, std::uint32_t sy, double res)
: size_x(sx), size_y(sy), resolution(res), data(std::size_t{sx} * sy, 0)
{
  // A lethal quadrant, as tests/conftest.py's make_costmap has.
  for (std::uint32_t my = sy / 2; my < sy; ++my) {
    for (std::uint32_t mx = sx / 2; mx < sx; ++mx) {
      data[std::size_t{my} * sx + mx] = 254;
    }
  }
}

CostmapRead GridCostmap::read(std::optional<std::uint64_t> known)
{
  ++reads;
  CostmapView view;
  view.frame_id = frame_id;
  view.size_x = size_x;
  view.size_y = size_y;
  view.resolution = resolution;
  view.origin_x = origin_x;
  view.origin_y = origin_y;
  view.data = data.data();
  view.footprint = footprint;
  view.robot_radius = robot_radius;
  return read_costmap(view, version_, known);
}

// --- FakeHost -------------------------------------------------------------------------------

FakeHost::FakeHost(FakeClock & clock, bool alive)
: clock_(clock), watcher_(clock)
{
  if (alive) {
    start();
  }
}

void FakeHost::kill()
{
  if (!primary_.empty()) {
    kill_replica(primary_);
  }
}

void FakeHost::start()
{
  primary_ = "fake-host-" + std::to_string(++generation_);
  add_replica(primary_);
}

void FakeHost::add_replica(const std::string & id)
{
  replicas_[id] = Replica{};
  watcher_.on_token(id, true);
}

void FakeHost::kill_replica(const std::string & id)
{
  auto it = replicas_.find(id);
  if (it != replicas_.end()) {
    it->second.alive = false;
    it->second.sessions.clear();
  }
  watcher_.on_token(id, false);
}

void FakeHost::freeze_replica(const std::string & id, bool frozen)
{
  replicas_.at(id).frozen = frozen;
}

bool FakeHost::has_session(const std::string & host, const std::string & sid) const
{
  const auto it = replicas_.find(host);
  return it != replicas_.end() && it->second.sessions.count(sid) != 0;
}

FakeHost::Replica * FakeHost::answering(const std::string & host, std::string * id)
{
  for (auto & [name, replica] : replicas_) {
    if (replica.alive && !replica.frozen && (host.empty() || host == name)) {
      *id = name;
      return &replica;
    }
  }
  return nullptr;
}

std::vector<std::string> FakeHost::ops() const {return ops_since(0);}

std::vector<std::string> FakeHost::ops_since(std::size_t index) const
{
  std::vector<std::string> out;
  for (std::size_t i = index; i < received.size(); ++i) {
    out.emplace_back(proto::op_name(received[i].request.op()));
  }
  return out;
}

bool FakeHost::last_had_costmap() const
{
  const auto & body = last().body;
  if (const auto * c = std::get_if<proto::ComputeVelocityCommandsRequest>(&body)) {
    return c->costmap.has_value();
  }
  if (const auto * p = std::get_if<proto::CreatePlanRequest>(&body)) {
    return p->costmap.has_value();
  }
  if (const auto * r = std::get_if<proto::OnRunRequest>(&body)) {
    return r->costmap.has_value();
  }
  if (const auto * u = std::get_if<proto::OnCycleUpdateRequest>(&body)) {
    return u->costmap.has_value();
  }
  return std::holds_alternative<proto::ConfigureRequest>(body);
}

std::optional<proto::Bytes> FakeHost::query(
  const Target & target, const proto::Bytes & payload, Duration timeout, const WaitHook * hook)
{
  if (transport_error_once) {
    transport_error_once = false;
    throw std::runtime_error("Failed to perform get operation(Error code: -100 )");
  }
  received.push_back({target.key, target.host, proto::decode_request(payload), payload.size(),
      false, "", timeout});
  const proto::Request request = received.back().request;
  EXPECT_EQ(target.key.substr(target.key.rfind('/') + 1), proto::op_name(request.op()));
  std::string id;
  Replica * replica = answering(target.host, &id);
  if (replica == nullptr) {
    clock_.advance(timeout);  // nobody answers
    return std::nullopt;
  }

  if (dies_during_next_call) {
    clock_.advance(std::min(*dies_during_next_call, timeout));
    dies_during_next_call.reset();
    kill_replica(id);
    return std::nullopt;
  }
  Duration work = next_call_time.value_or(call_time);
  next_call_time.reset();
  if (request.op() == proto::Op::CreatePlan && replica->sessions.count(request.sid)) {
    const auto * mode = replica->sessions[request.sid].params.find("mode");
    if (mode && std::get<std::string>(*mode) == "slow") {
      work = std::max(work, Duration{10s});
    }
  }
  running_seq_ = request.seq;
  cancel_requested_ = false;
  Duration elapsed{0};
  while (elapsed < work && !cancel_requested_) {
    if (elapsed >= timeout) {
      running_seq_ = 0;
      return std::nullopt;  // the plugin stopped waiting; the host still works on
    }
    Duration step = std::min(work, timeout) - elapsed;
    if (hook) {
      step = std::min(step, hook->period);
    }
    clock_.advance(step);
    elapsed += step;
    if (hook && hook->poll) {
      hook->poll();
    }
  }
  running_seq_ = 0;
  if (elapsed >= timeout && !cancel_requested_) {
    return std::nullopt;
  }
  received.back().answered = true;
  received.back().answered_by = id;
  if (raw_reply_once) {
    auto raw = std::move(*raw_reply_once);
    raw_reply_once.reset();
    return raw;
  }
  proto::Reply reply = handle(*replica, id, request, elapsed);
  reply.seq = request.seq + static_cast<std::uint64_t>(seq_offset_once);
  seq_offset_once = 0;
  return proto::encode_reply(reply);
}

void FakeHost::send(const Target & target, const proto::Bytes & payload, Duration timeout)
{
  received.push_back({target.key, target.host, proto::decode_request(payload), payload.size(),
      true, "", timeout});
  const auto & request = received.back().request;
  EXPECT_EQ(target.key.substr(target.key.rfind('/') + 1), "cancel");
  std::string id;
  if (answering(target.host, &id) == nullptr) {
    return;
  }
  if (const auto * cancel = std::get_if<proto::CancelPlanRequest>(&request.body)) {
    if (cancel->target_seq == running_seq_) {
      cancel_requested_ = true;
    }
  }
}

proto::Reply FakeHost::error(
  const std::string & id, const proto::Request & request, std::string type, std::string message)
{
  proto::Reply reply;
  reply.seq = request.seq;
  reply.host = id;
  reply.outcome = proto::Error{std::move(type), std::move(message),
    "Traceback (most recent call last):\n  File \"echo_planners.py\", line 1\n", ""};
  return reply;
}

std::optional<std::vector<proto::CarriedCall>> FakeHost::carried(
  Replica & replica, const std::string & id,
  const std::optional<std::vector<proto::CarriedCall>> & carry)
{
  if (!carry) {
    return std::nullopt;
  }
  std::vector<proto::CarriedCall> replies;
  for (const proto::CarriedCall & call : *carry) {
    const proto::Request request = proto::decode_request(call.payload);
    carried_ops.emplace_back(proto::op_name(request.op()));
    const proto::Reply reply = handle(replica, id, request, Duration{0});
    replies.push_back({call.key, proto::encode_reply(reply)});
    const auto * body = std::get_if<proto::ReplyBody>(&reply.outcome);
    const auto * goal = body ? std::get_if<proto::IsGoalReachedReply>(body) : nullptr;
    const auto * check = body ? std::get_if<proto::CheckReply>(body) : nullptr;
    if (!body || (goal && goal->reached) || (check && !check->making_progress)) {
      break;  // Nav2 stops here
    }
  }
  return replies;
}

proto::Reply FakeHost::handle(
  Replica & replica, const std::string & id, const proto::Request & request, Duration elapsed)
{
  const proto::Op op = request.op();
  proto::Reply reply;
  reply.seq = request.seq;
  reply.host = id;
  reply.compute_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count();
  if (error_once) {
    proto::Error e = std::move(*error_once);
    error_once.reset();
    reply.outcome = std::move(e);
    return reply;
  }
  auto & sessions = replica.sessions;
  if (op == proto::Op::Configure) {
    const auto & body = std::get<proto::ConfigureRequest>(request.body);
    Session session;
    session.epoch = request.epoch;
    session.params = body.params;
    session.costmap_version = body.costmap.version;
    proto::Params declared;
    const auto * gain = body.params.find("gain");
    double g = 1.5;
    if (gain) {
      g = std::holds_alternative<double>(*gain) ? std::get<double>(*gain) :
        static_cast<double>(std::get<std::int64_t>(*gain));
    }
    session.params.set("gain", g);
    declared.set("gain", g);
    declared.set("label", std::string("echo"));
    sessions[request.sid] = session;
    proto::ConfigureReply configured;
    configured.declared = declared;
    configured.planner = "fakes:Echo";
    for (const auto & entry : body.params) {
      const std::string & name = entry.first;
      if (name != "gain" && name != "mode" && name != "points") {
        if (!configured.undeclared) {
          configured.undeclared.emplace();
        }
        // as the host: the reason leaves out what is declared (the warning gives it once)
        configured.undeclared->set(name, name + " is not a parameter of this planner");
      }
    }
    reply.outcome = proto::ReplyBody{configured};
    return reply;
  }
  auto it = sessions.find(request.sid);
  if (always_session_unknown || it == sessions.end() || it->second.epoch != request.epoch) {
    return error(
      id, request, "SessionUnknown", "session " + request.sid.substr(0, 8) + " epoch " +
      std::to_string(request.epoch) + " is unknown to this host");
  }
  Session & s = it->second;
  switch (op) {
    case proto::Op::Activate:
      s.active = true;
      reply.outcome = proto::ReplyBody{proto::ActivateReply{}};
      break;
    case proto::Op::Deactivate:
      s.active = false;
      reply.outcome = proto::ReplyBody{proto::DeactivateReply{}};
      break;
    case proto::Op::Cleanup:
      sessions.erase(it);
      reply.outcome = proto::ReplyBody{proto::CleanupReply{}};
      break;
    case proto::Op::SetParameters: {
        proto::SetParametersReply out;
        for (const auto & [name, value] : std::get<proto::SetParametersRequest>(request.body).params) {
          if (name == "label" && !std::holds_alternative<std::string>(value)) {
            out.rejected.set(name, "label: expected str, got int");
          } else {
            s.params.set(name, value);
          }
        }
        reply.outcome = proto::ReplyBody{out};
        break;
      }
    case proto::Op::SetPlan:
      s.plan_size = static_cast<double>(std::get<proto::SetPlanRequest>(request.body).path.pose_count());
      reply.outcome = proto::ReplyBody{proto::SetPlanReply{}};
      break;
    case proto::Op::SetSpeedLimit:
      s.speed_limit = std::get<proto::SetSpeedLimitRequest>(request.body).speed_limit;
      reply.outcome = proto::ReplyBody{proto::SetSpeedLimitReply{}};
      break;
    case proto::Op::ComputeVelocityCommands: {
        const auto & body = std::get<proto::ComputeVelocityCommandsRequest>(request.body);
        if (body.costmap) {
          s.costmap_version = body.costmap->version;
        }
        if (body.plan) {  // Lyrical's transformed plan: the host's set_plan, first
          s.plan_size = static_cast<double>(body.plan->pose_count());
        }
        const auto * gain = s.params.find("gain");
        proto::TwistStamped cmd;
        cmd.frame_id = "base_link";
        cmd.stamp_ns = body.pose.stamp_ns;
        cmd.twist = {s.plan_size, gain ? std::get<double>(*gain) : 1.5, s.speed_limit,
          static_cast<double>(s.costmap_version), body.goal_checker ? 1.0 : 0.0, ++s.calls};
        if (nan_once) {
          cmd.twist[0] = std::numeric_limits<double>::quiet_NaN();
          nan_once = false;
        }
        reply.outcome = proto::ReplyBody{
          proto::ComputeVelocityCommandsReply{cmd, std::nullopt, carried(replica, id, body.carry)}};
        break;
      }
    case proto::Op::IsGoalReached: {
        const auto & body = std::get<proto::IsGoalReachedRequest>(request.body);
        proto::IsGoalReachedReply out;
        out.reached = body.pose[0] >= reached_x;
        if (!out.reached) {
          out.carried = carried(replica, id, body.carry);
        }
        reply.outcome = proto::ReplyBody{out};
        break;
      }
    case proto::Op::Check: {
        const auto & body = std::get<proto::CheckRequest>(request.body);
        proto::CheckReply out;
        out.making_progress = making_progress;
        if (making_progress) {
          out.carried = carried(replica, id, body.carry);
        }
        reply.outcome = proto::ReplyBody{out};
        break;
      }
    case proto::Op::Cancel:
      reply.outcome = proto::ReplyBody{proto::CancelReply{true}};
      break;
    case proto::Op::Reset:
      reply.outcome = proto::ReplyBody{proto::ResetReply{}};
      break;
    case proto::Op::CreatePlan: {
        if (cancel_requested_) {
          return error(id, request, "PlannerCancelled", "create_plan cancelled");
        }
        const auto & body = std::get<proto::CreatePlanRequest>(request.body);
        if (body.costmap) {
          s.costmap_version = body.costmap->version;
        }
        const auto * mode = s.params.find("mode");
        if (mode && std::get<std::string>(*mode) == "occupied") {
          return error(id, request, "GoalOccupied", "goal is in a wall");
        }
        std::int64_t points = 25;
        if (const auto * p = s.params.find("points")) {
          points = std::get<std::int64_t>(*p);
        }
        proto::Path path = straight_path(
          static_cast<std::size_t>(points), body.goal.pose[0], body.goal.pose[1]);
        if (mode && std::get<std::string>(*mode) == "nan") {
          path.poses[3] = std::numeric_limits<double>::infinity();
        }
        reply.outcome = proto::ReplyBody{proto::CreatePlanReply{path}};
        break;
      }
    case proto::Op::OnRun: {
        // A backup: SUCCEEDED unless the speed is 0 (INVALID_INPUT).
        const auto & body = std::get<proto::OnRunRequest>(request.body);
        if (body.costmap) {
          s.costmap_version = body.costmap->version;
        }
        const auto * speed = body.command.find("speed");
        const auto * target = body.command.find("target_x");
        const bool valid = speed && target && std::get<double>(*speed) != 0.0;
        if (valid) {
          ++s.runs;
          s.start_x = body.pose.pose[0];
          s.distance = std::abs(std::get<double>(*target));
        }
        reply.outcome = proto::ReplyBody{
          proto::OnRunReply{valid ? "succeeded" : "failed", valid ? "" : "invalid_input"}};
        break;
      }
    case proto::Op::OnCycleUpdate: {
        // Backs up at 0.1 m/s until |x - start_x| reaches the distance.
        const auto & body = std::get<proto::OnCycleUpdateRequest>(request.body);
        if (body.costmap) {
          s.costmap_version = body.costmap->version;
        }
        proto::OnCycleUpdateReply out;
        const double travelled = std::abs(body.pose.pose[0] - s.start_x);
        out.feedback.emplace();
        out.feedback->set("distance_traveled", travelled);
        out.feedback->set("runs", s.runs);
        if (travelled >= s.distance) {
          out.status = "succeeded";
        } else {
          out.status = "running";
          proto::TwistStamped cmd;
          cmd.frame_id = "base_link";
          cmd.stamp_ns = body.pose.stamp_ns;
          cmd.twist = {-0.1, 0.0, 0.0, 0.0, 0.0, 0.0};
          if (nan_once) {
            cmd.twist[0] = std::numeric_limits<double>::quiet_NaN();
            nan_once = false;
          }
          out.cmd_vel = cmd;
        }
        reply.outcome = proto::ReplyBody{out};
        break;
      }
    case proto::Op::OnActionCompletion:
      reply.outcome = proto::ReplyBody{proto::OnActionCompletionReply{}};
      break;
    case proto::Op::FindPlanSegment: {
        // the poses from the robot's x on (one per 0.1 m), five of them, within the plan
        const auto & body = std::get<proto::FindPlanSegmentRequest>(request.body);
        const auto size = static_cast<std::uint64_t>(std::max(0.0, s.plan_size));
        proto::FindPlanSegmentReply out;
        out.start = std::min(static_cast<std::uint64_t>(std::max(0.0, body.pose.pose[0] * 10.0)),
            size > 0 ? size - 1 : 0);
        out.end = std::min(out.start + 5, size);
        reply.outcome = proto::ReplyBody{out};
        break;
      }
    default:
      return error(id, request, "BadRequest", "unexpected op");
  }
  return reply;
}


// --- helpers --------------------------------------------------------------------------------

bool LogSink::contains(const std::string & text) const
{
  for (const auto & line : lines) {
    if (line.second.find(text) != std::string::npos) {
      return true;
    }
  }
  return false;
}

proto::Path straight_path(std::size_t n, double x, double y)
{
  proto::Path path;
  path.frame_id = "odom";
  for (std::size_t i = 0; i < n; ++i) {
    const double t = n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 1.0;
    path.poses.insert(path.poses.end(), {t * x, t * y, 0.0, 0.0, 0.0, 0.0, 1.0});
  }
  return path;
}

proto::CreatePlanRequest plan_request(
  const proto::PoseStamped & start, const proto::PoseStamped & goal)
{
  proto::CreatePlanRequest request;
  request.start = start;
  request.goal = goal;
  return request;
}

proto::PoseStamped pose_at(double x, double y, const std::string & frame)
{
  return proto::PoseStamped{frame, 1700000000000000000, {x, y, 0.0, 0.0, 0.0, 0.0, 1.0}};
}

}  // namespace nav2_pyif_bridge::client::test
