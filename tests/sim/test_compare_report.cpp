// ctest-labels: unit
// `centaur compare`'s numbers on synthetic data: the pitch of known rotations (ZYX Euler, analytic), the IMU
// pitch history read from a log-shaped HDF5 file, the markdown/JSON table and the merged pitch CSV.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "sim/compare_pitch.hpp"
#include "sim/compare_report.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Quaterniond ypr(double yaw, double pitch, double roll) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

double pitchOf(const Eigen::Quaterniond& q) { return pitchFromQuaternion(q.w(), q.x(), q.y(), q.z()); }

void writeDataset(hid_t f, const char* name, const std::vector<double>& v, std::vector<hsize_t> dims) {
  hid_t sp = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t ds = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(ds);
  H5Sclose(sp);
}

BatchResult completed(double peak, double torque, double rtf, std::map<std::string, double> extra) {
  BatchResult r;
  r.status = BatchResult::Status::Completed;
  r.summary.outcome = "success";
  r.summary.peak_pitch_deg = peak;
  r.summary.max_torque_ratio = torque;
  r.summary.real_time_factor = rtf;
  r.summary.wall_time_s = 1.5;
  r.summary.duration_s = 4.0;
  r.summary.extra = std::move(extra);
  return r;
}

}  // namespace

TEST(ComparePitch, RotationAboutYGivesItsAngle) {
  for (double deg : {-80.0, -30.0, -1.0, 0.0, 0.5, 12.0, 45.0, 89.0}) {
    const double a = deg * kDeg;
    // q = (cos a/2, 0, sin a/2, 0): rotation by a about y, so pitch = a.
    EXPECT_NEAR(pitchFromQuaternion(std::cos(a / 2), 0.0, std::sin(a / 2), 0.0), a, 1e-12) << deg;
  }
}

TEST(ComparePitch, ZyxEulerPitchIndependentOfYawAndRollSignAndScale) {
  for (double yaw : {-2.5, 0.0, 0.7, 3.0}) {
    for (double pitch : {-1.2, -0.3, 0.0, 0.25, 1.4}) {
      for (double roll : {-0.8, 0.0, 0.4}) {
        const Eigen::Quaterniond q = ypr(yaw, pitch, roll);
        EXPECT_NEAR(pitchOf(q), pitch, 1e-12);
        EXPECT_NEAR(pitchFromQuaternion(-q.w(), -q.x(), -q.y(), -q.z()), pitch, 1e-12) << "q and -q";
        EXPECT_NEAR(pitchFromQuaternion(3 * q.w(), 3 * q.x(), 3 * q.y(), 3 * q.z()), pitch, 1e-12) << "|q| = 3";
        // The same number is minus the elevation of the rotated x axis above the horizontal plane.
        const Eigen::Vector3d x_axis = q.toRotationMatrix().col(0);
        EXPECT_NEAR(pitchOf(q), -std::asin(x_axis.z()), 1e-12);
      }
    }
  }
  EXPECT_TRUE(std::isnan(pitchFromQuaternion(0, 0, 0, 0)));
}

TEST(ComparePitch, ReadsTheImuPitchHistoryOfALog) {
  const centaur_test::TempDir dir("compare-pitch");
  const std::string path = dir.file("log.h5");
  std::vector<double> t, quat, base;
  for (int k = 0; k < 50; ++k) {
    t.push_back(0.001 * k);
    const Eigen::Quaterniond q = ypr(0.3, (k - 20) * 0.5 * kDeg, 0.1);  // pitch -10 .. +14.5 deg
    quat.insert(quat.end(), {q.w(), q.x(), q.y(), q.z()});              // log order w, x, y, z
    base.insert(base.end(), {1.0, 0.0, 0.0, 0.0});
  }
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  writeDataset(f, "t", t, {50});
  writeDataset(f, "imu_quat", quat, {50, 4});
  writeDataset(f, "base_quat", base, {50, 4});
  writeDataset(f, "bad_quat", base, {25, 8});
  H5Fclose(f);

  const PitchSeries s = readLogPitch(path);
  ASSERT_EQ(s.t.size(), 50u);
  ASSERT_EQ(s.pitch_deg.size(), 50u);
  for (int k = 0; k < 50; ++k) {
    EXPECT_DOUBLE_EQ(s.t[k], 0.001 * k);
    EXPECT_NEAR(s.pitch_deg[k], (k - 20) * 0.5, 1e-9);
  }
  const PitchSeries level = readLogPitch(path, "base_quat");
  for (double p : level.pitch_deg) EXPECT_EQ(p, 0.0);

  try {
    readLogPitch(path, "no_quat");
    FAIL() << "a missing dataset must be an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no_quat"), std::string::npos);
  }
  EXPECT_THROW(readLogPitch(path, "bad_quat"), InputError);            // (25, 8), not (50, 4)
  EXPECT_THROW(readLogPitch(dir.file("missing.h5")), InputError);      // no file
  std::ofstream(dir.file("text.h5")) << "not hdf5\n";
  EXPECT_THROW(readLogPitch(dir.file("text.h5")), InputError);         // not HDF5
}

