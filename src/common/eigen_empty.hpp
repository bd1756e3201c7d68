#pragma once
// Eigen 3.4 operations that must be skipped when an operand is empty. Its triangular solves and triangular
// product updates take a reference to the first coefficient of the right-hand side or of the destination even
// when it has no rows or columns: a reference bound to a null pointer, undefined behaviour (UBSan reports it).
// Empty blocks are legitimate in our solvers: a stage without free controls, a QP without active rows.
namespace centaur {

/// tri.solveInPlace(rhs) unless rhs is empty; tri is a triangular view or a Cholesky factorisation.
template <class Triangular, class Rhs>
void solveInPlaceUnlessEmpty(const Triangular& tri, Rhs&& rhs) {
  if (rhs.size() > 0) tri.solveInPlace(rhs);
}

}  // namespace centaur
