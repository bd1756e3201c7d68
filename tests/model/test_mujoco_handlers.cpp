// ctest-labels: unit
// MuJoCo's message handlers (model/mjcf_load.hpp): an engine error becomes a RuntimeError instead of a prompt on
// stdin and exit(1), a warning goes to stderr, and neither writes MUJOCO_LOG.TXT into the working directory.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"
#include "support/temp_dir.hpp"

TEST(MujocoHandlers, ErrorsThrowAndNothingIsLogged) {
  centaur_test::TempDir dir;
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  centaur::installMujocoHandlers();
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  EXPECT_THROW(mj_makeEmptyFileVFS(&vfs, "x.xml", 0), centaur::RuntimeError);  // MuJoCo: "expects positive filesize"
  mju_warning("a test warning");
  mj_deleteVFS(&vfs);
  EXPECT_FALSE(std::filesystem::exists(dir.file("MUJOCO_LOG.TXT")));
  EXPECT_THROW(centaur::loadMjcf(dir.path().string(), false), centaur::InputError) << "a directory is refused";
  std::filesystem::current_path(cwd);
}
