#pragma once
// The runs of a sweep and what each one is: run index <-> (grid point, seed index, mode), its seeds and its
// perturbation sample, all derived from the spec alone, so every rank of an MPI job, every restart and a replay
// of one run agree.
//
// Order: run = (point * seeds + seed_index) * modes + mode (the modes of one perturbation sample are neighbours).
// Seeds: seed64 = mix(base seed, hash of the grid point's jump and parameters, seed index) - the same for every
//   mode (paired comparisons) and for the same parameters in another grid; sensors.seed = its top 31 bits.
// Sampling: every perturbed key draws from its own counter-based stream (splitmix64 of seed64 and the key), so
//   adding a key does not change the others' samples. uniform: lo + u (hi - lo), u in [0, 1) with 53 bits;
//   integer keys: every integer of [lo, hi] equally likely; normal: Box-Muller, then clipped if asked; choice: one
//   of the values, equally likely. Written with our own arithmetic (not <random>'s distributions, whose output
//   differs between standard libraries).
#include <cstdint>
#include <string>
#include <vector>

#include "sweep/sweep_spec.hpp"

namespace centaur::sweep {

struct RunId {
  std::size_t run = 0, point = 0, seed_index = 0, mode = 0;
};

RunId runId(const SweepSpec& spec, std::size_t run);

/// The 64-bit seed of (grid point, seed index).
std::uint64_t runSeed(const SweepSpec& spec, std::size_t point, std::size_t seed_index);
/// The simulator's noise seed of a run: the top 31 bits of its 64-bit seed.
std::int64_t sensorSeed(std::uint64_t seed64);

/// One sampled value vector per distribution of spec.perturb (in its order).
std::vector<std::vector<double>> samplePerturbation(const SweepSpec& spec, std::uint64_t seed64);

/// Column names of the sampled values: the key for a scalar, key[i] for the elements of a list key.
std::vector<std::string> perturbationColumns(const SweepSpec& spec);

/// The simulation overrides ("key=value") of a run: simulation.set, the sampled values, sensors.seed.
std::vector<std::string> runOverrides(const SweepSpec& spec, std::size_t point, std::size_t seed_index);

}  // namespace centaur::sweep
