// From an error reply (or a plugin-side failure) to the nav2_core exception the plugin throws
// (PROTOCOL.md section 7). The units throw CallError, which names the exception by ErrorKind;
// only the Nav2 plugin classes turn it into the nav2_core class (nav2_exceptions.hpp), so
// everything here builds and is tested without Nav2.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "nav2_pyif_bridge/protocol/nav2_errors.hpp"
#include "nav2_pyif_bridge/protocol/types.hpp"

namespace nav2_pyif_bridge::client
{

// The plugin types and the nav2_core exception classes (Jazzy / Kilted), whose names are also
// the wire's error.type values, and the lookups in their tables (plugin_type_name,
// error_kind_name, error_kind_from_name, plugin_kind_of, belongs_to, generic_error,
// host_failure_error, invalid_error): generated from constants.py (protocol/nav2_errors.hpp).
using protocol::ErrorKind;
using protocol::kErrorKindCount;
using protocol::PluginKind;
using protocol::belongs_to;
using protocol::error_kind_from_name;
using protocol::error_kind_name;
using protocol::generic_error;
using protocol::host_failure_error;
using protocol::invalid_error;
using protocol::plugin_kind_of;
using protocol::plugin_type_name;

// Which nav2_core exception classes exist: Humble has only PlannerException (its controllers
// and smoothers throw it too); Jazzy and Kilted have the controller, planner and smoother
// classes of ErrorKind.
enum class Nav2Api : std::uint8_t {Humble, Jazzy};

// The class actually thrown on `api`: `kind` itself on Jazzy, PlannerException on Humble.
constexpr ErrorKind for_api(ErrorKind kind, Nav2Api api) noexcept
{
  return api == Nav2Api::Humble ? ErrorKind::PlannerException : kind;
}

// Why a call failed. Remote errors come from the host; the others happen in the plugin.
enum class Cause : std::uint8_t
{
  Remote,         // an error reply
  NoHost,         // no host liveliness token under P: nothing was sent
  TimedOut,       // no reply within the op's timeout
  BadReply,       // a reply that does not decode, or answers another seq
  NotConfigured,  // a call before configure (or after cleanup)
  Transport,      // the transport failed (a Zenoh session that lost its connection)
  Local,          // the plugin refused (a non-finite command, a message it cannot encode, ...)
};

// What the units throw. what() is the message Nav2's action result and log show; log_text()
// adds the Python traceback for the log.
class CallError : public std::runtime_error
{
public:
  struct Remote
  {
    std::string type;         // error.type as received (may be a protocol error's name)
    std::string traceback;    // the Python traceback, empty when none
    std::string python_type;  // e.g. builtins.ZeroDivisionError
  };

  CallError(ErrorKind kind, Cause cause, const std::string & message, Remote remote = {});

  ErrorKind kind() const noexcept {return kind_;}
  Cause cause() const noexcept {return cause_;}
  const Remote & remote() const noexcept {return remote_;}
  // A failure of reaching a host (none alive, no reply in time, a broken transport) rather
  // than its answer.
  bool unreachable() const noexcept
  {
    return cause_ == Cause::NoHost || cause_ == Cause::TimedOut || cause_ == Cause::Transport;
  }
  // The host, not its planner, failed the call: unreachable, or it answered Unavailable (its
  // worker crashed, is restarting or overran its deadline).
  bool host_failed() const noexcept;
  // The message, then the Python exception's type and traceback when the host sent them.
  std::string log_text() const;

private:
  ErrorKind kind_;
  Cause cause_;
  Remote remote_;
};

// The exception for an error reply: the named class when it belongs to `kind`'s plugin type
// (message as sent); for Unavailable the host-failure class; otherwise the generic class,
// with "[<type>] " before the message (protocol errors, and the other plugin type's names).
// Same as the reference client's error_from_reply.
CallError error_from_reply(const protocol::Error & error, PluginKind kind);

}  // namespace nav2_pyif_bridge::client
