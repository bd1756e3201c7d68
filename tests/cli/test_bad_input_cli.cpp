// ctest-labels: integration cli
// Bad input handled as promised, class by class (docs/reliability.md): the `centaur` command is run on generated
// bad files and arguments; every case must exit 2 with a message naming the file and the key or dataset, within
// a bounded size, leave no output and no temporary behind, and never hang (each run is under `timeout 60`: a hang
// shows as exit code 124). The inputs named as outputs' victims must be unchanged.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "data/primitive_io.hpp"
#include "data/sim_log_file.hpp"
#include "support/cli_run.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using centaur::data::Primitive;

namespace {

/// `s` single-quoted for sh.
std::string shq(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

struct Case {
  Case(std::string n, std::string a, std::vector<std::string> e, std::vector<std::string> ab = {},
       std::vector<std::string> u = {})
      : name(std::move(n)), args(std::move(a)), expect(std::move(e)), absent(std::move(ab)), unchanged(std::move(u)) {}
  std::string name;
  std::string args;                   ///< after `centaur`, paths already quoted
  std::vector<std::string> expect;    ///< substrings of the message
  std::vector<std::string> absent;    ///< outputs that must not exist afterwards
  std::vector<std::string> unchanged; ///< inputs that must keep their content
};

/// Runs every case: exit 2, the substrings, a bounded message, no output, no temporary, inputs unchanged.
void expectRefused(const centaur_test::TempDir& dir, const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    std::vector<std::string> before;
    for (const auto& f : c.unchanged) before.push_back(readFile(f));
    const centaur_test::CliRun r = centaur_test::run(c.args, true, 60);
    EXPECT_EQ(r.code, 2) << c.name << " (124 = hung)\n" << r.out.substr(0, 2000);
    for (const auto& s : c.expect) {
      EXPECT_NE(r.out.find(s), std::string::npos) << c.name << ": message lacks '" << s << "':\n" << r.out.substr(0, 2000);
    }
    EXPECT_LT(r.out.size(), 3000u) << c.name << ": the message is not bounded";
    for (const auto& f : c.absent) EXPECT_FALSE(fs::exists(f)) << c.name << ": output written: " << f;
    for (std::size_t i = 0; i < c.unchanged.size(); ++i) {
      EXPECT_EQ(readFile(c.unchanged[i]), before[i]) << c.name << ": input changed: " << c.unchanged[i];
    }
    for (const auto& e : fs::recursive_directory_iterator(dir.path())) {
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << c.name << ": left " << e.path();
    }
  }
}

/// The synthetic jump at 0.1 s (11 samples), with `edit` applied, written to `path`.
std::string primitiveFile(const std::string& path, const std::function<void(Primitive&)>& edit = {}) {
  const Primitive full = centaur::test::makeSyntheticJump("squat-jump");
  Primitive p = full;
  const Eigen::Index n = 11;
  auto rows = [&](const centaur::data::RowMatrix& m) {
    centaur::data::RowMatrix out(n, m.cols());
    for (Eigen::Index i = 0; i < n; ++i) out.row(i) = m.row(100 * i);
    return out;
  };
  p.t.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) p.t[i] = full.t[100 * i];
  p.q = rows(full.q), p.nu = rows(full.nu), p.base_pos = rows(full.base_pos), p.base_quat = rows(full.base_quat);
  p.base_vel = rows(full.base_vel), p.base_omega = rows(full.base_omega), p.foot_pos = rows(full.foot_pos);
  p.foot_pos_rel = rows(full.foot_pos_rel), p.foot_vel_rel = rows(full.foot_vel_rel), p.force = rows(full.force);
  p.contact = rows(full.contact), p.tau = rows(full.tau);
  if (edit) edit(p);
  centaur::data::writePrimitive(path, p);
  return path;
}

