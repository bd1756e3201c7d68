#pragma once
// The optional group `knots/multipliers` of a primitive: the solver's constraint and bound multipliers at the
// knots' solution (docs/primitive-format.md), which lets a neighbour's plan start primal-dual.
#include <hdf5.h>

#include <string>

#include "data/hdf5.hpp"
#include "data/primitive.hpp"

namespace centaur::data {

/// Writes `knots/multipliers` into the open `knots` group when the primitive holds multipliers; RuntimeError
/// (through the writer) if only some of them are set or the two bound vectors differ in length.
void writeSolverMultipliers(const h5::Writer& w, hid_t knots, const Primitive& p);

/// Reads `knots/multipliers` if present (else leaves the vectors empty); InputError naming the dataset if it
/// is incomplete, too long, not finite, or has a negative bound multiplier. `key` is the knots group's key
/// (e.g. "squat-jump/knots/").
void readSolverMultipliers(const h5::Reader& r, hid_t knots, const std::string& key, Primitive& p);

}  // namespace centaur::data
