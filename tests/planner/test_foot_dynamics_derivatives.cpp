// ctest-labels: unit
// The hand-written derivatives of the foot's inverse-dynamics element (foot_dynamics_derivatives.hpp) equal the
// generic AD's (the reverse tape of AdElement, and nested forward AD) to rounding, at random points: non-unit
// quaternions, every foot, every model preset, random weights and scales.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "model/template_params.hpp"
#include "planner/template_elements.hpp"

using namespace centaur;
using namespace centaur::planner;

namespace {

constexpr int kNi = FootDynamicsElement::kInputs, kNo = FootDynamicsElement::kOutputs;

double relErr(double a, double b) { return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b))); }

// A random point: inputs in [-1, 1] with the quaternion scaled by a factor in [0.3, 2] (not unit), omega and the
// force multiplied by `om_gain` and `force_gain`; weights in [-1, 1], some of them zero when `sparse_w`.
struct Point {
  std::vector<double> x = std::vector<double>(kNi), w = std::vector<double>(kNo);
};
Point randomPoint(std::mt19937& rng, double om_gain, double force_gain, bool sparse_w) {
  std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.3, 2.0);
  Point p;
  for (double& v : p.x) v = U(rng);
  const double s = S(rng);
  for (int k = 0; k < 4; ++k) p.x[k] *= s;
  for (int k = 4; k < 7; ++k) p.x[k] *= om_gain;
  for (int k = 22; k < 25; ++k) p.x[k] *= force_gain;
  for (int j = 0; j < kNo; ++j) p.w[j] = sparse_w && j % 3 == 1 ? 0.0 : U(rng);
  return p;
}

void expectClose(const std::vector<double>& a, const std::vector<double>& b, double tol, const char* what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_LT(relErr(a[k], b[k]), tol) << what << "[" << k << "]";
}

// Everything the element's overrides give at p against the AD's, and against each other.
void checkPoint(const FootDynamicsElement& e, const Point& p) {
  std::vector<double> f(kNo), J(kNo * kNi), H(kNi * kNi);
  e.evalJacobianHessian(p.x.data(), p.w.data(), f.data(), J.data(), H.data());
  std::vector<double> f_ad(kNo), J_ad(kNo * kNi), H_ad(kNi * kNi), H_fwd(kNi * kNi), f_eval(kNo);
  e.Ad::evalJacobianHessian(p.x.data(), p.w.data(), f_ad.data(), J_ad.data(), H_ad.data());
  e.evalHessianForward(p.x.data(), p.w.data(), H_fwd.data());
  e.eval(p.x.data(), f_eval.data());
  for (int j = 0; j < kNo; ++j) EXPECT_EQ(f[j], f_eval[j]);
  expectClose(f, f_ad, 1e-12, "f");
  expectClose(J, J_ad, 1e-12, "J");
  expectClose(H, H_ad, 1e-12, "H (tape)");
  expectClose(H, H_fwd, 1e-12, "H (forward)");
  for (int a = 0; a < kNi; ++a)
    for (int b = 0; b < kNi; ++b) EXPECT_EQ(H[a * kNi + b], H[b * kNi + a]) << "H not symmetric at " << a << "," << b;
  for (int a = 13; a < kNi; ++a)
    for (int b = 13; b < kNi; ++b) EXPECT_EQ(H[a * kNi + b], 0.0) << "linear-linear block at " << a << "," << b;
  // evalJacobian and evalHessian alone: the same numbers.
  std::vector<double> f1(kNo), J1(kNo * kNi), H1(kNi * kNi);
  e.evalJacobian(p.x.data(), f1.data(), J1.data());
  e.evalHessian(p.x.data(), p.w.data(), H1.data());
  EXPECT_EQ(f1, f);
  EXPECT_EQ(J1, J);
  EXPECT_EQ(H1, H);
}

}  // namespace

TEST(FootDynamicsDerivatives, EqualTheAdAtRandomPoints) {
  std::mt19937 rng(2026);
  for (const auto& preset : model::templatePresetNames()) {
    const model::TemplateParams P = model::templatePreset(preset);
    for (int i = 0; i < 4; ++i) {
      for (const double scale : {1.0, 7.0, P.totalMass() * P.gravity}) {
        const FootDynamicsElement e(P, i, scale);
        for (int trial = 0; trial < 4; ++trial) {
          SCOPED_TRACE(preset + " foot " + std::to_string(i) + " scale " + std::to_string(scale));
          checkPoint(e, randomPoint(rng, 1.0, 1.0, trial == 3));
          checkPoint(e, randomPoint(rng, 5.0, 500.0, false));  // planner magnitudes: fast spins, large forces
        }
      }
    }
  }
}

TEST(FootDynamicsDerivatives, EqualTheAdAtAUnitQuaternionAndAtRest) {
  const model::TemplateParams P = model::templatePreset("centauro");
  const FootDynamicsElement e(P, 2, 100.0);
  Point p;
  const double half = std::sqrt(0.5);
  p.x = std::vector<double>(kNi, 0.0);
  p.x[0] = half;
  p.x[3] = half;  // 90 degrees about z
  for (int j = 0; j < kNo; ++j) p.w[j] = 0.1 * (j + 1);
  checkPoint(e, p);
}