/// A primitive group whose `t` declares `samples` samples (chunked, nothing written: the file stays tiny).
std::string hugeDeclaredFile(const std::string& path, hsize_t samples) {
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t g = H5Gcreate2(f, "squat-jump", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  const hsize_t chunk = 1024;
  H5Pset_chunk(dcpl, 1, &chunk);
  const hid_t space = H5Screate_simple(1, &samples, nullptr);
  const hid_t ds = H5Dcreate2(g, "t", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Dclose(ds), H5Sclose(space), H5Pclose(dcpl), H5Gclose(g), H5Fclose(f);
  return path;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST(BadInputCli, FifosDirectoriesAndDevicesAreRefusedAtOnce) {
  centaur_test::TempDir dir("bad-special");
  const std::string fifo = dir.file("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string d = dir.path().string(), out = dir.file("out.h5"), q = shq(fifo);
  expectRefused(dir, {
      {"plan --config FIFO", "plan squat-jump --config " + q + " --out " + shq(out), {"fifo", "FIFO"}, {out}},
      {"plan --config directory", "plan squat-jump --config " + shq(d) + " --out " + shq(out), {"directory"}, {out}},
      {"plan --config device", "plan squat-jump --config /dev/zero --out " + shq(out), {"/dev/zero", "device"}, {out}},
      {"plan arm-flywheel --config FIFO", "plan arm-flywheel --config " + q + " --out " + shq(out), {"FIFO"}, {out}},
      {"inspect FIFO", "inspect " + q, {"fifo", "FIFO"}},
      {"inspect directory", "inspect " + shq(d), {"directory"}},
      {"plot FIFO", "plot " + q + " --out " + shq(dir.file("p.png")), {"FIFO"}, {dir.file("p.png")}},
      {"bench tick --stack FIFO", "bench tick --ticks 10 --stack " + q, {"fifo", "FIFO"}},
      {"simulate --config FIFO", "simulate stand --duration 0.01 --config " + q, {"FIFO"}},
      {"simulate model FIFO", "simulate stand --duration 0.01 --set model=" + q, {"fifo", "FIFO"}},
      {"simulate --primitive FIFO", "simulate squat-jump --duration 0.01 --primitive " + q, {"FIFO"}},
      {"compare --primitives FIFO", "compare --out " + shq(dir.file("cmp")) + " --primitives " + q, {"FIFO"},
       {dir.file("cmp")}},
  });
}

TEST(BadInputCli, YamlThatIsNotStrictOrTooLargeIsRefused) {
  centaur_test::TempDir dir("bad-yaml");
  const std::string out = dir.file("out.h5");
  auto cfg = [&](const std::string& name, const std::string& text) {
    writeFile(dir.file(name), text);
    return shq(dir.file(name));
  };
  std::string many_keys, laughs = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 0; i < 100000; ++i) many_keys += "k" + std::to_string(i) + ": 1\n";
  for (int i = 1; i < 9; ++i) {
    laughs += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) laughs += std::string(k ? ", " : "") + "*l" + std::to_string(i - 1);
    laughs += "]\n";
  }
  const std::string plan = "plan squat-jump --out " + shq(out) + " --config ";
  expectRefused(dir, {
      {"duplicate key", plan + cfg("dup.yaml", "horizon: {intervals: 30}\nhorizon: {takeoff: 10}\n"),
       {"dup.yaml", "duplicate key 'horizon'", "line 2"}, {out}},
      {"duplicate nested key", plan + cfg("dup2.yaml", "cost:\n  base_height: 1\n  base_height: 2\n"),
       {"dup2.yaml", "duplicate key 'base_height'"}, {out}},
      {"two documents", plan + cfg("docs.yaml", "horizon: {intervals: 30}\n---\ncost: {}\n"),
       {"docs.yaml", "more than one YAML document"}, {out}},
      {"scalar root", plan + cfg("scalar.yaml", "42\n"), {"scalar.yaml", "expected a mapping"}, {out}},
      {"list root", plan + cfg("list.yaml", "- a\n- b\n"), {"list.yaml", "expected a mapping"}, {out}},
      {"complex key", plan + cfg("complex.yaml", "? [a, b]\n: 1\n"), {"complex.yaml", "plain name"}, {out}},
      {"100000 unknown keys", plan + cfg("many.yaml", many_keys), {"many.yaml", "nodes"}, {out}},
      {"2 MB file", plan + cfg("big.yaml", many_keys + many_keys), {"big.yaml", "limit"}, {out}},
      {"billion laughs", plan + cfg("laughs.yaml", laughs), {"laughs.yaml", "nodes"}, {out}},
      {"first unknown keys", plan + cfg("unknown.yaml", "a: 1\nb: 1\nc: 1\nd: 1\ne: 1\nf: 1\ng: 1\n"),
       {"unknown.yaml", "a, b, c, d, e and 2 more"}, {out}},
      {"huge value", plan + cfg("value.yaml", "wheel_radius: " + std::string(500000, '7') + "\n"),
       {"value.yaml", "wheel_radius", "(500000 bytes)"}, {out}},
      {"stack duplicate key", "bench tick --ticks 10 --stack " + cfg("stack.yaml", "stack: [[a]]\nstack: [[b]]\n"),
       {"stack.yaml", "duplicate key 'stack'"}},
      {"arm-flywheel duplicate", "plan arm-flywheel --out " + shq(out) + " --config " +
                                     cfg("arm.yaml", "horizon: {period: 1}\nhorizon: {period: 2}\n"),
       {"arm.yaml", "duplicate"}, {out}},
      {"sim config scalar root", "simulate stand --duration 0.01 --config " + cfg("sim.yaml", "stand\n"),
       {"sim.yaml", "expected a mapping"}},
      {"--set with two documents", "simulate stand --duration 0.01 --set 'duration=1\n---\n2'", {"--set"}},
  });
}

TEST(BadInputCli, NonFiniteNumbersAndUnknownNamesAreRefused) {
  centaur_test::TempDir dir("bad-numbers");
  const std::string png = dir.file("s.png");
  expectRefused(dir, {
      {"--set duration=nan", "simulate stand --set duration=.nan", {"duration"}},
      {"--set duration=inf", "simulate stand --set duration=.inf", {"duration"}},
      {"--duration nan", "simulate stand --duration nan", {"--duration"}},
      {"--at nan", "simulate stand --duration 0.01 --snapshot " + shq(png) + " --at nan", {"--at"}, {png}},
      {"--at inf", "simulate stand --duration 0.01 --snapshot " + shq(png) + " --at inf", {"--at"}, {png}},
      {"unknown camera", "simulate stand --duration 0.01 --snapshot " + shq(png) + " --at 0 --set render.camera=moon",
       {"render.camera", "moon", "side"}, {png}},
      {"planner nan", "plan squat-jump --out " + shq(dir.file("o.h5")) + " --set target.height=.nan",
       {"target.height"}, {dir.file("o.h5")}},
      {"robot --duration nan", "robot stand --lockstep --duration nan --out " + shq(dir.file("r.h5")), {"--duration"},
       {dir.file("r.h5")}},
      {"report --rate nan", "report --primitive " + shq(dir.file("none.h5")) + " --rate nan", {"--rate"}},
      {"control --start-after nan", "control squat-jump --start-after nan", {"--start-after"}},
      {"bench planner unknown key", "bench planner --set cost.no_such_weight=1", {"cost.no_such_weight"}},
      {"bench planner nan", "bench planner --set cost.landing_steps=.nan", {"cost.landing_steps"}},
  });
}

TEST(BadInputCli, DefectiveHdf5FilesAreRefusedNamingFileAndDataset) {
  centaur_test::TempDir dir("bad-h5");
  const std::string good = primitiveFile(dir.file("good.h5"));
  writeFile(dir.file("text.h5"), "not hdf5 at all\n");
  writeFile(dir.file("truncated.h5"), readFile(good).substr(0, 4096));
  hugeDeclaredFile(dir.file("huge.h5"), 200000000ULL);
  hugeDeclaredFile(dir.file("huger.h5"), 1000000000000ULL);
  primitiveFile(dir.file("one.h5"), [](Primitive& p) {
    p.t.conservativeResize(1);
    for (auto* m : {&p.q, &p.nu, &p.base_pos, &p.base_quat, &p.base_vel, &p.base_omega, &p.foot_pos,
                    &p.foot_pos_rel, &p.foot_vel_rel, &p.force, &p.contact, &p.tau}) {
      m->conservativeResize(1, m->cols());
    }
    p.knot_t.resize(0), p.knot_x.resize(0, 37), p.knot_u.resize(0, 31), p.knot_dt.resize(0);
  });
  primitiveFile(dir.file("backwards.h5"), [](Primitive& p) { p.t[6] = p.t[4]; });
  primitiveFile(dir.file("nan-time.h5"), [](Primitive& p) { p.t[3] = kNaN; });
  primitiveFile(dir.file("nan-force.h5"), [](Primitive& p) { p.force(4, 2) = kNaN; });
  primitiveFile(dir.file("all-nan.h5"), [](Primitive& p) { p.foot_pos_rel.setConstant(kNaN); });
  primitiveFile(dir.file("tiny-dt.h5"), [](Primitive& p) {
    for (Eigen::Index i = 0; i < p.t.size(); ++i) p.t[i] = 1e-300 * static_cast<double>(i);
  });
  primitiveFile(dir.file("quat.h5"), [](Primitive& p) { p.base_quat.row(2) << 2.0, 0.0, 0.0, 0.0; });
  primitiveFile(dir.file("knots.h5"), [](Primitive& p) { p.knot_dt[3] = 0.5; });
  primitiveFile(dir.file("iterations.h5"), [](Primitive& p) { p.solve.iterations = -4; });
  primitiveFile(dir.file("mass.h5"), [](Primitive& p) { p.scalars["total_mass"] = kNaN; });
  const centaur_test::CliRun log = centaur_test::run("simulate stand --duration 0.005 --out " + shq(dir.file("log.h5")));
  ASSERT_EQ(log.code, 0) << log.out;
  auto inspect = [&](const std::string& name, std::vector<std::string> expect) {
    expect.insert(expect.begin(), name);
    return Case{"inspect " + name, "inspect " + shq(dir.file(name)), expect};
  };
  expectRefused(dir, {
      inspect("text.h5", {"not an HDF5 file"}),
      inspect("truncated.h5", {}),
      inspect("huge.h5", {"squat-jump/t", "200000000 samples", "allowed"}),
      inspect("huger.h5", {"squat-jump/t", "1000000000000 samples"}),
      inspect("one.h5", {"squat-jump/t", "1 samples"}),
      inspect("backwards.h5", {"squat-jump/t", "does not increase at sample 6"}),
      inspect("nan-time.h5", {"squat-jump/t", "nan"}),
      inspect("nan-force.h5", {"squat-jump/force", "row 4"}),
      inspect("all-nan.h5", {"squat-jump/foot_pos_rel", "row 0"}),
      inspect("tiny-dt.h5", {"squat-jump/t", "sample period"}),
      inspect("quat.h5", {"squat-jump/base_quat", "unit quaternion"}),
      inspect("knots.h5", {"squat-jump/knots/dt", "interval 3"}),
      inspect("iterations.h5", {"solve_iterations"}),
      inspect("mass.h5", {"squat-jump/total_mass", "finite"}),
      inspect("log.h5", {"simulation log"}),
      {"plot a NaN primitive", "plot " + shq(dir.file("nan-force.h5")) + " --out " + shq(dir.file("p.png")),
       {"nan-force.h5", "force"}, {dir.file("p.png")}},
      {"simulate a NaN primitive", "simulate squat-jump --duration 0.01 --primitive " + shq(dir.file("all-nan.h5")),
       {"all-nan.h5", "foot_pos_rel"}},
      {"a primitive as --flywheel", "compare --out " + shq(dir.file("cmp")) + " --primitives " + shq(good) +
                                        " --flywheel " + shq(good) + " --jumps squat-jump",
       {"good.h5", "arm-flywheel"}, {dir.file("cmp")}},
  });
}

TEST(BadInputCli, AnOutputThatIsAnInputIsRefusedAndTheInputKept) {
  centaur_test::TempDir dir("bad-outputs");
  const std::string prim = primitiveFile(dir.file("p.h5"));
  const std::string cfg = dir.file("a.squat-jump.yaml");
  writeFile(cfg, "horizon: {intervals: 30}\n");
  fs::create_symlink(prim, dir.file("link.h5"));
  fs::create_hard_link(prim, dir.file("hard.h5"));
  const std::string simcfg = dir.file("sim.yaml");
  writeFile(simcfg, "duration: 0.01\n");
  const std::string q = shq(prim);
  fs::copy_file(prim, dir.file("squat-jump-none.h5"));
  expectRefused(dir, {
      {"plan --out = --config", "plan squat-jump --config " + shq(cfg) + " --out " + shq(cfg), {"--out", "--config"},
       {}, {cfg}},
      {"plan sidecar = --config", "plan squat-jump --config " + shq(cfg) + " --out " + shq(dir.file("a.h5")),
       {"effective configuration", "--config"}, {dir.file("a.h5")}, {cfg}},
      {"plot --out = input", "plot " + q + " --out " + q, {"--out"}, {}, {prim}},
      {"plot --out = symlink to input", "plot " + q + " --out " + shq(dir.file("link.h5")), {"link.h5"}, {}, {prim}},
      {"plot --out = hard link", "plot " + q + " --out " + shq(dir.file("hard.h5")), {"hard.h5"}, {}, {prim}},
      {"simulate --out = --primitive", "simulate squat-jump --duration 0.01 --primitive " + q + " --out " + q,
       {"--out", "--primitive"}, {}, {prim}},
      {"simulate --video = --config", "simulate stand --config " + shq(simcfg) + " --video " + shq(simcfg),
       {"--video", "--config"}, {}, {simcfg}},
      {"simulate --out = model", "simulate stand --duration 0.01 --set model=" + shq(simcfg) + " --out " + shq(simcfg),
       {"--out", "model"}, {}, {simcfg}},
      {"two outputs on one file", "simulate stand --duration 0.01 --out " + shq(dir.file("x.h5")) + " --video " +
                                      shq(dir.file("x.h5")),
       {"--video", "--out"}, {dir.file("x.h5")}},
      {"compare log = --primitives", "compare --out " + shq(dir.path().string()) + " --jumps squat-jump --modes none " +
                                         "--primitives " + shq(dir.file("squat-jump-none.h5")),
       {"--primitives", "squat-jump-none.h5"}, {}, {dir.file("squat-jump-none.h5")}},
      {"report --out = the log", "report " + shq(dir.file("squat-jump-none.h5")) + " --out " +
                                     shq(dir.file("squat-jump-none.h5")),
       {"--out", "the log"}, {}, {dir.file("squat-jump-none.h5")}},
      {"report --out = --primitive", "report --primitive " + q + " --out " + shq(dir.file("link.h5")),
       {"--out", "--primitive"}, {}, {prim}},
      {"robot --out = --config", "robot stand --lockstep --config " + shq(simcfg) + " --out " + shq(simcfg),
       {"--out", "--config"}, {}, {simcfg}},
  });
}

TEST(BadInputCli, PlannerConsistencyRulesAreCheckedBeforeSolving) {
  centaur_test::TempDir dir("bad-planner");
  const std::string out = dir.file("o.h5");
  expectRefused(dir, {
      {"threshold lifts the robot", "plan squat-jump --set contact.force_threshold=2000 --out " + shq(out),
       {"contact.force_threshold", "2000"}, {out}},
      {"threshold above force_max",
       "plan half-squat-jump --set contact.force_threshold=100 --set contact.force_max=50 --out " + shq(out),
       {"contact.force_threshold", "force_max"}, {out}},
  });
}
