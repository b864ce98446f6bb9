#include "nav2_pyif_bridge/client/local_host.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

extern char ** environ;  // NOLINT: POSIX

namespace nav2_pyif_bridge::client
{
namespace
{

std::string describe_status(int status)
{
  if (WIFEXITED(status)) {
    return "exited with status " + std::to_string(WEXITSTATUS(status));
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char * name = ::strsignal(sig);
    return "killed by signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
  }
  return "ended with wait status " + std::to_string(status);
}

std::string seconds_text(Duration d)
{
  return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count() / 1000.0)
         .substr(0, 4) + " s";
}

std::string command_line(const std::vector<std::string> & argv)
{
  std::string out;
  for (const auto & arg : argv) {
    out += (out.empty() ? "" : " ") + arg;
  }
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
  std::vector<std::string> argv{spec.planner_host_command, "--key", key};
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

// --- ProcessSupervisor ----------------------------------------------------------------------

ProcessSupervisor::ProcessSupervisor(Options options, Logger logger)
: options_(std::move(options)), logger_(std::move(logger))
{
  if (options_.argv.empty()) {
    throw std::invalid_argument("ProcessSupervisor: empty argv");
  }
}

ProcessSupervisor::~ProcessSupervisor()
{
  stop();
}

void ProcessSupervisor::start()
{
  environment_.clear();
  for (char ** entry = environ; entry && *entry; ++entry) {
    if (std::strncmp(*entry, "PYTHONUNBUFFERED=", 17) != 0) {
      environment_.emplace_back(*entry);
    }
  }
  environment_.emplace_back("PYTHONUNBUFFERED=1");

  if (thread_.joinable()) {
    throw std::logic_error("ProcessSupervisor::start called twice");
  }
  stopping_ = false;
  const std::string error = spawn();
  if (!error.empty()) {
    throw std::runtime_error(error);
  }
  thread_ = std::thread([this]() {supervise();});
}

std::string ProcessSupervisor::spawn()
{
  std::vector<char *> argv;
  for (auto & arg : options_.argv) {
    argv.push_back(arg.data());
  }
  argv.push_back(nullptr);
  std::vector<char *> envp;
  for (auto & entry : environment_) {
    envp.push_back(entry.data());
  }
  envp.push_back(nullptr);

  int error_pipe[2];
  if (::pipe2(error_pipe, O_CLOEXEC) != 0) {
    return "pipe: " + std::string(std::strerror(errno));
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // The child: async-signal-safe calls only until execve.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) {
      ::_exit(127);
    }
    sigset_t none;
    ::sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::execvpe(argv[0], argv.data(), envp.data());  // $PATH searched as a shell does
    const int error = errno;
    [[maybe_unused]] const auto written = ::write(error_pipe[1], &error, sizeof(error));
    ::_exit(127);
  }
  ::close(error_pipe[1]);
  if (pid < 0) {
    ::close(error_pipe[0]);
    return "fork: " + std::string(std::strerror(errno));
  }
  int exec_error = 0;
  ssize_t got = 0;
  do {
    got = ::read(error_pipe[0], &exec_error, sizeof(exec_error));
  } while (got < 0 && errno == EINTR);
  ::close(error_pipe[0]);
  if (got == static_cast<ssize_t>(sizeof(exec_error))) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    return "cannot start '" + options_.argv.front() + "': " + std::strerror(exec_error);
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pid_ = pid;
    ++starts_;
    if (stopping_) {
      ::kill(pid, SIGKILL);  // stop() came while it started, and will not signal it
    }
  }
  changed_.notify_all();
  log(
    logger_, LogLevel::Info,
    "planner host started (pid " + std::to_string(pid) + "): " + command_line(options_.argv));
  return {};
}

void ProcessSupervisor::supervise()
{
  Duration delay = options_.restart_delay;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (const pid_t pid = pid_; pid > 0) {  // the process started last: wait for its end
      const auto started_at = std::chrono::steady_clock::now();
      lock.unlock();
      int status = 0;
      pid_t waited = 0;
      do {
        waited = ::waitpid(pid, &status, 0);
      } while (waited < 0 && errno == EINTR);
      lock.lock();
      pid_ = 0;
      last_exit_ = waited == pid ? describe_status(status) : "lost (waitpid failed)";
      changed_.notify_all();
      if (std::chrono::steady_clock::now() - started_at >= options_.stable_after) {
        delay = options_.restart_delay;
      }
      if (!stopping_) {
        log(
          logger_, LogLevel::Error, "planner host (pid " + std::to_string(pid) + ") " +
          last_exit_ + "; restarting in " + seconds_text(delay));
      }
    }
    if (changed_.wait_for(lock, delay, [this]() {return stopping_;})) {
      return;
    }
    delay = std::min(delay * 2, options_.max_restart_delay);
    lock.unlock();
    const std::string error = spawn();
    lock.lock();
    if (!error.empty()) {
      log(logger_, LogLevel::Error, "planner host: " + error);
    }
  }
}

void ProcessSupervisor::stop()
{
  pid_t pid = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!thread_.joinable()) {
      return;
    }
    stopping_ = true;
    pid = pid_;
  }
  changed_.notify_all();
  if (pid > 0) {
    ::kill(pid, SIGTERM);
    std::unique_lock<std::mutex> lock(mutex_);
    if (!changed_.wait_for(lock, options_.stop_grace, [this]() {return pid_ == 0;})) {
      log(
        logger_, LogLevel::Warn, "planner host (pid " + std::to_string(pid) +
        ") ignored SIGTERM; killing it");
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
    }
  }
  thread_.join();
  if (pid > 0) {
    ::kill(-pid, SIGKILL);  // whatever the host left in its process group (its workers)
  }
}

pid_t ProcessSupervisor::pid() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return pid_;
}

unsigned ProcessSupervisor::starts() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return starts_;
}

std::string ProcessSupervisor::last_exit() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return last_exit_;
}

bool ProcessSupervisor::wait_for_starts(unsigned n, Duration timeout) const
{
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [this, n]() {return starts_ >= n;});
}

// --- LocalHost ------------------------------------------------------------------------------

LocalHost::LocalHost(
  const BridgeParameters & spec, std::string key, Logger logger,
  ProcessSupervisor::Options supervision)
: key_(std::move(key))
{
  endpoint_ = "tcp/127.0.0.1:" + std::to_string(pick_free_tcp_port());
  supervision.argv = local_host_arguments(spec, key_, endpoint_);
  process_ = std::make_unique<ProcessSupervisor>(std::move(supervision), std::move(logger));
  process_->start();
}

}  // namespace nav2_pyif_bridge::client
