// ctest-labels: unit
// RobotState over sensor_msgs/JointState + sensor_msgs/Imu and JointCommand over centaur_msgs/JointCommand:
// every double arrives with the same bits, the time as whole nanoseconds (the robot clock), joints sent in
// another order are mapped by name, and what does not fit (other joints, ragged arrays, a non-unit quaternion,
// a bad stamp) is refused without touching the decoded state. Encoding and decoding allocate nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "middleware/state_codec.hpp"
#include "support/allocation_counter.hpp"

namespace mw = centaur::middleware;
using centaur::RobotState;

namespace {

const std::vector<std::string> kNames = {"j_a", "j_b", "j_c", "j_d"};

RobotState randomState(std::mt19937_64& rng, std::int64_t ns) {
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  RobotState s;
  s.resize(4);
  s.t = centaur::secondsFromNanoseconds(ns);
  for (int i = 0; i < 4; ++i) s.q[i] = u(rng), s.qd[i] = u(rng), s.tau[i] = 100.0 * u(rng);
  s.imu_quat = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
  s.imu_omega = Eigen::Vector3d(u(rng), u(rng), u(rng));
  s.imu_acc = Eigen::Vector3d(u(rng), u(rng), 9.81 + u(rng));
  return s;
}

void expectSameBits(const RobotState& a, const RobotState& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.qd, b.qd);
  EXPECT_EQ(a.tau, b.tau);
  EXPECT_EQ(a.imu_quat.coeffs(), b.imu_quat.coeffs());
  EXPECT_EQ(a.imu_omega, b.imu_omega);
  EXPECT_EQ(a.imu_acc, b.imu_acc);
}

}  // namespace

TEST(StateCodec, EveryValueArrivesBitForBitAndTimesAsNanoseconds) {
  std::mt19937_64 rng(3);
  mw::StateEncoder enc(kNames, "imu_link");
  mw::StateDecoder dec(kNames);
  RobotState out;
  out.resize(4);
  for (std::int64_t k = 0; k < 100; ++k) {
    const std::int64_t ns = 1000000 * k + 3;  // 1 ms periods, not a multiple of a second
    const RobotState in = randomState(rng, ns);
    enc.encode(in);
    EXPECT_EQ(enc.jointState().header.stamp.sec, static_cast<std::int32_t>(ns / 1000000000));
    EXPECT_EQ(enc.jointState().header.stamp.nanosec, static_cast<std::uint32_t>(ns % 1000000000));
    EXPECT_EQ(enc.imu().orientation.w, in.imu_quat.w());  // ROS order x, y, z, w
    ASSERT_TRUE(dec.acceptImu(enc.imu()));
    EXPECT_FALSE(dec.complete()) << "half an instant is not a state";
    ASSERT_TRUE(dec.acceptJoints(enc.jointState()));
    ASSERT_TRUE(dec.complete());
    EXPECT_EQ(dec.take(out), ns);
    expectSameBits(in, out);
    EXPECT_FALSE(dec.complete()) << "a state is taken once";
  }
}

TEST(StateCodec, JointsInAnotherOrderAreMappedByName) {
  mw::StateEncoder enc({"j_c", "j_a", "j_d", "j_b"}, "imu");
  mw::StateDecoder dec(kNames);
  RobotState in;
  in.resize(4);
  in.q << 3.0, 1.0, 4.0, 2.0;  // robot order c, a, d, b
  in.t = 0.5;
  enc.encode(in);
  ASSERT_TRUE(dec.acceptJoints(enc.jointState()));
  ASSERT_TRUE(dec.acceptImu(enc.imu()));
  RobotState out;
  out.resize(4);
  dec.take(out);
  EXPECT_EQ(out.q, Eigen::Vector4d(1.0, 2.0, 3.0, 4.0));
}

TEST(StateCodec, WhatDoesNotFitIsRefusedWithoutTouchingTheState) {
  mw::StateEncoder enc(kNames, "imu");
  std::mt19937_64 rng(5);
  enc.encode(randomState(rng, 7000000));
  mw::StateDecoder dec(kNames);
  ASSERT_TRUE(dec.acceptJoints(enc.jointState()));
  ASSERT_TRUE(dec.acceptImu(enc.imu()));
  RobotState good;
  good.resize(4);
  dec.take(good);

  mw::JointStateMsg m = enc.jointState();
  m.header.stamp.nanosec += 1000000;  // a newer instant ...
  m.effort._length = 3;               // ... with a ragged array
  EXPECT_FALSE(dec.acceptJoints(m));
  m.effort._length = 4;
  std::string other = "j_x";
  char* names[4] = {m.name._buffer[0], m.name._buffer[1], other.data(), m.name._buffer[3]};
  m.name._buffer = names;
  EXPECT_FALSE(dec.acceptJoints(m)) << "a joint we do not have";
  char* twice[4] = {names[0], names[1], names[1], names[3]};
  m.name._buffer = twice;
  EXPECT_FALSE(dec.acceptJoints(m)) << "a joint named twice";
  mw::ImuMsg imu = enc.imu();
  imu.header.stamp.nanosec += 1000000;
  imu.orientation.w *= 1.01;
  EXPECT_FALSE(dec.acceptImu(imu)) << "not a unit quaternion";
  imu.orientation = enc.imu().orientation;
  imu.header.stamp.nanosec = 1000000000u;
  EXPECT_FALSE(dec.acceptImu(imu)) << "nanosec out of range";
  EXPECT_FALSE(dec.complete()) << "nothing new was accepted";
}

TEST(StateCodec, CommandEncodingCarriesTheStampSessionAndIncreasingSeq) {
  mw::CommandEncoder enc(kNames, 0xfeed);
  centaur::JointCommand c;
  c.resize(4);
  c.q_ref << 0.1, 0.2, 0.3, 0.4;
  c.kd << 1, 2, 3, std::nextafter(4.0, 5.0);
  enc.encode(c, 2500000001);
  enc.encode(c, 2501000001);
  const mw::JointCommandMsg& m = enc.message();
  EXPECT_EQ(m.session, 0xfeedu);
  EXPECT_EQ(m.seq, 2u);
  EXPECT_EQ(mw::nanosecondsFromTime(m.state_stamp), 2501000001);
  ASSERT_EQ(m.name._length, 4u);
  EXPECT_STREQ(m.name._buffer[2], "j_c");
  EXPECT_EQ(m.kd._buffer[3], std::nextafter(4.0, 5.0));
}

TEST(StateCodec, EncodingAndDecodingAllocateNothing) {
  std::mt19937_64 rng(9);
  mw::StateEncoder enc(kNames, "imu");
  mw::StateDecoder dec(kNames);
  mw::CommandEncoder cenc(kNames, 1);
  RobotState out;
  out.resize(4);
  std::vector<RobotState> states;
  for (int k = 0; k < 50; ++k) states.push_back(randomState(rng, 1000000 * (k + 1)));
  centaur::JointCommand c;
  c.resize(4);
  enc.encode(states[0]);
  dec.acceptJoints(enc.jointState());  // the first message maps the names (allocates once)
  const long before = centaur_test::heapAllocations();
  for (const RobotState& s : states) {
    enc.encode(s);
    dec.acceptJoints(enc.jointState());
    dec.acceptImu(enc.imu());
    dec.take(out);
    cenc.encode(c, 1);
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
}
