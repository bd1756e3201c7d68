#pragma once
// The Math of Tasks (after OpenSoT): a readable stack expression over shared task and constraint objects.
//
//   task % Rows{0, 1, 2}     sub-task: only these rows of the task (its weight restricted to them)
//   0.1 * task               the task's cost scaled by 0.1 inside its level (soft priority weight)
//   a + b                    soft priority: one level, the weighted sum of the costs
//   a / b                    hard priority: b is optimised without worsening a (a cascade of levels)
//   stack << constraint      the constraint holds at every level
//
//   auto stack = (feet / pelvis) / (ang_mom + 0.1 * posture) << joint_limits << velocity_limits;
//
// C++ precedence: % * / bind tighter than +, and << binds loosest, so write soft sums inside parentheses:
// `a / (b + c)`; `a / b + c` does not compile (there is no Stack + Level), which catches the mistake.
// (Braced lists cannot be an operand of %, hence `task % Rows{0, 1, 2}` rather than `task % {0, 1, 2}`.)
// Tasks are shared: the same task object may appear in several places; each is updated once per tick.
#include <memory>
#include <type_traits>
#include <vector>

#include "qp/constraint.hpp"
#include "qp/task.hpp"

namespace centaur {

using Rows = std::vector<int>;

/// One task (or a row subset of it) with a scale of its cost inside a level.
struct Term {
  TaskPtr task;
  Rows rows;           ///< selected rows of the task, empty = all rows
  double scale = 1.0;  ///< multiplies the task's weight inside the level

  Term() = default;
  template <class T, class = std::enable_if_t<std::is_base_of<Task, T>::value>>
  Term(std::shared_ptr<T> t) : task(std::move(t)) {}  // NOLINT: implicit by design (MoT expressions)
  int size() const { return rows.empty() ? task->rows() : static_cast<int>(rows.size()); }
  /// Row r of the term -> row of the task.
  int taskRow(int r) const { return rows.empty() ? r : rows[r]; }
};

/// Soft-priority aggregate: the costs of its terms are summed.
struct Level {
  std::vector<Term> terms;

  Level() = default;
  Level(Term t) { terms.push_back(std::move(t)); }  // NOLINT
  template <class T, class = std::enable_if_t<std::is_base_of<Task, T>::value>>
  Level(std::shared_ptr<T> t) : Level(Term(std::move(t))) {}  // NOLINT
  int size() const;
};

/// Hard-priority levels (index 0 = highest) plus the constraints imposed at every level.
struct Stack {
  std::vector<Level> levels;
  std::vector<ConstraintPtr> constraints;
  /// Damping eps ||x||^2 added to every level's cost (keeps each level's Hessian positive definite).
  double regularisation = 1e-6;

  Stack() = default;
  Stack(Level l) { levels.push_back(std::move(l)); }  // NOLINT
  Stack(Term t) : Stack(Level(std::move(t))) {}        // NOLINT
  template <class T, class = std::enable_if_t<std::is_base_of<Task, T>::value>>
  Stack(std::shared_ptr<T> t) : Stack(Level(Term(std::move(t)))) {}  // NOLINT
};

/// Sub-task: rows of a term (composes: selecting from an already selected term picks among its rows).
/// Throws std::out_of_range if a row is outside the term.
Term operator%(Term t, const Rows& rows);
template <class T, class = std::enable_if_t<std::is_base_of<Task, T>::value>>
Term operator%(std::shared_ptr<T> t, const Rows& rows) {
  return Term(std::move(t)) % rows;
}

/// Scale a term's cost inside its level (w >= 0; throws std::invalid_argument otherwise).
Term operator*(double w, Term t);
template <class T, class = std::enable_if_t<std::is_base_of<Task, T>::value>>
Term operator*(double w, std::shared_ptr<T> t) {
  return w * Term(std::move(t));
}

/// Soft priority.
Level operator+(Level a, const Level& b);
template <class T, class U, class = std::enable_if_t<std::is_base_of<Task, T>::value && std::is_base_of<Task, U>::value>>
Level operator+(std::shared_ptr<T> a, std::shared_ptr<U> b) {
  return Level(Term(std::move(a))) + Level(Term(std::move(b)));
}

/// Hard priority: the levels of b below those of a; constraints and regularisation are merged.
Stack operator/(Stack a, const Stack& b);
template <class T, class U, class = std::enable_if_t<std::is_base_of<Task, T>::value && std::is_base_of<Task, U>::value>>
Stack operator/(std::shared_ptr<T> a, std::shared_ptr<U> b) {
  return Stack(std::move(a)) / Stack(std::move(b));
}

/// Add a constraint to every level.
Stack operator<<(Stack s, ConstraintPtr c);
template <class C, class = std::enable_if_t<std::is_base_of<Constraint, C>::value>>
Stack operator<<(Stack s, std::shared_ptr<C> c) {
  return std::move(s) << ConstraintPtr(std::move(c));
}

}  // namespace centaur