TEST(CompareReport, RowsMarkdownAndJson) {
  std::vector<CompareRow> rows;
  rows.push_back(makeCompareRow("squat-jump", "none", completed(12.3456, 0.8, 7.25, {{"pitch_rms_deg", 3.21}}),
                                "d/squat-jump-none.h5"));
  BatchResult fall = completed(61.0, 1.0, 6.0, {{"pitch_rms_deg", 20.0}, {"wall_contact_s", 0.125}});
  fall.summary.outcome = "fall";
  fall.summary.fall_time_s = 2.5;
  rows.push_back(makeCompareRow("half-squat-jump", "none", fall, "d/half-squat-jump-none.h5"));
  BatchResult failed;
  failed.status = BatchResult::Status::RuntimeFailure;
  failed.error = "cannot write d/x.h5 | disk full";
  rows.push_back(makeCompareRow("half-squat-jump", "ocp", failed, "d/half-squat-jump-ocp.h5"));

  EXPECT_EQ(rows[0].outcome, "success");
  ASSERT_TRUE(rows[0].pitch_rms_deg.has_value());
  EXPECT_FALSE(rows[0].wall_contact_s.has_value()) << "a squat jump has no wall contact";
  EXPECT_FALSE(rows[0].fall_time_s.has_value());
  EXPECT_EQ(rows[2].outcome, "error");
  EXPECT_TRUE(rows[2].log.empty()) << "a failed run has no log";

  const std::string md = compareMarkdown(rows);
  std::istringstream lines(md);
  std::string header, rule, r0, r1, r2;
  std::getline(lines, header);
  std::getline(lines, rule);
  std::getline(lines, r0);
  std::getline(lines, r1);
  std::getline(lines, r2);
  EXPECT_EQ(header,
            "| jump | mode | outcome | peak pitch [deg] | pitch RMS [deg] | max torque ratio | wall contact [s] | "
            "real-time factor |");
  EXPECT_EQ(rule, "|---|---|---|---:|---:|---:|---:|---:|");
  EXPECT_EQ(r0, "| squat-jump | none | success | 12.35 | 3.21 | 0.800 | - | 7.25 |");
  EXPECT_EQ(r1, "| half-squat-jump | none | fall | 61.00 | 20.00 | 1.000 | 0.125 | 6.00 |");
  EXPECT_EQ(r2, "| half-squat-jump | ocp | error | - | - | - | - | - |");
  EXPECT_NE(md.find("half-squat-jump / ocp: cannot write d/x.h5 \\| disk full"), std::string::npos) << md;

  const nlohmann::json j = compareJson(rows);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 3u);
  for (const auto& o : j) {
    for (const char* k : {"scenario", "stabilizer", "outcome", "peak_pitch_deg", "pitch_rms_deg", "max_torque_ratio",
                          "wall_contact_s", "real_time_factor", "wall_time_s", "duration_s", "fall_time_s", "log"}) {
      EXPECT_TRUE(o.contains(k)) << k;
    }
  }
  EXPECT_EQ(j[0]["scenario"], "squat-jump");
  EXPECT_EQ(j[0]["stabilizer"], "none");
  EXPECT_DOUBLE_EQ(j[0]["peak_pitch_deg"].get<double>(), 12.3456);
  EXPECT_DOUBLE_EQ(j[0]["pitch_rms_deg"].get<double>(), 3.21);
  EXPECT_TRUE(j[0]["wall_contact_s"].is_null());
  EXPECT_TRUE(j[0]["fall_time_s"].is_null());
  EXPECT_EQ(j[0]["log"], "d/squat-jump-none.h5");
  EXPECT_FALSE(j[0].contains("error"));
  EXPECT_EQ(j[1]["outcome"], "fall");
  EXPECT_DOUBLE_EQ(j[1]["fall_time_s"].get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(j[1]["wall_contact_s"].get<double>(), 0.125);
  EXPECT_EQ(j[2]["outcome"], "error");
  EXPECT_TRUE(j[2]["peak_pitch_deg"].is_null());
  EXPECT_TRUE(j[2]["log"].is_null());
  EXPECT_EQ(j[2]["error"], "cannot write d/x.h5 | disk full");
}

TEST(CompareReport, PitchCsvMergesTimesAndMarksMissingSamples) {
  PitchSeries a{{0.0, 0.001, 0.002, 0.003}, {0.0, 1.5, -2.25, 3.0}};
  PitchSeries b{{0.0, 0.001}, {10.0, 11.0}};  // stopped early (e.g. after a fall)
  PitchSeries c{{0.0010000000001, 0.004}, {-1.0, -4.0}};  // same time to 1 ns; one time of its own
  const std::string csv = pitchCsv({"sq/none", "sq/raibert", "hs/none"}, {a, b, c});
  EXPECT_EQ(csv,
            "t_s,sq/none,sq/raibert,hs/none\n"
            "0,0.000000,10.000000,nan\n"
            "0.001,1.500000,11.000000,-1.000000\n"
            "0.002,-2.250000,nan,nan\n"
            "0.003,3.000000,nan,nan\n"
            "0.004,nan,nan,-4.000000\n");
  EXPECT_THROW(pitchCsv({"one"}, {a, b}), RuntimeError);
  EXPECT_THROW(pitchCsv({"bad"}, {PitchSeries{{0.0, 1.0}, {0.0}}}), RuntimeError);
}
