#include "middleware/command_guard.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"

namespace centaur::middleware {

const char* SafetyConfig::defaultsYaml() {
  return R"(safety:                      # the robot side's checks of every command (docs/middleware.md)
  watchdog_timeout: 0.005     # [s] robot time without a valid command -> damping mode (realtime), [0.001, 10]
  max_kp: 5000.0              # [N m/rad] stiffness above it is rejected, [0, 1e6]
  max_kd: 500.0               # [N m s/rad] damping above it is rejected, [0, 1e5]
  q_ref_tolerance: 0.05       # [rad] q_ref up to this far beyond a limit is clamped, further is rejected, [0, 1]
  max_velocity: 100.0         # [rad/s] |qd_ref| above it is rejected, [0, 1e4]
  damping_scale: 3.0          # damping mode: kd = damping_scale x the joint group's nominal kd, kp = 0, [0, 100]
)";
}

void SafetyConfig::read(YamlReader& r) {
  r.get("watchdog_timeout", watchdog_timeout, 0.001, 10.0);
  r.get("max_kp", max_kp, 0.0, 1e6);
  r.get("max_kd", max_kd, 0.0, 1e5);
  r.get("q_ref_tolerance", q_ref_tolerance, 0.0, 1.0);
  r.get("max_velocity", max_velocity, 0.0, 1e4);
  r.get("damping_scale", damping_scale, 0.0, 100.0);
  r.finish();
}

const char* toString(Verdict v) {
  switch (v) {
    case Verdict::kApplied: return "applied";
    case Verdict::kMalformed: return "malformed";
    case Verdict::kNonFinite: return "non_finite";
    case Verdict::kGains: return "gains";
    case Verdict::kLimits: return "limits";
    case Verdict::kStale: return "stale";
  }
  return "unknown";
}

CommandGuard::CommandGuard(JointLimits limits, const SafetyConfig& config)
    : limits_(std::move(limits)), config_(config) {
  const auto n = static_cast<Eigen::Index>(limits_.names.size());
  if (limits_.q_lo.size() != n || limits_.q_hi.size() != n || limits_.tau_max.size() != n) {
    throw InputError("command guard: joint limits of " + std::to_string(n) + " joints are inconsistent");
  }
}

namespace {
bool finite(const dds_sequence_double& s) {
  for (std::uint32_t i = 0; i < s._length; ++i) {
    if (!std::isfinite(s._buffer[i])) return false;
  }
  return true;
}
}  // namespace

Verdict CommandGuard::inspect(const JointCommandMsg& m, std::int64_t latest_state_ns) const noexcept {
  const std::uint32_t n = static_cast<std::uint32_t>(limits_.names.size());
  if (m.name._length != n || m.q_ref._length != n || m.qd_ref._length != n || m.tau_ff._length != n ||
      m.kp._length != n || m.kd._length != n) {
    return Verdict::kMalformed;
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (m.name._buffer[i] == nullptr || limits_.names[i] != m.name._buffer[i]) return Verdict::kMalformed;
  }
  if (!finite(m.q_ref) || !finite(m.qd_ref) || !finite(m.tau_ff) || !finite(m.kp) || !finite(m.kd)) {
    return Verdict::kNonFinite;
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const double kp = m.kp._buffer[i], kd = m.kd._buffer[i];
    if (kp < 0.0 || kp > config_.max_kp || kd < 0.0 || kd > config_.max_kd) return Verdict::kGains;
    const auto k = static_cast<Eigen::Index>(i);
    const double q = m.q_ref._buffer[i];
    if (q < limits_.q_lo[k] - config_.q_ref_tolerance || q > limits_.q_hi[k] + config_.q_ref_tolerance ||
        std::abs(m.qd_ref._buffer[i]) > config_.max_velocity) {
      return Verdict::kLimits;
    }
  }
  const std::int64_t state_ns = nanosecondsFromTime(m.state_stamp);
  if (state_ns < 0 || state_ns > latest_state_ns || state_ns < last_state_ns_) return Verdict::kStale;
  if (have_session_ && m.session == session_ && m.seq <= last_seq_) return Verdict::kStale;
  return Verdict::kApplied;
}

Verdict CommandGuard::count(Verdict v) noexcept {
  switch (v) {
    case Verdict::kApplied: ++counters_.applied; return v;
    case Verdict::kMalformed: ++counters_.malformed; break;
    case Verdict::kNonFinite: ++counters_.non_finite; break;
    case Verdict::kGains: ++counters_.gains; break;
    case Verdict::kLimits: ++counters_.limits; break;
    case Verdict::kStale: ++counters_.stale; break;
  }
  ++counters_.rejected;
  return v;
}

Verdict CommandGuard::check(const JointCommandMsg& m, std::int64_t latest_state_ns, JointCommand& out) noexcept {
  ++counters_.received;
  const Verdict v = inspect(m, latest_state_ns);
  if (v != Verdict::kApplied) return count(v);
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(limits_.names.size()); ++k) {
    const auto i = static_cast<std::uint32_t>(k);
    const double q = m.q_ref._buffer[i];
    const double q_clamped = std::clamp(q, limits_.q_lo[k], limits_.q_hi[k]);
    const double tau = m.tau_ff._buffer[i];
    const double tau_max = limits_.tau_max[k] > 0.0 ? limits_.tau_max[k] : INFINITY;  // 0: not limited
    const double tau_clamped = std::clamp(tau, -tau_max, tau_max);
    if (q_clamped != q) ++counters_.clamped;
    if (tau_clamped != tau) ++counters_.clamped;
    out.q_ref[k] = q_clamped;
    out.qd_ref[k] = m.qd_ref._buffer[i];
    out.tau_ff[k] = tau_clamped;
    out.kp[k] = m.kp._buffer[i];
    out.kd[k] = m.kd._buffer[i];
  }
  have_session_ = true;
  session_ = m.session;
  last_seq_ = m.seq;
  last_state_ns_ = nanosecondsFromTime(m.state_stamp);
  return count(Verdict::kApplied);
}

}  // namespace centaur::middleware
