// ctest-labels: middleware integration
// The wire contract, checked from the outside: a subscriber written only from the IDL (the idlc-generated
// types and Cyclone DDS's C API, none of the nodes' code) receives the robot's joint states and IMU under the
// ROS 2 topic and type names (DDS topic rt/centaur/joint_states, type sensor_msgs::msg::dds_::JointState_),
// with CENTAURO's 39 joints, and the robot status under centaur_msgs::msg::dds_::RobotStatus_.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>

#include <dds/dds.h>

#include "centaur_msgs.h"
#include "sensor_msgs.h"
#include "support/child_process.hpp"
#include "support/temp_dir.hpp"

namespace {

constexpr int kDomain = 51;
const char* kLoopback =
    "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
    "<MaxAutoParticipantIndex>30</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers>"
    "</Discovery></Domain></CycloneDDS>";

/// Takes one sample of `desc` on `topic` within `timeout_s`; calls check(sample). False on timeout.
template <class Msg, class Check>
bool receiveOne(dds_entity_t participant, const dds_topic_descriptor_t* desc, const char* topic, double timeout_s,
                Check check) {
  const dds_entity_t t = dds_create_topic(participant, desc, topic, nullptr, nullptr);
  if (t < 0) return false;
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_BEST_EFFORT, 0);  // as a ROS sensor-data subscriber
  const dds_entity_t reader = dds_create_reader(participant, t, qos, nullptr);
  dds_delete_qos(qos);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info[1];
    const dds_return_t n = dds_take(reader, samples, info, 1, 1);
    if (n > 0 && info[0].valid_data) {
      check(*static_cast<const Msg*>(samples[0]));
      dds_return_loan(reader, samples, n);
      dds_delete(reader);
      return true;
    }
    if (n > 0) dds_return_loan(reader, samples, n);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  dds_delete(reader);
  return false;
}

}  // namespace

TEST(WireContract, RosNamedTopicsAndTypesCarryTheRobotState) {
  const centaur_test::TempDir dir("wire");
  // The robot waits for a controller; until one answers it republishes its first state every 100 ms.
  centaur_test::ChildProcess robot(
      CENTAUR_BIN,
      {"robot", "stand", "--lockstep", "--set", "middleware.domain=" + std::to_string(kDomain), "--set",
       "robot_node.connect_timeout=30"},
      dir.file("robot.log"));
  ASSERT_GE(dds_create_domain(kDomain, kLoopback), 0);
  const dds_entity_t participant = dds_create_participant(kDomain, nullptr, nullptr);
  ASSERT_GT(participant, 0);
  bool joints_ok = false;
  ASSERT_TRUE(receiveOne<sensor_msgs_msg_dds__JointState_>(
      participant, &sensor_msgs_msg_dds__JointState__desc, "rt/centaur/joint_states", 30.0,
      [&](const sensor_msgs_msg_dds__JointState_& m) {
        EXPECT_EQ(m.name._length, 39u);
        EXPECT_EQ(m.position._length, 39u);
        EXPECT_EQ(m.velocity._length, 39u);
        EXPECT_EQ(m.effort._length, 39u);
        bool finite = true;
        for (std::uint32_t i = 0; i < m.position._length; ++i) finite = finite && std::isfinite(m.position._buffer[i]);
        EXPECT_TRUE(finite);
        EXPECT_STREQ(m.name._buffer[0], "torso_yaw");
        joints_ok = true;
      }))
      << robot.output();
  EXPECT_TRUE(joints_ok);
  ASSERT_TRUE(receiveOne<sensor_msgs_msg_dds__Imu_>(
      participant, &sensor_msgs_msg_dds__Imu__desc, "rt/centaur/imu", 10.0, [](const sensor_msgs_msg_dds__Imu_& m) {
        const auto& q = m.orientation;
        EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0, 1e-9);
        EXPECT_NEAR(q.w, 1.0, 1e-3) << "CENTAURO starts level";
        EXPECT_STREQ(m.header.frame_id, "imu_link");
      }));
  ASSERT_TRUE(receiveOne<centaur_msgs_msg_dds__RobotStatus_>(
      participant, &centaur_msgs_msg_dds__RobotStatus__desc, "rt/centaur/robot_status", 10.0,
      [](const centaur_msgs_msg_dds__RobotStatus_& m) { EXPECT_EQ(m.mode, 0) << "waiting for a controller"; }));
  dds_delete(participant);
  robot.signal(SIGTERM);
  EXPECT_TRUE(robot.wait(10.0));
}
