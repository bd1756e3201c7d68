// ctest-labels: unit
// The `middleware:` and `safety:` sections: documented defaults, the Cyclone DDS configuration they give
// (loopback: unicast peer 127.0.0.1, multicast off; another interface: that interface, multicast on), and bad
// values refused with the key named (no XML injection through names).
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "middleware/command_guard.hpp"
#include "middleware/dds.hpp"
#include "middleware/middleware_config.hpp"
#include "middleware/topics.hpp"

namespace mw = centaur::middleware;

namespace {

mw::MiddlewareConfig read(const std::string& yaml) {
  YAML::Node root = centaur::mergeYaml(centaur::loadYamlString(mw::MiddlewareConfig::defaultsYaml(), "d"),
                                       centaur::loadYamlString(yaml, "test.yaml"));
  centaur::YamlReader r(root["middleware"], "test.yaml", "middleware");
  mw::MiddlewareConfig c;
  c.read(r);
  return c;
}

std::string errorOf(const std::string& yaml) {
  try {
    read(yaml);
  } catch (const centaur::InputError& e) {
    return e.what();
  }
  return "<accepted>";
}

}  // namespace

TEST(MiddlewareConfig, DefaultsGiveALoopbackUnicastDomain) {
  const mw::MiddlewareConfig c = read("{}");
  EXPECT_EQ(c.domain, 0);
  EXPECT_EQ(c.ns, "/centaur");
  const std::string xml = c.cycloneConfig();
  EXPECT_NE(xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Peer address=\"127.0.0.1\"/>"), std::string::npos) << xml;
}

TEST(MiddlewareConfig, ARealInterfaceKeepsMulticastAndAddsPeers) {
  const mw::MiddlewareConfig c = read("middleware: {interface: eth0, peers: [10.0.0.2, robot.local], domain: 42}");
  const std::string xml = c.cycloneConfig();
  EXPECT_NE(xml.find("name=\"eth0\""), std::string::npos);
  EXPECT_EQ(xml.find("AllowMulticast"), std::string::npos);
  EXPECT_NE(xml.find("<Peer address=\"10.0.0.2\"/><Peer address=\"robot.local\"/>"), std::string::npos) << xml;
  EXPECT_EQ(c.domain, 42);
  EXPECT_EQ(read("middleware: {interface: auto}").cycloneConfig(), "") << "auto: CYCLONEDDS_URI or Cyclone's own";
}

TEST(MiddlewareConfig, BadValuesNameTheKey) {
  EXPECT_NE(errorOf("middleware: {domain: 233}").find("middleware.domain"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {interface: 'lo\"/><x'}").find("middleware.interface"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {peers: ['a b']}").find("middleware.peers"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {peers: 3}").find("middleware.peers"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {namespace: centaur}").find("middleware.namespace"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {namespace: /a//b}").find("middleware.namespace"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {config_file: /nonexistent.xml}").find("middleware.config_file"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {bogus: 1}").find("middleware.bogus"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {realtime_priority: 99}").find("middleware.realtime_priority"), std::string::npos);
  EXPECT_NE(errorOf("middleware: {realtime_priority: -1}").find("middleware.realtime_priority"), std::string::npos);
}

TEST(MiddlewareConfig, RealtimePriorityPutsTheNodeAndCycloneThreadsUnderFifo) {
  // In a child process (the test's own scheduling stays): a participant created with realtime_priority 3 runs
  // the creating thread and every thread Cyclone DDS starts for it under SCHED_FIFO 3. Without the privilege
  // the participant is refused with the key named.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    mw::MiddlewareConfig c = read("middleware: {domain: 151, realtime_priority: 3}");
    int code = 0;
    try {
      mw::Participant participant(c);
      int threads = 0, fifo = 0;
      for (const auto& e : std::filesystem::directory_iterator("/proc/self/task")) {
        const pid_t tid = static_cast<pid_t>(std::stoi(e.path().filename().string()));
        sched_param p{};
        ++threads;
        if (::sched_getscheduler(tid) == SCHED_FIFO && ::sched_getparam(tid, &p) == 0 && p.sched_priority == 3) ++fifo;
      }
      code = threads > 1 && fifo == threads ? 0 : 1;
    } catch (const centaur::InputError& e) {
      code = std::string(e.what()).find("middleware.realtime_priority") != std::string::npos ? 3 : 2;
    }
    ::_exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 3) GTEST_SKIP() << "SCHED_FIFO not permitted here (refused with the key named)";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: a thread not under SCHED_FIFO 3; 2: refused without naming the key";
}

TEST(MiddlewareConfig, SafetyDefaultsAndRanges) {
  YAML::Node root = centaur::loadYamlString(mw::SafetyConfig::defaultsYaml(), "d");
  centaur::YamlReader r(root["safety"], "d", "safety");
  mw::SafetyConfig s;
  s.read(r);
  EXPECT_EQ(s.watchdog_timeout, 0.005);
  EXPECT_EQ(s.damping_scale, 3.0);
  root["safety"]["watchdog_timeout"] = 0.0;
  centaur::YamlReader bad(root["safety"], "d", "safety");
  EXPECT_THROW(s.read(bad), centaur::InputError);
}

TEST(Topics, RosNamesAndTypesFollowTheConventions) {
  int count = 0;
  const mw::TopicSpec* const* all = mw::allTopics(count);
  ASSERT_EQ(count, 9);
  for (int i = 0; i < count; ++i) {
    const mw::TopicSpec& t = *all[i];
    // "<pkg>/msg/<Type>" <-> DDS "<pkg>::msg::dds_::<Type>_"
    std::string ros = t.ros_type;
    const auto slash = ros.find("/msg/");
    ASSERT_NE(slash, std::string::npos) << ros;
    const std::string dds = ros.substr(0, slash) + "::msg::dds_::" + ros.substr(slash + 5) + "_";
    EXPECT_EQ(dds, t.descriptor->m_typename) << t.name;
    EXPECT_GE(t.depth, 1);
  }
}
