#include "qp/stack.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace centaur {

int Level::size() const {
  int m = 0;
  for (const Term& t : terms) m += t.size();
  return m;
}

Term operator%(Term t, const Rows& rows) {
  if (!t.task) throw std::invalid_argument("sub-task of an empty term");
  if (rows.empty()) throw std::out_of_range("task '" + t.task->name() + "': empty row selection");
  Rows selected;
  selected.reserve(rows.size());
  for (int r : rows) {
    if (r < 0 || r >= t.size())
      throw std::out_of_range("task '" + t.task->name() + "': row " + std::to_string(r) + " outside [0, " +
                              std::to_string(t.size() - 1) + "]");
    selected.push_back(t.taskRow(r));
  }
  t.rows = std::move(selected);
  return t;
}

Term operator*(double w, Term t) {
  if (!(w >= 0.0) || !std::isfinite(w)) throw std::invalid_argument("term weight must be >= 0");
  t.scale *= w;
  return t;
}

Level operator+(Level a, const Level& b) {
  a.terms.insert(a.terms.end(), b.terms.begin(), b.terms.end());
  return a;
}

Stack operator/(Stack a, const Stack& b) {
  a.levels.insert(a.levels.end(), b.levels.begin(), b.levels.end());
  for (const ConstraintPtr& c : b.constraints)
    if (std::find(a.constraints.begin(), a.constraints.end(), c) == a.constraints.end()) a.constraints.push_back(c);
  a.regularisation = std::max(a.regularisation, b.regularisation);
  return a;
}

Stack operator<<(Stack s, ConstraintPtr c) {
  if (!c) throw std::invalid_argument("null constraint");
  if (std::find(s.constraints.begin(), s.constraints.end(), c) == s.constraints.end()) s.constraints.push_back(c);
  return s;
}

}  // namespace centaur
