// Generated from protocol/nav2_pyif_protocol/schema.py by
// `python -m nav2_pyif_codegen.generate`: do not edit.
//
// The structures shared by several messages (PROTOCOL.md section 13, "Structures"). Plain data: the
// codec checks them when encoding. Units are SI; stamps are integer nanoseconds.

#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace nav2_pyif_bridge::protocol
{

// Values per row of the packed float64 arrays (PROTOCOL.md section 2).
inline constexpr std::size_t kPoseRowSize = 7;  // x, y, z, qx, qy, qz, qw
inline constexpr std::size_t kFootprintRowSize = 2;  // x, y

// A stamped pose, in the costmap's global frame.
struct PoseStamped
{
  // frame of the pose
  std::string frame_id;
  // header stamp, ns since the epoch of the ROS clock
  std::int64_t stamp_ns{0};
  // x, y, z [m], qx, qy, qz, qw
  std::array<double, 7> pose{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
};

// A stamped velocity, in the robot base frame.
struct TwistStamped
{
  // frame of the twist (the robot base frame)
  std::string frame_id;
  // header stamp [ns]
  std::int64_t stamp_ns{0};
  // vx, vy, vz [m/s], wx, wy, wz [rad/s]
  std::array<double, 6> twist{};
};

// A plan: poses packed as float64 rows (one 56-byte row per pose, not 7 floats).
struct Path
{
  // frame of every pose
  std::string frame_id;
  // header stamp [ns]
  std::int64_t stamp_ns{0};
  // N x 7 float64 little-endian, row-major: x, y, z, qx, qy, qz, qw
  std::vector<double> poses;

  // Rows of poses (kPoseRowSize values each).
  std::size_t pose_count() const noexcept {return poses.size() / kPoseRowSize;}
};

// Nav2's Costmap2D: metadata, the raw cost bytes and the footprint.
struct Costmap
{
  // client's counter; changes whenever data or metadata change
  std::uint64_t version{0};
  // the costmap's global frame
  std::string frame_id;
  // cells along x (width)
  std::uint32_t size_x{0};
  // cells along y (height)
  std::uint32_t size_y{0};
  // m per cell
  double resolution{0.0};
  // world x of cell (0, 0)'s outer corner [m]
  double origin_x{0.0};
  // world y of cell (0, 0)'s outer corner [m]
  double origin_y{0.0};
  // size_x * size_y uint8 costs, index = my * size_x + mx
  std::vector<std::uint8_t> data;
  // K x 2 float64 little-endian x, y [m] in the robot frame; K may be 0
  std::vector<double> footprint;
  // [m]; used when the footprint is empty
  double robot_radius{0.0};

  // Rows of footprint (kFootprintRowSize values each).
  std::size_t footprint_count() const noexcept {return footprint.size() / kFootprintRowSize;}
};

// The goal checker's tolerances.
struct GoalChecker
{
  // [m]
  double xy_goal_tolerance{0.0};
  // [rad]
  double yaw_goal_tolerance{0.0};
  // [m/s]
  double trans_stopped_velocity{0.0};
  // [rad/s]
  double rot_stopped_velocity{0.0};
  // optional: [m] the remaining plan length within which the goal may count as reached (Lyrical's
  // getTolerances); absent when the checker has none, or before Lyrical
  std::optional<double> path_length_tolerance;
};

// The error of a failed reply (PROTOCOL.md section 7).
struct Error
{
  // nav2_core exception name or protocol error name
  std::string type;
  // human-readable, names the cause
  std::string message;
  // Python traceback, empty when none
  std::string traceback;
  // qualified name of the Python exception, empty when none
  std::string python_type;
};

// The latest message of one of the plugin's input topics, ROS-serialized (CDR).
struct Input
{
  // the input's name in the plugin's `inputs` parameter (e.g. scan)
  std::string name;
  // ROS message type, e.g. sensor_msgs/msg/LaserScan
  std::string type;
  // when the plugin received it, ns on the server's clock
  std::int64_t stamp_ns{0};
  // the message as ROS serializes it (CDR with its 4-byte header)
  std::vector<std::uint8_t> cdr;
};

// A message the planner publishes for debugging, ROS-serialized (CDR).
struct DebugOutput
{
  // the output's name: published on <plugin name>/<name>
  std::string name;
  // ROS message type, one the configure reply listed for this name
  std::string type;
  // the message as ROS serializes it (CDR with its 4-byte header)
  std::vector<std::uint8_t> cdr;
};

// One call carried in another plugin's query (PROTOCOL.md section 15).
struct CarriedCall
{
  // key prefix of the plugin it is for
  std::string key;
  // its encoded request (in a request) or reply (in a reply)
  std::vector<std::uint8_t> payload;
};

}  // namespace nav2_pyif_bridge::protocol
