#include "data/solver_multipliers_io.hpp"

#include <string>

namespace centaur::data {
namespace {

constexpr hsize_t kMaxEntries = 10000000;  // bounds the memory a file can ask for

}  // namespace

void writeSolverMultipliers(const h5::Writer& w, hid_t knots, const Primitive& p) {
  const Eigen::Index m = p.mult_constraints.size(), n = p.mult_lower.size();
  if (m == 0 && n == 0 && p.mult_upper.size() == 0) return;
  if (m == 0 || n == 0 || p.mult_upper.size() != n) {
    w.fail("primitive '" + p.name + "': the solver multipliers need constraints, lower and upper bounds (" +
           std::to_string(m) + ", " + std::to_string(n) + ", " + std::to_string(p.mult_upper.size()) +
           " values; the bound vectors of equal length)");
  }
  h5::Id g(w.check(H5Gcreate2(knots, "multipliers", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   "group 'knots/multipliers'"),
           H5Gclose);
  w.doubles(g.get(), "constraints", {static_cast<hsize_t>(m)}, p.mult_constraints.data(),
            {"SI", nullptr, "constraint multipliers y of the solved OCP, one per constraint row (Lagrangian f + y^T g)"});
  w.doubles(g.get(), "lower_bounds", {static_cast<hsize_t>(n)}, p.mult_lower.data(),
            {"SI", nullptr, "lower-bound multipliers (>= 0), one per decision variable of the solved OCP"});
  w.doubles(g.get(), "upper_bounds", {static_cast<hsize_t>(n)}, p.mult_upper.data(),
            {"SI", nullptr, "upper-bound multipliers (>= 0), one per decision variable of the solved OCP"});
}

void readSolverMultipliers(const h5::Reader& r, hid_t knots, const std::string& key, Primitive& p) {
  if (!r.exists(knots, "multipliers")) return;
  const std::string k = key + "multipliers/";
  const h5::Id g = r.openGroup(knots, key + "multipliers", "multipliers");
  const hsize_t m = r.length(g.get(), k + "constraints", "constraints", 1, kMaxEntries);
  const hsize_t n = r.length(g.get(), k + "lower_bounds", "lower_bounds", 1, kMaxEntries);
  p.mult_constraints = r.vector(g.get(), k + "constraints", "constraints", m);
  p.mult_lower = r.vector(g.get(), k + "lower_bounds", "lower_bounds", n);
  p.mult_upper = r.vector(g.get(), k + "upper_bounds", "upper_bounds", n);
  r.requireFinite(k + "constraints", p.mult_constraints);
  for (const char* name : {"lower_bounds", "upper_bounds"}) {
    const Eigen::VectorXd& v = name[0] == 'l' ? p.mult_lower : p.mult_upper;
    r.requireFinite(k + name, v);
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (v[i] < 0.0) r.fail(k + name, "entry " + std::to_string(i) + " is negative (bound multipliers are >= 0)");
    }
  }
}

}  // namespace centaur::data
