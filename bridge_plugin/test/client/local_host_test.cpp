// The local planner host: its command line, and the start and stop of a real child process
// (a shell script stands in for planner-host; its restarts are planner-host --respawn's,
// tests/test_respawn.py).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "nav2_pyif_bridge/client/keys.hpp"
#include "nav2_pyif_bridge/client/local_host.hpp"

namespace nav2_pyif_bridge::client
{
namespace
{

using namespace std::chrono_literals;

// Running, not a zombie: an orphan's zombie may linger where PID 1 does not reap.
bool alive(pid_t pid)
{
  if (pid <= 0 || ::kill(pid, 0) != 0) {
    return false;
  }
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const auto paren = line.rfind(')');
  return paren == std::string::npos || line.size() < paren + 3 || line[paren + 2] != 'Z';
}

// This process's id, as the keeper is told it (--parent-pid).
std::string this_pid() {return std::to_string(::getpid());}

// A fake planner-host in a fresh directory, $DIR: a shell script running `body`.
struct FakeHost
{
  explicit FakeHost(const std::string & body)
  {
    char dir_template[] = "/tmp/nav2_pyif_local_host_XXXXXX";
    dir = ::mkdtemp(dir_template) ? dir_template : "";
    std::ofstream(dir + "/planner-host") << "#!/bin/sh\nDIR=" << dir << "\n" << body << "\n";
    ::chmod((dir + "/planner-host").c_str(), 0755);
  }
  ~FakeHost() {std::filesystem::remove_all(dir);}

  BridgeParameters spec() const
  {
    BridgeParameters spec;
    spec.planner_host_command = dir + "/planner-host";
    spec.python_planner = "pkg.m:C";
    return spec;
  }

  // The line the script wrote to $DIR/`name`, once it has ("" after 2 s).
  std::string written(const std::string & name) const
  {
    std::string line;
    for (int i = 0; i < 200 && line.empty(); ++i) {
      std::this_thread::sleep_for(10ms);
      std::ifstream in(dir + "/" + name);
      std::getline(in, line);
    }
    return line;
  }

  std::string dir;
};

TEST(LocalHost, CommandLineForAModuleWithDelegates)
{
  BridgeParameters spec;
  spec.python_module = "nav2_pyif_planners.apf";
  spec.python_delegates = {"configure", "compute_velocity_commands=compute,set_plan=plan"};
  spec.python_path = {"/opt/p"};
  spec.planner_host_args = {"--isolation", "none"};
  EXPECT_EQ(
    local_host_arguments(spec, "nav2_pyif/local/cs/FollowPath", "tcp/127.0.0.1:7000"),
    (std::vector<std::string>{"planner-host", "--respawn", "--parent-pid", this_pid(), "--key",
      "nav2_pyif/local/cs/FollowPath", "--module", "nav2_pyif_planners.apf", "--delegate",
      "configure", "--delegate", "compute_velocity_commands=compute,set_plan=plan", "--path",
      "/opt/p", "--listen", "tcp/127.0.0.1:7000", "--isolation", "none"}));
  spec = BridgeParameters{};
  spec.planner_host_command = "/venv/bin/planner-host";
  spec.python_planner = "pkg.m:C";
  EXPECT_EQ(
    local_host_arguments(spec, "k", "tcp/127.0.0.1:1"),
    (std::vector<std::string>{"/venv/bin/planner-host", "--respawn", "--parent-pid", this_pid(),
      "--key", "k", "--planner", "pkg.m:C", "--listen", "tcp/127.0.0.1:1"}));
}

TEST(LocalHost, KeysAreValidPrefixes)
{
  EXPECT_EQ(local_host_key("controller_server", "FollowPath"),
    "nav2_pyif/local/controller_server/FollowPath");
  const std::string odd = local_host_key("a*b/c", "");
  EXPECT_EQ(odd, "nav2_pyif/local/a_b_c/_");
  EXPECT_NO_THROW(validate_prefix(odd));
}

TEST(LocalHost, PicksAFreePort)
{
  const auto port = pick_free_tcp_port();
  EXPECT_GT(port, 0);
}

TEST(LocalHost, StartsTheHostCommandOnALoopbackEndpoint)
{
  FakeHost fake("echo \"$@\" > $DIR/args\nexec sleep 60");
  LocalHost host(fake.spec(), local_host_key("controller_server", "FollowPath"), {}, 1s);
  EXPECT_EQ(host.endpoint().rfind("tcp/127.0.0.1:", 0), 0u);
  EXPECT_EQ(
    fake.written("args"), "--respawn --parent-pid " + this_pid() +
    " --key nav2_pyif/local/controller_server/FollowPath "
    "--planner pkg.m:C --listen " + host.endpoint());
}

TEST(LocalHost, StopEndsTheHostAndItsGroup)
{
  // A host with a worker: the worker (in the host's process group) must not outlive stop().
  FakeHost fake("sleep 60 & echo $! > $DIR/worker; wait");
  LocalHost host(fake.spec(), "k", {}, 300ms);
  const pid_t pid = host.pid();
  EXPECT_TRUE(alive(pid));
  const std::string worker_line = fake.written("worker");
  ASSERT_FALSE(worker_line.empty());
  const pid_t worker = std::stoi(worker_line);
  const auto start = std::chrono::steady_clock::now();
  host.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
  EXPECT_EQ(host.pid(), 0);
  EXPECT_FALSE(alive(pid));
  EXPECT_EQ(host.stop(), -1);  // once
  for (int i = 0; i < 100 && alive(worker); ++i) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_FALSE(alive(worker));
}

TEST(LocalHost, KillsAHostThatIgnoresSigterm)
{
  FakeHost fake("trap '' TERM; echo ready > $DIR/ready; while :; do sleep 0.05; done");
  std::vector<std::string> logs;
  LocalHost host(fake.spec(), "k", [&](LogLevel, const std::string & t) {logs.push_back(t);},
    300ms);
  ASSERT_EQ(fake.written("ready"), "ready");  // the trap is set
  const int status = host.stop();
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
  EXPECT_NE(logs.back().find("ignored SIGTERM; killing it"), std::string::npos) << logs.back();
}

TEST(LocalHost, AMissingProgramIsAClearError)
{
  FakeHost fake("exit 0");
  ::chmod((fake.dir + "/planner-host").c_str(), 0644);  // not executable, even for root
  BridgeParameters spec = fake.spec();
  const std::vector<std::string> programs{"no-such-planner-host-here", spec.planner_host_command};
  for (const std::string & program : programs) {
    spec.planner_host_command = program;
    try {
      LocalHost host(spec, "k");
      FAIL() << "started " << program;
    } catch (const std::runtime_error & e) {
      EXPECT_NE(std::string(e.what()).find("cannot start '" + program + "'"), std::string::npos)
        << e.what();
    }
  }
}

TEST(LocalHost, HostInheritsThePluginsEnvironment)
{
  ::setenv("NAV2_PYIF_TEST_MARK", "kept", 1);
  FakeHost fake("echo $NAV2_PYIF_TEST_MARK > $DIR/env; exec sleep 60");
  LocalHost host(fake.spec(), "k", {}, 1s);
  ::unsetenv("NAV2_PYIF_TEST_MARK");
  EXPECT_EQ(fake.written("env"), "kept");
}

}  // namespace
}  // namespace nav2_pyif_bridge::client
