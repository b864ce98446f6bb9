// The structures shared by several messages (PROTOCOL.md section 13, "Structures").
// Plain data: the codec checks them when encoding, so they carry no invariants of their own.
// Units are SI; stamps are integer nanoseconds; poses and plans are in the costmap's global
// frame, velocities in the robot base frame (PROTOCOL.md section 6).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace nav2_pyif_bridge::protocol
{

// Values per row of the packed float64 arrays (PROTOCOL.md section 2).
inline constexpr std::size_t kPoseRowSize = 7;       // x, y, z, qx, qy, qz, qw
inline constexpr std::size_t kFootprintRowSize = 2;  // x, y

struct PoseStamped
{
  std::string frame_id;
  std::int64_t stamp_ns{0};
  // x, y, z [m], qx, qy, qz, qw; the identity rotation by default, not an invalid all-zero one.
  std::array<double, 7> pose{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
};

struct TwistStamped
{
  std::string frame_id;
  std::int64_t stamp_ns{0};
  std::array<double, 6> twist{};  // vx, vy, vz [m/s], wx, wy, wz [rad/s]
};

struct Path
{
  std::string frame_id;
  std::int64_t stamp_ns{0};
  // N x 7 row-major (kPoseRowSize per pose). On the wire a packed little-endian `bin`, so a
  // 1000-pose plan is one 56 kB copy instead of 7000 msgpack floats.
  std::vector<double> poses;

  std::size_t size() const noexcept {return poses.size() / kPoseRowSize;}
};

struct Costmap
{
  // The client's counter: bumped whenever anything below changes, so the costmap is sent only
  // when the host has not seen this version yet (PROTOCOL.md section 5).
  std::uint64_t version{0};
  std::string frame_id;
  std::uint32_t size_x{0};  // unsigned int in Nav2's Costmap2D
  std::uint32_t size_y{0};
  double resolution{0.0};  // m per cell
  double origin_x{0.0};    // world coordinates of cell (0, 0)'s outer corner [m]
  double origin_y{0.0};
  // size_x * size_y costs, Costmap2D::getCharMap() layout: index = my * size_x + mx.
  std::vector<std::uint8_t> data;
  // K x 2 row-major (kFootprintRowSize per point) in the robot frame [m]; K may be 0.
  std::vector<double> footprint;
  double robot_radius{0.0};  // [m]; used when the footprint is empty
};

struct GoalChecker
{
  double xy_goal_tolerance{0.0};       // [m]
  double yaw_goal_tolerance{0.0};      // [rad]
  double trans_stopped_velocity{0.0};  // [m/s]
  double rot_stopped_velocity{0.0};    // [rad/s]
};

// The error of a failed reply (PROTOCOL.md section 7).
struct Error
{
  std::string type;         // nav2_core exception name or protocol error name
  std::string message;      // human-readable, names the cause
  std::string traceback;    // Python traceback, empty when none
  std::string python_type;  // qualified name of the Python exception, empty when none
};

}  // namespace nav2_pyif_bridge::protocol
