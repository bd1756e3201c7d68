// ctest-labels: integration cli
// Security and data safety of the `centaur` command (docs/reliability.md):
//   - text from a primitive file (attributes, group names) and output paths never reach gnuplot or ffmpeg as
//     commands: hostile values produce a plot / a video at the given path and execute nothing;
//   - a command stopped by SIGINT or SIGTERM leaves no output and no temporary file behind, and no ffmpeg;
//   - a failed model load writes nothing into the working directory (no MUJOCO_LOG.TXT).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "data/primitive_io.hpp"
#include "support/child_process.hpp"
#include "support/cli_run.hpp"
#include "support/synthetic_primitive.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

std::string shq(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// `centaur args` run in `cwd`, with $PWNED_DIR = cwd (where a command executed by an injection creates its marker).
centaur_test::CliRun runIn(const std::string& cwd, const std::string& args) {
  const std::string cmd =
      "cd " + shq(cwd) + " && PWNED_DIR=" + shq(cwd) + " " + std::string(CENTAUR_BIN) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  centaur_test::CliRun r;
  char buf[4096];
  while (p != nullptr && fgets(buf, sizeof buf, p)) r.out += buf;
  r.code = p != nullptr ? WEXITSTATUS(pclose(p)) : -1;
  return r;
}

/// Names in `dir` that an injected command would have created.
std::vector<std::string> markers(const centaur_test::TempDir& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir.path())) {
    const std::string n = e.path().filename().string();
    if (n.rfind("PWNED", 0) == 0) found.push_back(n);
  }
  return found;
}

bool anyWithPrefix(const centaur_test::TempDir& dir, const std::string& prefix) {
  for (const auto& e : fs::directory_iterator(dir.path())) {
    if (e.path().filename().string().rfind(prefix, 0) == 0) return true;
  }
  return false;
}

}  // namespace

TEST(OutputSafetyCli, HostileAttributesGroupNamesAndPathsExecuteNothingThroughGnuplot) {
  centaur_test::TempDir dir("inject-gnuplot");
  // Each injected command would create a marker file in `dir` (gnuplot runs in its own directory; the shell of an
  // injected `system` finds `dir` in $PWNED_DIR, set for the command by runIn).
  auto touch = [](int k) { return "cd $PWNED_DIR && touch PWNED" + std::to_string(k); };
  const std::vector<std::string> hostile = {
      "solved\nsystem \"" + touch(1) + "\"\n#",
      "x`" + touch(2) + "`'; system '" + touch(3) + "' ;#",
      "a\"; system(\"" + touch(4) + "\") ;\"",
      "@cmd \\\n system '" + touch(5) + "'",
  };
  centaur::data::Primitive p = centaur::test::makeSyntheticJump("squat-jump");
  p.solve.status = hostile[0];
  centaur::data::Primitive q = centaur::test::makeSyntheticJump("x`" + touch(6) + "`'\nsystem '" + touch(7) + "' ;#");
  q.solve.status = hostile[1];
  centaur::data::Primitive r = centaur::test::makeSyntheticJump("b\"; system(\"" + touch(8) + "\") ;\"");
  r.solve.status = hostile[2];
  centaur::data::Primitive s = centaur::test::makeSyntheticJump("c");
  s.solve.status = hostile[3];
  const std::string file = dir.file("hostile.h5");
  centaur::data::writePrimitives(file, {p, q, r, s});

  // One PNG per primitive, named after the sanitized group names, and an output path full of syntax.
  const centaur_test::CliRun all = runIn(dir.path().string(), "plot " + shq(file) + " --width 400 --height 400");
  EXPECT_EQ(all.code, 0) << all.out;
  EXPECT_TRUE(fs::exists(dir.file("hostile-squat-jump.png"))) << all.out;
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, 4);
  const std::string out = dir.file("o\nsystem \"" + touch(9) + "\"\n`" + touch(10) + "`'; system '" + touch(11) + "';.png");
  const centaur_test::CliRun one =
      runIn(dir.path().string(), "plot " + shq(file) + " --primitive squat-jump --width 400 --height 400 --out " + shq(out));
  EXPECT_EQ(one.code, 0) << one.out;
  EXPECT_TRUE(fs::exists(out)) << "the PNG is at exactly the given path";
  EXPECT_TRUE(markers(dir).empty()) << "an injected command ran: " << markers(dir).front();
}

TEST(OutputSafetyCli, FfmpegOutputPathsAreLocalFilesNotOptionsOrUrls) {
  centaur_test::TempDir dir("inject-ffmpeg");
  // A name ffmpeg would read as a protocol and one a shell would read as commands: both become local files.
  for (const std::string name : {"http:PWNED.mp4", "-y; touch PWNED12 `touch PWNED13`.mp4"}) {
    const centaur_test::CliRun r = runIn(
        dir.path().string(), "simulate stand --duration 0.04 --set render.width=64 --set render.height=48 "
                             "--set render.shadows=false --video ./" + shq(name));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(fs::exists(dir.file(name))) << name << "\n" << r.out;
  }
  EXPECT_TRUE(markers(dir).empty()) << "an injected command ran: " << markers(dir).front();
}

TEST(OutputSafetyCli, SignalsLeaveNoOutputNoTemporaryAndNoFfmpeg) {
  for (int sig : {SIGINT, SIGTERM}) {
    centaur_test::TempDir dir("signal");
    centaur_test::TempDir logs("signal-log");  // the command's output, outside the directory that must stay empty
    centaur_test::ChildProcess command(CENTAUR_BIN,
                                       {"simulate", "stand", "--duration", "60", "--video", "v.mp4", "--out", "v.h5",
                                        "--set", "render.width=64", "--set", "render.height=48"},
                                       logs.file("out.txt"), dir.path().string());
    // Wait until the video's temporary exists (ffmpeg started), then stop the command.
    const auto t0 = std::chrono::steady_clock::now();
    while (!anyWithPrefix(dir, "v.mp4.tmp.") && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_TRUE(anyWithPrefix(dir, "v.mp4.tmp.")) << "the run never started its video";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    command.signal(sig);
    ASSERT_TRUE(command.wait(60.0)) << "the command did not stop";
    EXPECT_EQ(command.code(), 128 + sig) << "the command ends with the signal\n" << command.output();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // an ffmpeg left running would write now
    EXPECT_TRUE(dir.entries().empty()) << "left behind: " << (dir.entries().empty() ? "" : dir.entries().front());
  }
}

TEST(OutputSafetyCli, AFailedModelLoadWritesNothingIntoTheWorkingDirectory) {
  centaur_test::TempDir dir("mujoco-log");
  std::ofstream(dir.file("empty.xml")).flush();
  std::ofstream(dir.file("broken.xml")) << "<mujoco><worldbody><geom type='sphere' size='x'/></worldbody></mujoco>\n";
  std::ofstream(dir.file("mesh.xml"))
      << "<mujoco><asset><mesh name='m' file='missing.stl'/></asset><worldbody><body><freejoint/>"
         "<geom type='mesh' mesh='m'/></body></worldbody></mujoco>\n";
  for (const char* model : {"empty.xml", "broken.xml", "mesh.xml", "missing.xml"}) {
    const centaur_test::CliRun r = runIn(dir.path().string(), std::string("simulate stand --duration 0.01 --set model=") + model);
    EXPECT_EQ(r.code, 2) << model << "\n" << r.out;
    EXPECT_NE(r.out.find(model), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(dir.file("MUJOCO_LOG.TXT")));
  EXPECT_EQ(dir.entries().size(), 3u) << "only the three model files";
}
