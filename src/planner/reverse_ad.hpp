#pragma once
// Second-order AD for small fixed-size element functions: forward-over-reverse on a tiny tape.
//
// `TapeVar` is a scalar that records every elementary operation (value, first and second partials w.r.t. its
// one or two operands) on a thread-local tape while the templated element code runs with doubles underneath.
// The weighted Hessian sum_j w_j d^2 out_j / dx^2 then needs two sweeps over the tape:
//   1. forward: tangents dot_v (NN directions = the nonlinear inputs) of every node;
//   2. reverse: adjoints bar_v (scalar) and their directional derivatives bardot_v (NN) seeded with w;
// bardot of input b is row b of the Hessian restricted to the NN nonlinear columns (all rows at once).
// Cost ~ (2 NN + small) flops per tape node, instead of ~ NI * NN per operation with nested forward AD.
// Constants never enter the tape; nodes that do not depend on a nonlinear input carry no tangent.
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace centaur::planner::rad {

/// One tape node v = f(a, b) (b < 0: unary; a < 0 as well: an independent input).
struct TapeNode {
  int a, b;
  double da, db;          // df/da, df/db
  double daa, dab, dbb;   // second partials
  bool curved;            // any second partial nonzero
};

class Tape {
 public:
  /// Append a node; returns its index. Inline and without a call on the common path: recording is a large part
  /// of an element's Hessian (every elementary operation pushes one node).
  int push(double /*v*/, int a, double da, int b, double db, double daa, double dab, double dbb, bool curved) {
    if (next_ == limit_) grow();
    *next_ = TapeNode{a, b, da, db, daa, dab, dbb, curved};
    return static_cast<int>(next_++ - storage_.data());
  }
  void clear() { next_ = storage_.data(); }
  int size() const { return static_cast<int>(next_ - storage_.data()); }
  const TapeNode* nodes() const { return storage_.data(); }

 private:
  // Doubles the storage (keeping the nodes); the buffers grow once to the largest tape and are reused.
  void grow() {
    const std::size_t n = next_ - storage_.data();
    storage_.resize(std::max<std::size_t>(256, 2 * storage_.size()));
    next_ = storage_.data() + n;
    limit_ = storage_.data() + storage_.size();
  }
  std::vector<TapeNode> storage_;  // the values live in the TapeVars; the sweeps need the partials only
  TapeNode* next_ = nullptr;       // first free node
  TapeNode* limit_ = nullptr;      // end of the storage
};

/// The tape all TapeVar operations record on (one per thread).
inline Tape& activeTape() {
  thread_local Tape tape;
  return tape;
}

/// A recorded scalar: its value and its tape index (-1: a constant, not recorded).
struct TapeVar {
  double v = 0.0;
  int i = -1;
  TapeVar() = default;
  TapeVar(double x) : v(x), i(-1) {}  // NOLINT: implicit, so that S(2.0) and Eigen's casts work
  TapeVar(double x, int idx) : v(x), i(idx) {}
  double value() const { return v; }

  TapeVar& operator+=(const TapeVar& o) { return *this = *this + o; }
  TapeVar& operator-=(const TapeVar& o) { return *this = *this - o; }
  TapeVar& operator*=(const TapeVar& o) { return *this = *this * o; }
  TapeVar& operator/=(const TapeVar& o) { return *this = *this / o; }

  // A constant that is exactly zero records nothing: 0 * x is the constant 0 (its node would only add exact zeros),
  // and x + 0, x - 0 and 0 + x are x's node (the value differs from x at most in the sign of a zero; a node would
  // pass x's tangent and adjoint on unchanged, so only the order in which x's adjoint sums its parts can change).
  friend TapeVar operator+(const TapeVar& x, const TapeVar& y) {
    const double r = x.v + y.v;
    if (x.i < 0 && y.i < 0) return TapeVar(r);
    if (y.i < 0) return TapeVar(r, y.v == 0.0 ? x.i : activeTape().push(r, x.i, 1.0, -1, 0.0, 0, 0, 0, false));
    if (x.i < 0) return TapeVar(r, x.v == 0.0 ? y.i : activeTape().push(r, y.i, 1.0, -1, 0.0, 0, 0, 0, false));
    return TapeVar(r, activeTape().push(r, x.i, 1.0, y.i, 1.0, 0, 0, 0, false));
  }
  friend TapeVar operator-(const TapeVar& x, const TapeVar& y) {
    const double r = x.v - y.v;
    if (x.i < 0 && y.i < 0) return TapeVar(r);
    if (y.i < 0) return TapeVar(r, y.v == 0.0 ? x.i : activeTape().push(r, x.i, 1.0, -1, 0.0, 0, 0, 0, false));
    if (x.i < 0) return TapeVar(r, activeTape().push(r, y.i, -1.0, -1, 0.0, 0, 0, 0, false));
    return TapeVar(r, activeTape().push(r, x.i, 1.0, y.i, -1.0, 0, 0, 0, false));
  }
  friend TapeVar operator-(const TapeVar& x) {
    if (x.i < 0) return TapeVar(-x.v);
    return TapeVar(-x.v, activeTape().push(-x.v, x.i, -1.0, -1, 0.0, 0, 0, 0, false));
  }
  friend TapeVar operator+(const TapeVar& x) { return x; }
  friend TapeVar operator*(const TapeVar& x, const TapeVar& y) {
    const double r = x.v * y.v;
    if (x.i < 0 && y.i < 0) return TapeVar(r);
    if (y.i < 0) return y.v == 0.0 ? TapeVar(r) : TapeVar(r, activeTape().push(r, x.i, y.v, -1, 0.0, 0, 0, 0, false));
    if (x.i < 0) return x.v == 0.0 ? TapeVar(r) : TapeVar(r, activeTape().push(r, y.i, x.v, -1, 0.0, 0, 0, 0, false));
    if (x.i == y.i) return TapeVar(r, activeTape().push(r, x.i, 2.0 * x.v, -1, 0.0, 2.0, 0, 0, true));
    return TapeVar(r, activeTape().push(r, x.i, y.v, y.i, x.v, 0.0, 1.0, 0.0, true));
  }
  friend TapeVar operator/(const TapeVar& x, const TapeVar& y) {
    const double r = x.v / y.v;
    if (x.i < 0 && y.i < 0) return TapeVar(r);
    const double iy = 1.0 / y.v;
    if (y.i < 0) return TapeVar(r, activeTape().push(r, x.i, iy, -1, 0.0, 0, 0, 0, false));
    // d(x/y)/dy = -x/y^2, d2/dy2 = 2x/y^3, d2/dxdy = -1/y^2
    if (x.i < 0) return TapeVar(r, activeTape().push(r, y.i, -r * iy, -1, 0.0, 2.0 * r * iy * iy, 0, 0, true));
    if (x.i == y.i) return TapeVar(r);  // x / x == 1 (constant)
    return TapeVar(r, activeTape().push(r, x.i, iy, y.i, -r * iy, 0.0, -iy * iy, 2.0 * r * iy * iy, true));
  }
  friend TapeVar sqrt(const TapeVar& x) {
    const double r = std::sqrt(x.v);
    if (x.i < 0) return TapeVar(r);
    const double d = 0.5 / r;
    return TapeVar(r, activeTape().push(r, x.i, d, -1, 0.0, -0.5 * d / x.v, 0, 0, true));
  }
  friend TapeVar sin(const TapeVar& x) {
    const double s = std::sin(x.v), c = std::cos(x.v);
    if (x.i < 0) return TapeVar(s);
    return TapeVar(s, activeTape().push(s, x.i, c, -1, 0.0, -s, 0, 0, true));
  }
  friend TapeVar cos(const TapeVar& x) {
    const double s = std::sin(x.v), c = std::cos(x.v);
    if (x.i < 0) return TapeVar(c);
    return TapeVar(c, activeTape().push(c, x.i, -s, -1, 0.0, -c, 0, 0, true));
  }
  friend bool operator<(const TapeVar& x, const TapeVar& y) { return x.v < y.v; }
  friend bool operator>(const TapeVar& x, const TapeVar& y) { return x.v > y.v; }
  friend bool operator<=(const TapeVar& x, const TapeVar& y) { return x.v <= y.v; }
  friend bool operator>=(const TapeVar& x, const TapeVar& y) { return x.v >= y.v; }
  friend bool operator==(const TapeVar& x, const TapeVar& y) { return x.v == y.v; }
  friend bool operator!=(const TapeVar& x, const TapeVar& y) { return x.v != y.v; }
};

/// Scratch for the sweeps (one per thread, grows to the largest tape seen, never shrinks).
struct SweepScratch {
  std::vector<double> dot, bar, bardot;
  std::vector<char> active, hasbardot;
};
inline SweepScratch& sweepScratch() {
  thread_local SweepScratch s;
  return s;
}

/// Record f (Derived::compute) at `in` on the active tape. Inputs are tape nodes 0..NI-1. Returns via `y`.
template <class F, int NI, int NO>
void record(const F& f, const double* in, TapeVar* y) {
  Tape& tape = activeTape();
  tape.clear();
  TapeVar x[NI];
  for (int k = 0; k < NI; ++k) x[k] = TapeVar(in[k], tape.push(in[k], -1, 0.0, -1, 0.0, 0, 0, 0, false));
  f.compute(x, y);
}

namespace detail {
// Node flags of the forward sweep: depends on a nonlinear input (the Hessian's directions); on any input of the
// forward sweep's directions.
constexpr char kNonlinear = 1, kTangent = 2;

/// Forward: every node's tangent in ND >= NN input directions (the first NN are the nonlinear inputs, ND == NI
/// covers them all), dot[v * ND + i], and its flags. A node's first NN components are the same sums whatever ND is.
template <int NI, int ND, int NN>
void forwardSweep(const TapeNode* nodes, int n, double* dot, char* active) {
  using VecD = Eigen::Matrix<double, ND, 1>;
  using MapD = Eigen::Map<VecD>;
  for (int v = 0; v < NI; ++v) {
    active[v] = static_cast<char>((v < NN ? kNonlinear : 0) | (v < ND ? kTangent : 0));
    if (v < ND) MapD(dot + v * ND) = VecD::Unit(v);
  }
  for (int v = NI; v < n; ++v) {
    const TapeNode& t = nodes[v];
    const char fa = active[t.a], fb = t.b >= 0 ? active[t.b] : 0;
    active[v] = static_cast<char>(fa | fb);
    const bool aa = fa & kTangent, ab = fb & kTangent;
    if (!aa && !ab) continue;
    MapD d(dot + v * ND);
    if (aa && ab) {
      d = t.da * MapD(dot + t.a * ND) + t.db * MapD(dot + t.b * ND);
    } else if (aa) {
      d = t.da * MapD(dot + t.a * ND);
    } else {
      d = t.db * MapD(dot + t.b * ND);
    }
  }
}

/// Reverse: adjoints bar (seeded with w at the outputs) and their tangents bardot in the NN nonlinear directions.
template <int NI, int ND, int NN>
void reverseSweep(const TapeVar* y, int no, const double* w, const TapeNode* nodes, int n, const double* dot,
                  const char* active, double* bar, double* bardot, char* hasbd) {
  for (int v = 0; v < n; ++v) {
    bar[v] = 0.0;
    hasbd[v] = 0;
  }
  for (int j = 0; j < no; ++j)
    if (y[j].i >= 0) bar[y[j].i] += w[j];
  for (int v = n - 1; v >= NI; --v) {
    const TapeNode& t = nodes[v];
    const double bv = bar[v];
    const bool bd = hasbd[v];
    if (bv == 0.0 && !bd) continue;
    // Operand p of node v: bar_p += dp bar_v; bardot_p += dp bardot_v + bar_v (d2v/dp da) dot_a + ... (b). The
    // terms are added in this order; a node's first contribution is assigned (0 + x == x), not added to zeros.
    auto addTo = [&](int p, double dp, double dpa, double dpb) __attribute__((always_inline)) {
      bar[p] += dp * bv;
      const bool sa = t.curved && bv != 0.0 && dpa != 0.0 && (active[t.a] & kNonlinear);
      const bool sb = t.curved && bv != 0.0 && t.b >= 0 && dpb != 0.0 && (active[t.b] & kNonlinear);
      if (!bd && !sa && !sb) return;
      double* out = bardot + p * NN;
      bool first = !hasbd[p];
      hasbd[p] = 1;
      auto add = [&](double c, const double* x) __attribute__((always_inline)) {
        if (first) {
          for (int i = 0; i < NN; ++i) out[i] = c * x[i];
        } else {
          for (int i = 0; i < NN; ++i) out[i] += c * x[i];
        }
        first = false;
      };
      if (bd) add(dp, bardot + v * NN);
      if (sa) add(bv * dpa, dot + t.a * ND);
      if (sb) add(bv * dpb, dot + t.b * ND);
    };
    if (t.b == t.a) {
      // never produced (x*x is recorded as a unary square), kept for safety
      addTo(t.a, t.da + t.db, t.daa + 2 * t.dab + t.dbb, 0.0);
      continue;
    }
    addTo(t.a, t.da, t.daa, t.dab);
    if (t.b >= 0) addTo(t.b, t.db, t.dab, t.dbb);
  }
}

/// The full NI x NI Hessian from the inputs' adjoint tangents (rows of its NN nonlinear columns).
template <int NI, int NN>
void assembleHessian(const double* bardot, const char* hasbd, double* hess) {
  for (int k = 0; k < NI * NI; ++k) hess[k] = 0.0;
  for (int b = 0; b < NI; ++b) {
    if (!hasbd[b]) continue;
    const double* row = bardot + b * NN;
    for (int a = 0; a < NN; ++a) {
      if (b < NN) {
        hess[b * NI + a] += 0.5 * row[a];  // symmetric block: average the two computed halves
        hess[a * NI + b] += 0.5 * row[a];
      } else {
        hess[b * NI + a] = row[a];
        hess[a * NI + b] = row[a];
      }
    }
  }
}

/// The sweeps of hessianFromTape with ND forward directions (ND == NI: the Jacobian as well).
template <int NI, int ND, int NN>
void sweeps(const TapeVar* y, int no, const double* w, double* hess, double* jac) {
  const Tape& tape = activeTape();
  const int n = tape.size();
  SweepScratch& s = sweepScratch();
  if (static_cast<int>(s.bar.size()) < n) {
    s.bar.resize(n);
    s.active.resize(n);
    s.hasbardot.resize(n);
  }
  if (static_cast<int>(s.dot.size()) < n * ND) s.dot.resize(n * ND);
  if (static_cast<int>(s.bardot.size()) < n * NN) s.bardot.resize(n * NN);
  forwardSweep<NI, ND, NN>(tape.nodes(), n, s.dot.data(), s.active.data());
  if (jac != nullptr) {
    for (int j = 0; j < no; ++j) {
      const bool has = y[j].i >= 0 && (s.active[y[j].i] & kTangent);
      for (int i = 0; i < ND; ++i) jac[j * ND + i] = has ? s.dot[y[j].i * ND + i] : 0.0;
    }
  }
  reverseSweep<NI, ND, NN>(y, no, w, tape.nodes(), n, s.dot.data(), s.active.data(), s.bar.data(), s.bardot.data(),
                           s.hasbardot.data());
  assembleHessian<NI, NN>(s.bardot.data(), s.hasbardot.data(), hess);
}
}  // namespace detail

/// Weighted Hessian of sum_j w_j y_j (the outputs recorded on the active tape), full NI x NI row-major, and, if
/// `jac` is given, the Jacobian of the outputs (NO x NI, row-major) from the same tape: the forward sweep then
/// carries all NI input directions (the NN nonlinear ones first, so the Hessian's sweeps read the same tangents).
/// Only the first NN inputs may enter nonlinearly (the others' Hessian block must be zero).
template <int NI, int NN>
void hessianFromTape(const TapeVar* y, int no, const double* w, double* hess, double* jac = nullptr) {
  if (jac != nullptr) {
    detail::sweeps<NI, NI, NN>(y, no, w, hess, jac);
  } else {
    detail::sweeps<NI, NN, NN>(y, no, w, hess, nullptr);
  }
}

}  // namespace centaur::planner::rad

namespace Eigen {
template <>
struct NumTraits<centaur::planner::rad::TapeVar> : NumTraits<double> {
  using Real = centaur::planner::rad::TapeVar;
  using NonInteger = centaur::planner::rad::TapeVar;
  using Nested = centaur::planner::rad::TapeVar;
  using Literal = centaur::planner::rad::TapeVar;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 1, AddCost = 3, MulCost = 3 };
};
}  // namespace Eigen
