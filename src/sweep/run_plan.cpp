#include "sweep/run_plan.hpp"

#include <algorithm>
#include <cmath>

#include "common/number_text.hpp"
#include "sweep/spec_check.hpp"
#include "sweep/yaml_values.hpp"

namespace centaur::sweep {

namespace {

constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

/// splitmix64's output function.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// A counter-based stream of uniform doubles in [0, 1).
class Stream {
 public:
  explicit Stream(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    state_ += kGolden;
    return static_cast<double>(mix(state_) >> 11) * 0x1.0p-53;
  }
  double normal() {  // Box-Muller
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::uint64_t state_;
};

std::string pointKey(const SweepSpec& spec, std::size_t point) {
  std::string key = pointJump(spec, point);
  const std::vector<data::GridValue> values = pointValues(spec, point);
  for (std::size_t a = 0; a < spec.axes.size(); ++a) key += "|" + spec.axes[a].key + "=" + values[a].yaml();
  return key;
}

std::vector<double> draw(const Distribution& d, Stream& s) {
  std::vector<double> v(static_cast<std::size_t>(d.size), 0.0);
  if (d.kind == Distribution::Kind::kChoice) {
    const auto n = static_cast<double>(d.choices.size());
    const auto i = std::min(d.choices.size() - 1, static_cast<std::size_t>(std::floor(s.uniform() * n)));
    return d.choices[i];
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (d.kind == Distribution::Kind::kUniform) {
      if (d.integer) {
        const double k = std::floor(s.uniform() * (d.b[i] - d.a[i] + 1.0));
        v[i] = std::min(d.b[i], d.a[i] + k);
      } else {
        v[i] = d.a[i] + s.uniform() * (d.b[i] - d.a[i]);
      }
    } else {
      v[i] = d.a[i] + d.b[i] * s.normal();
      if (!d.clip_lo.empty()) v[i] = std::clamp(v[i], d.clip_lo[i], d.clip_hi[i]);
      if (d.integer) v[i] = std::round(v[i]);
    }
  }
  return v;
}

}  // namespace

RunId runId(const SweepSpec& spec, std::size_t run) {
  RunId id;
  id.run = run;
  id.mode = run % spec.modes.size();
  const std::size_t sample = run / spec.modes.size();
  id.seed_index = sample % static_cast<std::size_t>(spec.seeds);
  id.point = sample / static_cast<std::size_t>(spec.seeds);
  return id;
}

std::uint64_t runSeed(const SweepSpec& spec, std::size_t point, std::size_t seed_index) {
  std::uint64_t h = mix(static_cast<std::uint64_t>(spec.seed) + kGolden);
  h = mix(h ^ fnv1a(pointKey(spec, point)));
  return mix(h ^ (static_cast<std::uint64_t>(seed_index) * kGolden + 1));
}

std::int64_t sensorSeed(std::uint64_t seed64) { return static_cast<std::int64_t>(seed64 >> 33); }

std::vector<std::vector<double>> samplePerturbation(const SweepSpec& spec, std::uint64_t seed64) {
  std::vector<std::vector<double>> out;
  for (const Distribution& d : spec.perturb) {
    Stream s(mix(seed64 ^ fnv1a(d.key)));
    out.push_back(draw(d, s));
  }
  return out;
}

std::vector<std::string> perturbationColumns(const SweepSpec& spec) {
  std::vector<std::string> out;
  for (const Distribution& d : spec.perturb) {
    if (d.size == 1) {
      out.push_back(d.key);
    } else {
      for (int i = 0; i < d.size; ++i) out.push_back(d.key + "[" + std::to_string(i) + "]");
    }
  }
  return out;
}

std::vector<std::string> runOverrides(const SweepSpec& spec, std::size_t point, std::size_t seed_index) {
  std::vector<std::string> out;
  for (const auto& [k, v] : spec.simulation_set) out.push_back(k + "=" + v);
  const std::uint64_t seed64 = runSeed(spec, point, seed_index);
  const std::vector<std::vector<double>> sample = samplePerturbation(spec, seed64);
  for (std::size_t i = 0; i < spec.perturb.size(); ++i) out.push_back(spec.perturb[i].key + "=" + numbersText(sample[i]));
  out.push_back("sensors.seed=" + std::to_string(sensorSeed(seed64)));
  return out;
}

}  // namespace centaur::sweep
