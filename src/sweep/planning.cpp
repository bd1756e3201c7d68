#include "sweep/planning.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "common/error.hpp"
#include "data/arm_trajectory_io.hpp"
#include "data/primitive_io.hpp"
#include "planner/arm_flywheel_problem.hpp"
#include "planner/jump_problem.hpp"
#include "sweep/spec_check.hpp"

namespace centaur::sweep {

namespace fs = std::filesystem;

namespace {

std::string groupName(const std::string& jump, std::size_t point, std::size_t points) {
  const std::size_t width = std::max<std::size_t>(4, std::to_string(points - 1).size());
  std::string digits = std::to_string(point);
  return jump + "-" + std::string(width - std::min(width, digits.size()), '0') + digits;
}

bool sameGrid(const data::DatabaseIndex& a, const data::DatabaseIndex& b) {
  if (a.axes != b.axes || a.numeric != b.numeric || a.points.size() != b.points.size()) return false;
  for (std::size_t p = 0; p < a.points.size(); ++p) {
    const data::GridEntry &x = a.points[p], &y = b.points[p];
    if (x.point != y.point || x.group != y.group || x.jump != y.jump || x.values.size() != y.values.size()) return false;
    for (std::size_t v = 0; v < x.values.size(); ++v) {
      if (x.values[v].yaml() != y.values[v].yaml()) return false;
    }
  }
  return true;
}

std::string describe(const data::DatabaseIndex& index, const data::GridEntry& e) {
  std::string s;
  for (std::size_t a = 0; a < index.axes.size(); ++a) s += (s.empty() ? "" : ", ") + index.axes[a] + "=" + e.values[a].yaml();
  return s.empty() ? std::string("defaults") : s;
}

/// Plans grid point `e` into `file`; returns how its solve ended (status, backend, ...).
data::SolveInfo planPoint(const SweepSpec& spec, const data::DatabaseIndex& index, const data::GridEntry& e,
                          const std::string& file) {
  const planner::JumpConfig cfg =
      planner::loadJumpConfig(e.jump, "", plannerOverrides(spec, static_cast<std::size_t>(e.point)));
  const planner::JumpProblem problem(cfg);
  const planner::SolveResult result = problem.solve(false);
  data::Primitive prim = problem.toPrimitive(result);
  prim.name = e.group;
  data::gridAttributes(index, e, prim);
  data::writePrimitive(file, prim, data::WriteMode::Replace);
  return result.info;
}

}  // namespace

data::DatabaseIndex gridIndex(const SweepSpec& spec) {
  data::DatabaseIndex index;
  for (const Axis& a : spec.axes) {
    index.axes.push_back(a.key);
    index.numeric.push_back(a.numeric());
  }
  for (std::size_t p = 0; p < spec.points(); ++p) {
    data::GridEntry e;
    e.point = static_cast<int>(p);
    e.jump = pointJump(spec, p);
    e.group = groupName(e.jump, p, spec.points());
    e.solve_status = "not_run";
    e.values = pointValues(spec, p);
    index.points.push_back(std::move(e));
  }
  return index;
}

data::DatabaseIndex planDatabase(const SweepSpec& spec, const SweepDir& dir) {
  data::DatabaseIndex index = gridIndex(spec);
  const std::string db = dir.path("primitives.h5");
  std::error_code ec;
  if (fs::exists(db, ec)) {
    try {
      const data::DatabaseIndex old = data::readDatabaseIndex(db);
      if (sameGrid(old, index)) return old;
    } catch (const InputError&) {
      // unreadable: planned again below
    }
  }
  const fs::path plans = dir.path("plans");
  fs::create_directories(plans, ec);
  if (ec) throw RuntimeError("cannot create " + plans.string() + ": " + ec.message());
  std::vector<std::string> sources;
  for (data::GridEntry& e : index.points) {
    const std::string file = (plans / (e.group + ".h5")).string();
    const auto t0 = std::chrono::steady_clock::now();
    bool reused = false;
    data::SolveInfo solve;
    if (fs::exists(file, ec)) {
      try {
        solve = data::readPrimitive(file, e.group).solve;
        reused = true;
      } catch (const InputError&) {
        // a partial or foreign file: plan the point again
      }
    }
    if (!reused) solve = planPoint(spec, index, e, file);
    e.solve_status = solve.status;
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The backend, when recorded: with solver.backend auto it says where Ipopt took over.
    const std::string by = solve.backend.empty() ? "" : " by " + solve.backend;
    std::fprintf(stderr, "sweep: [%d/%zu] %s %s (%s): %s%s%s, %.1f s\n", e.point + 1, index.points.size(),
                 reused ? "kept" : "planned", e.group.c_str(), describe(index, e).c_str(), e.solve_status.c_str(),
                 by.c_str(), e.solve_status == "solved" ? "" : " (its runs are recorded as not_planned)", dt);
    sources.push_back(file);
  }
  data::writeDatabase(db, index, sources, spec.canonicalYaml());
  fs::remove_all(plans, ec);
  return index;
}

std::string planFlywheel(const SweepDir& dir) {
  const std::string path = dir.path("arm-flywheel.h5");
  std::error_code ec;
  if (fs::exists(path, ec)) {
    try {
      data::readArmTrajectory(path);
      return path;
    } catch (const InputError&) {
      // planned again
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const planner::ArmFlywheelProblem problem(planner::loadArmFlywheelConfig("", {}));
  const planner::SolveResult result = problem.solve(false);
  data::writeArmTrajectory(path, problem.toTrajectory(result), false);
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "sweep: planned arm-flywheel (mode ocp): %s, %.1f s%s\n", result.info.status.c_str(), dt,
               result.info.solved() ? "" : " (used as it is)");
  return path;
}

}  // namespace centaur::sweep
