// ctest-labels: unit
// The robot side's check of every command from the wire: each class of bad command is rejected whole and
// counted by its reason, nothing of it reaches the output; references in the tolerance band are clamped and
// counted; stale commands (older state, repeated seq) are refused, a new controller session starts afresh;
// check() allocates nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "middleware/command_guard.hpp"
#include "support/allocation_counter.hpp"

namespace mw = centaur::middleware;
using mw::Verdict;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Three joints: a limited one, a continuous wheel and one with a small effort limit.
mw::JointLimits limits() {
  mw::JointLimits l;
  l.names = {"hip", "wheel", "wrist"};
  l.q_lo = Eigen::Vector3d(-1.0, -kInf, -0.5);
  l.q_hi = Eigen::Vector3d(1.0, kInf, 0.5);
  l.tau_max = Eigen::Vector3d(300.0, 50.0, 10.0);
  return l;
}

/// A valid command message answering the state at `state_ns`, with buffers it owns.
struct Msg {
  std::vector<std::string> names = {"hip", "wheel", "wrist"};
  std::vector<char*> ptrs;
  std::vector<double> q_ref{0.1, 5.0, 0.2}, qd_ref{0.0, 1.0, 0.0}, tau_ff{10.0, 0.0, 1.0}, kp{1000, 100, 50},
      kd{10, 2, 0.5};
  char empty[1] = {'\0'};
  mw::JointCommandMsg m{};
  Msg(std::int64_t state_ns, std::uint64_t seq, std::uint64_t session = 7) {
    m.header.frame_id = empty;
    m.session = session;
    m.seq = seq;
    m.state_stamp = mw::timeFromNanoseconds(state_ns);
  }
  const mw::JointCommandMsg& get() {
    ptrs.clear();
    for (auto& n : names) ptrs.push_back(n.data());
    auto bind = [](dds_sequence_double& s, std::vector<double>& v) {
      s = {static_cast<std::uint32_t>(v.size()), static_cast<std::uint32_t>(v.size()), v.data(), false};
    };
    m.name = {static_cast<std::uint32_t>(ptrs.size()), static_cast<std::uint32_t>(ptrs.size()), ptrs.data(), false};
    bind(m.q_ref, q_ref);
    bind(m.qd_ref, qd_ref);
    bind(m.tau_ff, tau_ff);
    bind(m.kp, kp);
    bind(m.kd, kd);
    return m;
  }
};

centaur::JointCommand outputSentinel() {
  centaur::JointCommand c;
  c.resize(3);
  c.q_ref.setConstant(-42.0);
  return c;
}

}  // namespace

TEST(CommandGuard, AValidCommandIsAppliedExactly) {
  mw::CommandGuard g(limits(), mw::SafetyConfig{});
  Msg msg(1000000, 1);
  centaur::JointCommand out = outputSentinel();
  ASSERT_EQ(g.check(msg.get(), 1000000, out), Verdict::kApplied);
  EXPECT_EQ(out.q_ref, Eigen::Vector3d(0.1, 5.0, 0.2));
  EXPECT_EQ(out.qd_ref, Eigen::Vector3d(0.0, 1.0, 0.0));
  EXPECT_EQ(out.tau_ff, Eigen::Vector3d(10.0, 0.0, 1.0));
  EXPECT_EQ(out.kp, Eigen::Vector3d(1000, 100, 50));
  EXPECT_EQ(out.kd, Eigen::Vector3d(10, 2, 0.5));
  EXPECT_EQ(g.counters().applied, 1u);
  EXPECT_EQ(g.counters().rejected, 0u);
  EXPECT_EQ(g.lastAppliedSeq(), 1u);
  EXPECT_EQ(g.lastAppliedStateStamp(), 1000000);
}

