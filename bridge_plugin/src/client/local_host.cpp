#include "nav2_pyif_bridge/client/local_host.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

extern char ** environ;  // NOLINT: POSIX

namespace nav2_pyif_bridge::client
{
namespace
{

std::string command_line(const std::vector<std::string> & argv)
{
  std::string out;
  for (const auto & arg : argv) {
    out += (out.empty() ? "" : " ") + arg;
  }
  return out;
}

std::vector<char *> pointers(std::vector<std::string> & strings)
{
  std::vector<char *> out;
  for (auto & text : strings) {
    out.push_back(text.data());
  }
  out.push_back(nullptr);
  return out;
}

}  // namespace

std::uint16_t pick_free_tcp_port()
{
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    throw std::system_error(errno, std::generic_category(), "socket");
  }
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  if (::bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof(address)) != 0 ||
    ::getsockname(fd, reinterpret_cast<sockaddr *>(&address), &length) != 0)
  {
    const int error = errno;
    ::close(fd);
    throw std::system_error(error, std::generic_category(), "bind 127.0.0.1:0");
  }
  ::close(fd);
  return ntohs(address.sin_port);
}

std::string local_host_key(std::string_view node, std::string_view plugin)
{
  auto chunk = [](std::string_view text) {
      std::string out;
      for (const char c : text) {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
          (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
        out += plain ? c : '_';
      }
      return out.empty() ? std::string("_") : out;
    };
  return "nav2_pyif/local/" + chunk(node) + "/" + chunk(plugin);
}

std::vector<std::string> local_host_arguments(
  const BridgeParameters & spec, const std::string & key, const std::string & listen_endpoint)
{
  // --respawn: planner-host restarts the host itself whenever it exits; --parent-pid: the
  // keeper gets SIGTERM when this process dies, and starts nothing if it is gone already
  // (PR_SET_PDEATHSIG), so a crashed Nav2 leaves no planner host behind.
  std::vector<std::string> argv{
    spec.planner_host_command, "--respawn", "--parent-pid", std::to_string(::getpid()), "--key",
    key};
  auto add = [&argv](const char * flag, const std::string & value) {
      if (!value.empty()) {
        argv.insert(argv.end(), {flag, value});
      }
    };
  add("--planner", spec.python_planner);
  add("--module", spec.python_module);
  for (const auto & item : spec.python_delegates) {
    add("--delegate", item);
  }
  for (const auto & path : spec.python_path) {
    add("--path", path);
  }
  add("--listen", listen_endpoint);
  argv.insert(argv.end(), spec.planner_host_args.begin(), spec.planner_host_args.end());
  return argv;
}

LocalHost::LocalHost(
  const BridgeParameters & spec, std::string key, Logger logger, Duration stop_grace)
: key_(std::move(key)), endpoint_("tcp/127.0.0.1:" + std::to_string(pick_free_tcp_port())),
  logger_(std::move(logger)), stop_grace_(stop_grace)
{
  std::vector<std::string> args = local_host_arguments(spec, key_, endpoint_);
  const std::vector<char *> argv = pointers(args);
  // A process group of its own (stop() signals the group: the host's workers too), and no
  // signal blocked by the thread that starts it.
  posix_spawnattr_t attributes;
  ::posix_spawnattr_init(&attributes);
  ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  ::posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t none;
  ::sigemptyset(&none);
  ::posix_spawnattr_setsigmask(&attributes, &none);
  pid_t pid = 0;
  // $PATH searched as a shell does; glibc reports a failed exec here (ENOENT, EACCES, ...)
  const int error = ::posix_spawnp(&pid, argv[0], nullptr, &attributes, argv.data(), environ);
  ::posix_spawnattr_destroy(&attributes);
  if (error != 0) {
    throw std::runtime_error("cannot start '" + args.front() + "': " + std::strerror(error));
  }
  pid_ = pid;
  log(
    logger_, LogLevel::Info,
    "planner host started (pid " + std::to_string(pid) + "): " + command_line(args));
}

int LocalHost::stop()
{
  const pid_t pid = std::exchange(pid_, 0);
  if (pid <= 0) {
    return -1;
  }
  ::kill(pid, SIGTERM);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + stop_grace_;
  pid_t waited = 0;
  while ((waited = ::waitpid(pid, &status, WNOHANG)) == 0 &&
    std::chrono::steady_clock::now() < deadline)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (waited == 0) {
    log(
      logger_, LogLevel::Warn, "planner host (pid " + std::to_string(pid) +
      ") ignored SIGTERM; killing it");
    ::kill(-pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  ::kill(-pid, SIGKILL);  // whatever the host left in its process group (its workers)
  return status;
}

}  // namespace nav2_pyif_bridge::client
