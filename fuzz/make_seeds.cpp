// Writes the HDF5 seed files of the fuzz corpora (fuzz/corpus/{primitive,arm_trajectory,sim_log}/): small valid
// files of each format (few samples, so that mutations reach the data) and a few that break one validation rule
// each, each prefixed with the byte 0x00 (a raw image, fuzz/h5_builder.hpp), plus a few inputs of the structured
// generator (first byte 0x80). Usage: fuzz_make_seeds <fuzz/corpus directory>. Built on request only.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "data/arm_trajectory_io.hpp"
#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "support/synthetic_primitive.hpp"

namespace fs = std::filesystem;
using namespace centaur::data;

namespace {

/// The synthetic jump of the tests, every 100th sample (11 samples at 0.1 s) and its 11 knots.
Primitive smallJump(const std::string& name) {
  const Primitive full = centaur::test::makeSyntheticJump(name);
  Primitive p = full;
  const Eigen::Index n = 11;
  auto rows = [&](const RowMatrix& m) {
    RowMatrix out(n, m.cols());
    for (Eigen::Index i = 0; i < n; ++i) out.row(i) = m.row(100 * i);
    return out;
  };
  p.t.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) p.t[i] = full.t[100 * i];
  p.q = rows(full.q), p.nu = rows(full.nu), p.base_pos = rows(full.base_pos), p.base_quat = rows(full.base_quat);
  p.base_vel = rows(full.base_vel), p.base_omega = rows(full.base_omega), p.foot_pos = rows(full.foot_pos);
  p.foot_pos_rel = rows(full.foot_pos_rel), p.foot_vel_rel = rows(full.foot_vel_rel), p.force = rows(full.force);
  p.contact = rows(full.contact), p.tau = rows(full.tau);
  return p;
}

ArmTrajectory smallArm() {
  ArmTrajectory tr;
  const int n = 11;
  tr.joint_names = {"j_arm1_1", "j_arm1_2", "j_arm1_3", "j_arm1_4", "j_arm1_5", "j_arm1_6", "j_arm1_7"};
  tr.period = 1.0;
  tr.t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  tr.q.resize(n, 7), tr.qd.resize(n, 7), tr.qdd.resize(n, 7), tr.tau.resize(n, 7), tr.h_ang.resize(n, 3);
  tr.ee_pos.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double s = 2.0 * M_PI * tr.t[i];
    for (int j = 0; j < 7; ++j) {
      tr.q(i, j) = 0.3 * std::sin(s + j), tr.qd(i, j) = 0.3 * 2 * M_PI * std::cos(s + j);
      tr.qdd(i, j) = -0.3 * 4 * M_PI * M_PI * std::sin(s + j), tr.tau(i, j) = 2.0 * std::sin(s);
    }
    tr.h_ang.row(i) << 0.0, 1.0 + 0.5 * std::sin(s), 0.0;
    tr.ee_pos.row(i) << 0.6, 0.3, 0.5;
  }
  tr.knot_t = Eigen::VectorXd::LinSpaced(5, 0.0, 1.0);
  tr.knot_x = RowMatrix::Zero(5, 14);
  tr.knot_u = RowMatrix::Zero(4, 7);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(7);
  tr.q_min = -ones, tr.q_max = ones, tr.qd_max = ones, tr.tau_max = 10 * ones;
  tr.q_min_model = -2 * ones, tr.q_max_model = 2 * ones, tr.qd_max_model = 2 * ones, tr.tau_max_model = 20 * ones;
  tr.ee_box_min << 0.4, 0.1, 0.15;
  tr.ee_box_max << 1.0, 0.7, 1.1;
  tr.solve.status = "solved";
  tr.config_yaml = "primitive: arm-flywheel\n";
  return tr;
}

void smallLog(const std::string& path, double nan_at) {
  SimLogHeader h;
  h.joint_names = {"j1", "j2"};
  h.contact_bodies = {"wheel_1"};
  h.config_yaml = "duration: 0.005\n";
  h.scenario = "stand";
  h.samples = 5;
  std::map<std::string, std::vector<double>> columns;
  std::map<std::string, const std::vector<double>*> data;
  for (const LogDataset& d : simLogDatasets()) {
    std::size_t n = 1;
    for (auto e : logDatasetDims(d, h)) n *= static_cast<std::size_t>(e);
    std::vector<double>& v = columns[d.name];
    v.assign(n, 0.0);
    if (std::string(d.name) == "t") {
      for (std::size_t i = 0; i < n; ++i) v[i] = 0.001 * static_cast<double>(i);
    }
    if (std::string(d.name) == "imu_quat" || std::string(d.name) == "base_quat") {
      for (std::size_t i = 0; i < n; i += 4) v[i] = 1.0;
    }
    if (nan_at >= 0 && std::string(d.name) == "tau_cmd") v[static_cast<std::size_t>(nan_at)] = std::nan("");
    data[d.name] = &v;
  }
  writeSimLog(path, h, data);
}

}  // namespace

/// Prefix every file of `dir` that is an HDF5 file with the raw-image byte 0x00; add structured seeds.
void finish(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    std::ifstream in(e.path(), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (bytes.compare(0, 4, "\x89HDF") != 0) continue;
    std::ofstream(e.path(), std::ios::binary | std::ios::trunc) << '\0' << bytes;
  }
  for (int i = 0; i < 4; ++i) {
    std::string choices(1, '\x80');
    for (int k = 0; k < 64 * (i + 1); ++k) choices += static_cast<char>((k * 37 + i * 11) % 251);
    std::ofstream(dir / ("structured-" + std::to_string(i)), std::ios::binary) << choices;
  }
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds <fuzz/corpus directory>\n");
    return 2;
  }
  const fs::path root(argv[1]);
  for (const char* d : {"primitive", "arm_trajectory", "sim_log"}) fs::create_directories(root / d);
  writePrimitive((root / "primitive/valid-one.h5").string(), smallJump("squat-jump"));
  writePrimitives((root / "primitive/valid-two.h5").string(), {smallJump("squat-jump"), smallJump("half-squat-jump")});
  Primitive bad = smallJump("squat-jump");
  bad.force(3, 2) = std::numeric_limits<double>::quiet_NaN();
  writePrimitive((root / "primitive/nan-force.h5").string(), bad);
  bad = smallJump("squat-jump");
  bad.t[5] = bad.t[4];
  writePrimitive((root / "primitive/time-not-increasing.h5").string(), bad);
  bad = smallJump("squat-jump");
  bad.base_quat(2, 0) = 3.0;
  writePrimitive((root / "primitive/not-unit-quaternion.h5").string(), bad);
  writeArmTrajectory((root / "arm_trajectory/valid.h5").string(), smallArm());
  ArmTrajectory arm = smallArm();
  arm.period = 2.0;
  writeArmTrajectory((root / "arm_trajectory/period-mismatch.h5").string(), arm);
  smallLog((root / "sim_log/valid.h5").string(), -1);
  smallLog((root / "sim_log/nan-tau-cmd.h5").string(), 3);
  for (const char* d : {"primitive", "arm_trajectory", "sim_log"}) finish(root / d);
  std::printf("seeds written to %s\n", root.string().c_str());
  return 0;
}
