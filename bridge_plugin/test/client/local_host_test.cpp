// The local planner host: its command line, and the supervision of a real child process
// (/bin/sh stands in for planner-host).
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
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

ProcessSupervisor::Options shell(const std::string & script)
{
  ProcessSupervisor::Options o;
  o.argv = {"sh", "-c", script};
  o.restart_delay = 10ms;
  o.max_restart_delay = 40ms;
  o.stop_grace = 300ms;
  return o;
}

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

TEST(LocalHost, CommandLineForTheSeedStyle)
{
  BridgeParameters spec;
  spec.python_module = "nav2_pyif_planners.apf";
  spec.python_delegates = {"configure", "compute_velocity_commands=compute,set_plan=plan"};
  spec.python_path = {"/opt/p"};
  spec.planner_host_args = {"--isolation", "none"};
  EXPECT_EQ(
    local_host_arguments(spec, "nav2_pyif/local/cs/FollowPath", "tcp/127.0.0.1:7000"),
    (std::vector<std::string>{"planner-host", "--key", "nav2_pyif/local/cs/FollowPath",
      "--module", "nav2_pyif_planners.apf", "--delegate", "configure", "--delegate",
      "compute_velocity_commands=compute,set_plan=plan", "--path", "/opt/p", "--listen",
      "tcp/127.0.0.1:7000", "--isolation", "none"}));
  spec = BridgeParameters{};
  spec.planner_host_command = "/venv/bin/planner-host";
  spec.python_planner = "pkg.m:C";
  EXPECT_EQ(
    local_host_arguments(spec, "k", "tcp/127.0.0.1:1"),
    (std::vector<std::string>{"/venv/bin/planner-host", "--key", "k", "--planner", "pkg.m:C",
      "--listen", "tcp/127.0.0.1:1"}));
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

TEST(ProcessSupervisor, RestartsAProcessThatExits)
{
  std::vector<std::string> logs;
  ProcessSupervisor process(shell("exit 3"), [&](LogLevel, const std::string & t) {logs.push_back(t);});
  process.start();
  ASSERT_TRUE(process.wait_for_starts(3, 10s));
  process.stop();
  bool restarting = false;
  for (const auto & line : logs) {
    restarting = restarting || line.find("exited with status 3; restarting in") != std::string::npos;
  }
  EXPECT_TRUE(restarting);
}

TEST(ProcessSupervisor, StopEndsTheProcessAndItsGroup)
{
  char dir_template[] = "/tmp/nav2_pyif_supervisor_XXXXXX";
  ASSERT_NE(::mkdtemp(dir_template), nullptr);
  const std::string pid_file = std::string(dir_template) + "/grandchild";
  // A host with a worker: the worker (in the host's process group) must not outlive stop().
  ProcessSupervisor process(shell("sleep 60 & echo $! > " + pid_file + "; wait"));
  process.start();
  const pid_t pid = process.pid();
  EXPECT_TRUE(alive(pid));
  pid_t worker = 0;
  for (int i = 0; i < 200 && worker == 0; ++i) {
    std::ifstream in(pid_file);
    in >> worker;
    std::this_thread::sleep_for(10ms);
  }
  ASSERT_GT(worker, 0);
  const auto start = std::chrono::steady_clock::now();
  process.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
  EXPECT_EQ(process.pid(), 0);
  EXPECT_EQ(process.starts(), 1u);  // stopping is no reason to restart
  for (int i = 0; i < 100 && alive(worker); ++i) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_FALSE(alive(worker));
  std::remove(pid_file.c_str());
  ::rmdir(dir_template);
}

TEST(ProcessSupervisor, KillsAProcessThatIgnoresSigterm)
{
  ProcessSupervisor process(shell("trap '' TERM; while :; do sleep 0.05; done"));
  process.start();
  std::this_thread::sleep_for(100ms);  // let the shell install its trap
  process.stop();
  EXPECT_NE(process.last_exit().find("killed by signal 9"), std::string::npos)
    << process.last_exit();
}

TEST(ProcessSupervisor, AMissingProgramIsAClearError)
{
  char file_template[] = "/tmp/nav2_pyif_not_executable_XXXXXX";
  const int fd = ::mkstemp(file_template);
  ASSERT_GE(fd, 0);
  ::close(fd);
  ::chmod(file_template, 0644);  // not executable, even for root
  const std::string programs[] = {"no-such-planner-host-here", file_template};
  for (const std::string & program : programs) {
    ProcessSupervisor::Options o;
    o.argv = {program};
    ProcessSupervisor process(o);
    try {
      process.start();
      FAIL() << "started " << program;
    } catch (const std::runtime_error & e) {
      EXPECT_NE(std::string(e.what()).find("cannot start '" + program + "'"), std::string::npos)
        << e.what();
    }
  }
  std::remove(file_template);
}

TEST(ProcessSupervisor, ChildSeesUnbufferedPython)
{
  char dir_template[] = "/tmp/nav2_pyif_supervisor_XXXXXX";
  ASSERT_NE(::mkdtemp(dir_template), nullptr);
  const std::string out = std::string(dir_template) + "/env";
  ProcessSupervisor process(shell("echo $PYTHONUNBUFFERED > " + out + "; sleep 60"));
  process.start();
  std::string value;
  for (int i = 0; i < 200 && value.empty(); ++i) {
    std::ifstream in(out);
    in >> value;
    std::this_thread::sleep_for(10ms);
  }
  process.stop();
  EXPECT_EQ(value, "1");
  std::remove(out.c_str());
  ::rmdir(dir_template);
}

TEST(LocalHost, StartsTheHostCommandOnALoopbackEndpoint)
{
  char dir_template[] = "/tmp/nav2_pyif_local_host_XXXXXX";
  ASSERT_NE(::mkdtemp(dir_template), nullptr);
  const std::string dir(dir_template);
  const std::string script = dir + "/fake-planner-host";
  {
    std::ofstream s(script);
    s << "#!/bin/sh\necho \"$@\" > " << dir << "/args\nexec sleep 60\n";
  }
  ::chmod(script.c_str(), 0755);
  BridgeParameters spec;
  spec.planner_host_command = script;
  spec.python_planner = "pkg.m:C";
  ProcessSupervisor::Options supervision;
  supervision.stop_grace = 1s;
  LocalHost host(spec, local_host_key("controller_server", "FollowPath"), {}, supervision);
  EXPECT_EQ(host.endpoint().rfind("tcp/127.0.0.1:", 0), 0u);
  std::string args;
  for (int i = 0; i < 200 && args.empty(); ++i) {
    std::ifstream in(dir + "/args");
    std::getline(in, args);
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(args, "--key nav2_pyif/local/controller_server/FollowPath --planner pkg.m:C --listen " +
    host.endpoint());
  host.process().stop();
  std::remove((dir + "/args").c_str());
  std::remove(script.c_str());
  ::rmdir(dir_template);
}

}  // namespace
}  // namespace nav2_pyif_bridge::client
