#pragma once
// Element functions: small smooth vector functions of a few scalar inputs, the building blocks of every
// constraint and cost of an OCP (partially separable structure, as in LANCELOT/ifopt: derivatives stay small).
// AdElement<Derived, NI, NO, NN> turns one templated `compute(const S* in, S* out)` into exact values, Jacobians
// (forward AD, Eigen's AutoDiffScalar with fixed sizes, no heap allocation) and weighted Hessians
// (forward-over-reverse AD on a small thread-local tape, reverse_ad.hpp; the tape's buffers grow once and are
// reused). evalHessianForward() keeps the nested forward-over-forward AutoDiffScalar Hessian as a cross-check. NN <= NI: only the FIRST NN inputs may appear nonlinearly; the remaining NI - NN inputs
// must enter linearly and never multiply each other (e.g. forces and accelerations in the inverse dynamics),
// so their Hessian block is zero and the outer AD level runs over NN directions only. The finite-difference
// tests of every element check this declaration too.
#include <unsupported/Eigen/AutoDiff>

#include "planner/reverse_ad.hpp"

#include <Eigen/Core>
#include <string>

namespace centaur::planner {

class Element {
 public:
  virtual ~Element() = default;
  virtual int numInputs() const = 0;
  virtual int numOutputs() const = 0;
  virtual const char* name() const = 0;
  /// out: numOutputs values.
  virtual void eval(const double* in, double* out) const = 0;
  /// out: values; jac: numOutputs x numInputs, row-major.
  virtual void evalJacobian(const double* in, double* out, double* jac) const = 0;
  /// hess: numInputs x numInputs (full, symmetric, row-major) of sum_j w[j] out[j].
  virtual void evalHessian(const double* in, const double* w, double* hess) const = 0;
  /// evalJacobian and evalHessian at one point, sharing what they can (the same exact derivatives; the Jacobian
  /// may round differently from evalJacobian's in the last bits).
  virtual void evalJacobianHessian(const double* in, const double* w, double* out, double* jac, double* hess) const {
    evalJacobian(in, out, jac);
    evalHessian(in, w, hess);
  }
  /// Declarations an element may make (the finite-difference tests check them): its Jacobian does not depend on
  /// the inputs (a linear function), or its Hessian does not (a quadratic). The Ocp then evaluates it once.
  virtual bool jacobianIsConstant() const { return false; }
  virtual bool hessianIsConstant() const { return false; }
};

template <class Derived, int NI, int NO, int NN = NI>
class AdElement : public Element {
  static_assert(NN >= 1 && NN <= NI, "NN nonlinear inputs must be a prefix of the NI inputs");

 public:
  static constexpr int kInputs = NI;
  static constexpr int kOutputs = NO;
  using D1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, NI, 1>>;
  using D2 = Eigen::AutoDiffScalar<Eigen::Matrix<D1, NN, 1>>;

  int numInputs() const override { return NI; }
  int numOutputs() const override { return NO; }

  void eval(const double* in, double* out) const override { derived().compute(in, out); }

  void evalJacobian(const double* in, double* out, double* jac) const override {
    D1 x[NI];
    for (int i = 0; i < NI; ++i) x[i] = D1(in[i], NI, i);
    D1 y[NO];
    derived().compute(x, y);
    for (int j = 0; j < NO; ++j) {
      out[j] = y[j].value();
      for (int i = 0; i < NI; ++i) jac[j * NI + i] = y[j].derivatives()[i];
    }
  }

  void evalHessian(const double* in, const double* w, double* hess) const override {
    rad::TapeVar y[NO];
    rad::record<Derived, NI, NO>(derived(), in, y);
    rad::hessianFromTape<NI, NN>(y, NO, w, hess);
  }

  /// One recording on the tape for both: its forward sweep carries all NI directions and gives the Jacobian
  /// (instead of a second evaluation with NI-wide forward AD), the reverse sweep the Hessian as evalHessian's.
  void evalJacobianHessian(const double* in, const double* w, double* out, double* jac, double* hess) const override {
    rad::TapeVar y[NO];
    rad::record<Derived, NI, NO>(derived(), in, y);
    for (int j = 0; j < NO; ++j) out[j] = y[j].value();
    rad::hessianFromTape<NI, NN>(y, NO, w, hess, jac);
  }

  /// The same weighted Hessian by nested forward AD (slower; for tests and benchmarks).
  void evalHessianForward(const double* in, const double* w, double* hess) const {
    D2 x[NI];
    for (int i = 0; i < NI; ++i) {
      x[i].value() = D1(in[i], NI, i);
      for (int k = 0; k < NN; ++k) x[i].derivatives()[k] = D1(k == i ? 1.0 : 0.0);
    }
    D2 y[NO];
    derived().compute(x, y);
    for (int i = 0; i < NI * NI; ++i) hess[i] = 0.0;
    for (int j = 0; j < NO; ++j) {
      if (w[j] == 0.0) continue;
      for (int a = 0; a < NN; ++a) {
        const auto& da = y[j].derivatives()[a].derivatives();
        for (int b = 0; b < NI; ++b) {
          hess[a * NI + b] += w[j] * da[b];
          if (b >= NN) hess[b * NI + a] += w[j] * da[b];  // symmetric partner in the (linear, nonlinear) block
        }
      }
    }
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
};

}  // namespace centaur::planner
