#pragma once
// centaur bench planner: the jump OCPs with both backends (solver.backend ipopt and riccati), in one run.
//   - benchPrimitive: cold solves from the default guess, the backends interleaved run by run;
//   - benchWarmReplan: re-plans of neighbouring problems (squat jump: target height 0.82 / 0.92 m; half-squat
//     jump: wall at 0.12 / 0.18 m) warm-started from the knots of the default plan of the same backend
//     (`centaur plan ... --warm-start`), interleaved the same way.
// `sets`: KEY=VALUE overrides of the embedded defaults (as `centaur plan --set`) for every solve; a neighbour's own
// override comes after them.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace centaur::cli {

/// Throws InputError (naming the key and its range) if `sets` does not apply to both jumps.
void checkPlannerOverrides(const std::vector<std::string>& sets);
nlohmann::json benchPrimitive(const std::string& primitive, int repeat, const std::vector<std::string>& sets = {});
nlohmann::json benchWarmReplan(const std::string& primitive, int repeat, const std::vector<std::string>& sets = {});

}  // namespace centaur::cli