TEST(CommandGuard, EveryBadClassIsRejectedWholeAndCountedByReason) {
  struct Case {
    const char* what;
    void (*mutate)(Msg&);
    Verdict verdict;
  };
  const std::vector<Case> cases = {
      {"one joint fewer", [](Msg& m) { m.names.pop_back(); }, Verdict::kMalformed},
      {"ragged arrays", [](Msg& m) { m.kd.pop_back(); }, Verdict::kMalformed},
      {"a wrong name", [](Msg& m) { m.names[1] = "wheel_9"; }, Verdict::kMalformed},
      {"names in another order", [](Msg& m) { std::swap(m.names[0], m.names[2]); }, Verdict::kMalformed},
      {"NaN q_ref", [](Msg& m) { m.q_ref[0] = std::nan(""); }, Verdict::kNonFinite},
      {"Inf tau_ff", [](Msg& m) { m.tau_ff[2] = kInf; }, Verdict::kNonFinite},
      {"NaN kd", [](Msg& m) { m.kd[1] = std::nan(""); }, Verdict::kNonFinite},
      {"negative kp", [](Msg& m) { m.kp[0] = -1.0; }, Verdict::kGains},
      {"kp above max", [](Msg& m) { m.kp[1] = 5001.0; }, Verdict::kGains},
      {"kd above max", [](Msg& m) { m.kd[2] = 501.0; }, Verdict::kGains},
      {"q_ref beyond limit + tolerance", [](Msg& m) { m.q_ref[0] = 1.06; }, Verdict::kLimits},
      {"q_ref below limit - tolerance", [](Msg& m) { m.q_ref[2] = -0.56; }, Verdict::kLimits},
      {"qd_ref above max_velocity", [](Msg& m) { m.qd_ref[1] = -101.0; }, Verdict::kLimits},
  };
  std::uint64_t rejected = 0;
  for (const Case& c : cases) {
    mw::CommandGuard g(limits(), mw::SafetyConfig{});
    Msg msg(1000000, 1);
    c.mutate(msg);
    centaur::JointCommand out = outputSentinel();
    EXPECT_EQ(g.check(msg.get(), 1000000, out), c.verdict) << c.what;
    EXPECT_EQ(out.q_ref, Eigen::Vector3d::Constant(-42.0)) << c.what << ": nothing may reach the output";
    EXPECT_EQ(g.counters().rejected, 1u) << c.what;
    EXPECT_EQ(g.counters().applied, 0u) << c.what;
    const auto& k = g.counters();
    EXPECT_EQ(k.malformed + k.non_finite + k.gains + k.limits + k.stale, 1u) << c.what;
    ++rejected;
  }
  EXPECT_EQ(rejected, cases.size());
}

TEST(CommandGuard, ReferencesInTheToleranceBandAreClampedAndCounted) {
  mw::CommandGuard g(limits(), mw::SafetyConfig{});
  Msg msg(1000000, 1);
  msg.q_ref = {1.04, -1e6, -0.53};  // hip 0.04 beyond, the wheel is continuous, wrist 0.03 beyond
  msg.tau_ff = {-400.0, 0.0, 10.0};  // hip above its 300 N m effort limit: clamped (the drive saturates anyway)
  centaur::JointCommand out = outputSentinel();
  ASSERT_EQ(g.check(msg.get(), 1000000, out), Verdict::kApplied);
  EXPECT_EQ(out.q_ref, Eigen::Vector3d(1.0, -1e6, -0.5));
  EXPECT_EQ(out.tau_ff[0], -300.0);
  EXPECT_EQ(g.counters().clamped, 3u);
}

TEST(CommandGuard, StaleCommandsAreRefusedAndANewSessionStartsAfresh) {
  mw::CommandGuard g(limits(), mw::SafetyConfig{});
  centaur::JointCommand out = outputSentinel();
  Msg a(2000000, 5);
  ASSERT_EQ(g.check(a.get(), 2000000, out), Verdict::kApplied);
  Msg again(2000000, 5);  // the same seq again (a replay)
  EXPECT_EQ(g.check(again.get(), 3000000, out), Verdict::kStale);
  Msg older(1000000, 6);  // answers an older state than the one applied
  EXPECT_EQ(g.check(older.get(), 3000000, out), Verdict::kStale);
  Msg future(4000000, 7);  // answers a state that was never published
  EXPECT_EQ(g.check(future.get(), 3000000, out), Verdict::kStale);
  Msg next(3000000, 6);
  EXPECT_EQ(g.check(next.get(), 3000000, out), Verdict::kApplied);
  Msg restarted(3000000, 1, /*session=*/99);  // a restarted controller: seq starts again
  EXPECT_EQ(g.check(restarted.get(), 3000000, out), Verdict::kApplied);
  EXPECT_EQ(g.counters().stale, 3u);
  EXPECT_EQ(g.counters().applied, 3u);
}

TEST(CommandGuard, CheckAllocatesNothing) {
  mw::CommandGuard g(limits(), mw::SafetyConfig{});
  centaur::JointCommand out = outputSentinel();
  std::vector<Msg> msgs;
  msgs.reserve(200);
  for (int k = 0; k < 200; ++k) msgs.emplace_back(1000000LL * (k + 1), k + 1);
  for (auto& m : msgs) m.get();
  msgs[50].q_ref[0] = std::nan("");
  msgs[60].names[0] = "x";
  msgs[60].get();
  const long before = centaur_test::heapAllocations();
  for (auto& m : msgs) (void)g.check(m.m, 1000000LL * 300, out);
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
  EXPECT_EQ(g.counters().applied, 198u);
}
