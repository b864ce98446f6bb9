// What the codec throws. Decoding failures name the protocol error a host answers with
// (BadRequest or VersionMismatch) and the field at fault.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace nav2_pyif_bridge::protocol
{

// Bytes that are not a valid message of this protocol version. what() reads
// "<field path>: <problem>", e.g.
// "compute_velocity_commands request body.pose.frame_id: expected str, got int".
class DecodeError : public std::runtime_error
{
public:
  DecodeError(
    std::string_view error_type, const std::string & field_path, const std::string & problem)
  : std::runtime_error(field_path + ": " + problem), error_type_(error_type),
    field_path_(field_path)
  {}

  // error_type::kBadRequest or error_type::kVersionMismatch (constants.hpp).
  const std::string & error_type() const noexcept {return error_type_;}
  // Where the problem is, e.g. "set_plan request body.path.poses".
  const std::string & field_path() const noexcept {return field_path_;}

private:
  std::string error_type_;
  std::string field_path_;
};

// A message that cannot be encoded canonically (a path whose size is not a multiple of 7, a
// costmap whose data does not match its size, a string that is not UTF-8, ...). Thrown before
// anything is sent, so a bug in the plugin never reaches the host as a malformed message.
class EncodeError : public std::invalid_argument
{
public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace nav2_pyif_bridge::protocol
