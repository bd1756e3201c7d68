#pragma once
// The robot never trusts the wire: every centaur_msgs/JointCommand is checked here before anything of it can
// reach the drives. A command is either applied whole (possibly with references clamped into the joint
// limits, counted) or rejected whole (counted by reason, never applied).
//
// Rules (SafetyConfig, YAML section `safety:`, docs/middleware.md):
//   malformed   joint count or names differ from the robot's (same order), or the arrays are ragged
//   non-finite  any NaN/Inf in q_ref, qd_ref, tau_ff, kp, kd
//   gains       kp outside [0, max_kp] or kd outside [0, max_kd]
//   limits      q_ref beyond a joint limit by more than q_ref_tolerance, |qd_ref| > max_velocity;
//               q_ref within the tolerance band is clamped to the limit, tau_ff to the effort limit (counted)
//   stale       answers a state older than the last applied one or newer than the latest published one, or a
//               seq not above the last applied one of the same session (a new session starts afresh)
// check() never allocates.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "controller/robot_interface.hpp"
#include "middleware/messages.hpp"

namespace centaur {
class YamlReader;
}

namespace centaur::middleware {

struct SafetyConfig {
  double watchdog_timeout = 0.005;  ///< [s] robot time without a valid command -> damping (realtime), [0.001, 10]
  double max_kp = 5000.0;           ///< [N m/rad], [0, 1e6]
  double max_kd = 500.0;            ///< [N m s/rad], [0, 1e5]
  double q_ref_tolerance = 0.05;    ///< [rad] band beyond a limit that is clamped instead of rejected, [0, 1]
  double max_velocity = 100.0;      ///< [rad/s] bound of |qd_ref|, [0, 1e4]
  double damping_scale = 3.0;       ///< damping mode: kd = damping_scale * nominal kd of the joint group, [0, 100]

  static const char* defaultsYaml();  ///< the `safety:` section
  void read(YamlReader& r);           ///< strict, finish() included
};

/// What the robot's drives accept.
struct JointLimits {
  std::vector<std::string> names;
  Eigen::VectorXd q_lo, q_hi;  ///< [rad] (-inf/+inf for continuous joints)
  Eigen::VectorXd tau_max;     ///< [N m] effort limits
};

enum class Verdict { kApplied, kMalformed, kNonFinite, kGains, kLimits, kStale };
const char* toString(Verdict v);

struct GuardCounters {
  std::uint64_t received = 0, applied = 0, rejected = 0;
  std::uint64_t malformed = 0, non_finite = 0, gains = 0, limits = 0, stale = 0;
  std::uint64_t clamped = 0;  ///< references clamped (q_ref into the limits, tau_ff to the effort limit)
};

class CommandGuard {
 public:
  CommandGuard(JointLimits limits, const SafetyConfig& config);

  /// Checks `msg` against the limits; `latest_state_ns` is the stamp of the newest state published. On
  /// kApplied, `out` (sized n) holds the command to apply and the session/seq/state stamp are remembered.
  Verdict check(const JointCommandMsg& msg, std::int64_t latest_state_ns, JointCommand& out) noexcept;
  const GuardCounters& counters() const { return counters_; }
  std::uint64_t lastAppliedSeq() const { return last_seq_; }
  std::int64_t lastAppliedStateStamp() const { return last_state_ns_; }

 private:
  Verdict inspect(const JointCommandMsg& msg, std::int64_t latest_state_ns) const noexcept;
  Verdict count(Verdict v) noexcept;

  JointLimits limits_;
  SafetyConfig config_;
  GuardCounters counters_;
  std::uint64_t session_ = 0, last_seq_ = 0;
  std::int64_t last_state_ns_ = -1;
  bool have_session_ = false;
};

}  // namespace centaur::middleware
