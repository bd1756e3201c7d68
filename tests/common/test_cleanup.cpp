// ctest-labels: unit
// Temporaries never outlive a command (common/cleanup.hpp, atomic_file.hpp, child_process.hpp, output_guard.hpp):
// registered files, directories and children are removed / killed on exit and on SIGINT / SIGTERM (checked in
// forked children that are signalled while their temporaries exist); outputs that are inputs are refused.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/atomic_file.hpp"
#include "common/child_process.hpp"
#include "common/cleanup.hpp"
#include "common/error.hpp"
#include "common/output_guard.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using centaur_test::TempDir;

namespace {

void touch(const std::string& path) { std::ofstream(path) << "x"; }

/// Fork a child that installs the cleanup, creates its temporaries (`setup`), says so through a pipe and waits;
/// the parent sends `sig` and returns the child's wait status.
template <class Setup>
int signalledChild(int sig, Setup setup) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    centaur::cleanup::install();
    setup();
    const char ready = 'r';
    if (write(fds[1], &ready, 1) != 1) _exit(3);
    for (;;) pause();
  }
  close(fds[1]);
  char ready = 0;
  const bool ok = read(fds[0], &ready, 1) == 1;
  close(fds[0]);
  if (ok) kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace

TEST(Cleanup, SignalRemovesTemporariesAndKeepsTheSignalAsExitStatus) {
  for (int sig : {SIGINT, SIGTERM}) {
    TempDir dir;
    const std::string target = dir.file("out.h5");
    const int status = signalledChild(sig, [&] {
      const std::string tmp = centaur::temporaryPathFor(target);  // registered: <target>.tmp.<pid>
      touch(tmp);
      centaur::StagedOutputs* staged = new centaur::StagedOutputs(dir.file("outdir"));  // never committed
      touch(staged->path("compare.md"));
      touch(staged->path("run.h5"));
    });
    ASSERT_TRUE(WIFSIGNALED(status)) << "the process still ends with the signal";
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_TRUE(dir.entries().empty()) << "left: " << (dir.entries().empty() ? "" : dir.entries().front());
  }
}

TEST(Cleanup, SignalKillsRegisteredChildren) {
  TempDir dir;
  const std::string pid_file = dir.file("child.pid");
  const int status = signalledChild(SIGTERM, [&] {
    auto* child = new centaur::ChildProcess({"sleep", "300"}, centaur::ChildProcess::Options{});
    std::ofstream(pid_file) << child->pid();
  });
  ASSERT_TRUE(WIFSIGNALED(status));
  pid_t grandchild = 0;
  std::ifstream(pid_file) >> grandchild;
  ASSERT_GT(grandchild, 0);
  EXPECT_NE(kill(grandchild, 0), 0) << "the `sleep 300` started by the signalled process is gone";
  // In this process: runNow() (what exit() runs) kills a registered child.
  centaur::ChildProcess child({"sleep", "300"}, centaur::ChildProcess::Options{});
  centaur::cleanup::runNow();
  EXPECT_EQ(child.wait(), 128 + SIGKILL);
}

TEST(Cleanup, CommittedAndRemovedTemporariesAreForgotten) {
  TempDir dir;
  const std::string target = dir.file("a.txt");
  centaur::writeTextFileAtomic(target, "kept");
  centaur::cleanup::runNow();  // what exit() runs: the committed file must survive it
  EXPECT_TRUE(fs::exists(target));
  const std::string tmp = centaur::temporaryPathFor(dir.file("b.txt"));
  touch(tmp);
  centaur::cleanup::runNow();
  EXPECT_FALSE(fs::exists(tmp)) << "a temporary nobody committed is removed at exit";
}

TEST(Cleanup, StagedOutputsAppearTogetherOrNotAtAll) {
  TempDir dir;
  {
    centaur::StagedOutputs staged(dir.file("new"));
    touch(staged.path("x.md"));
  }
  EXPECT_FALSE(fs::exists(dir.file("new"))) << "an uncommitted staging leaves nothing, not even the directory";
  centaur::StagedOutputs staged(dir.file("new"));
  touch(staged.path("x.md"));
  touch(staged.path("y.json"));
  EXPECT_FALSE(fs::exists(dir.file("new/x.md")));
  const auto moved = staged.commit();
  EXPECT_EQ(moved.size(), 2u);
  EXPECT_TRUE(fs::exists(dir.file("new/x.md")));
  EXPECT_TRUE(fs::exists(dir.file("new/y.json")));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.file("new")), fs::directory_iterator()), 2);
}

TEST(OutputGuard, AnOutputThatIsAnInputIsRefusedWhateverItsName) {
  TempDir dir;
  const std::string input = dir.file("in.yaml");
  touch(input);
  fs::create_symlink(input, dir.file("link.yaml"));
  fs::create_hard_link(input, dir.file("hard.yaml"));
  fs::create_directories(dir.file("sub"));
  for (const std::string& out : {input, dir.file("link.yaml"), dir.file("hard.yaml"), dir.file("sub/../in.yaml"),
                                 dir.file("./in.yaml")}) {
    try {
      centaur::guardOutputs({{"--config", input}}, {{"--out", out}});
      FAIL() << out;
    } catch (const centaur::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--config"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--out"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(centaur::guardOutputs({{"--config", input}}, {{"--out", dir.file("other.h5")}}));
  EXPECT_NO_THROW(centaur::guardOutputs({{"--config", ""}}, {{"--out", input}})) << "an absent option is skipped";
  EXPECT_THROW(centaur::guardOutputs({}, {{"--out", dir.file("x.h5")}, {"--video", dir.file("sub/../x.h5")}}),
               centaur::InputError)
      << "two outputs on one path";
  EXPECT_EQ(std::ifstream(input).get(), 'x') << "the input is untouched";
}
