// ctest-labels: unit physics
// MJCF loading without the visual-only geoms: the shipped model keeps exactly its colliding geoms and its
// dynamics (mass matrix, bias forces, contact accelerations at the home keyframe) bit for bit; a model whose body
// inertia comes from a visual geom is returned whole instead; a missing file is an InputError naming it.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "common/error.hpp"
#include "model/mjcf_load.hpp"
#include "support/temp_dir.hpp"

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

int countColliding(const mjModel* m) {
  int n = 0;
  for (int g = 0; g < m->ngeom; ++g) n += (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0) ? 1 : 0;
  return n;
}

// mj_forward at the home keyframe, the base dropped 5 mm into the ground so that the wheels are in contact.
DataPtr forwardAtHome(const mjModel* m) {
  DataPtr d(mj_makeData(m));
  mj_resetDataKeyframe(m, d.get(), mj_name2id(m, mjOBJ_KEY, "home"));
  d->qpos[2] -= 0.005;
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = 0.01 * ((i % 5) - 2);
  mj_forward(m, d.get());
  return d;
}

TEST(MjcfLoad, DiscardingVisualsKeepsTheCollidingGeomsAndTheDynamicsExactly) {
  ModelPtr full(centaur::loadMjcf(kModel, false));
  ModelPtr lean(centaur::loadMjcf(kModel, true));
  ASSERT_TRUE(full && lean);
  EXPECT_GT(full->ngeom, 50);                                  // the robot's visual shapes
  EXPECT_EQ(lean->ngeom, countColliding(full.get()));           // only they are gone
  EXPECT_EQ(countColliding(lean.get()), lean->ngeom);
  EXPECT_EQ(lean->ngeom, 6);                                    // ground, wall, four wheels
  ASSERT_EQ(lean->nv, full->nv);
  ASSERT_EQ(lean->nbody, full->nbody);
  for (int b = 0; b < full->nbody; ++b) EXPECT_EQ(lean->body_mass[b], full->body_mass[b]) << b;

  DataPtr df = forwardAtHome(full.get());
  DataPtr dl = forwardAtHome(lean.get());
  ASSERT_GT(df->ncon, 0);
  EXPECT_EQ(dl->ncon, df->ncon);
  for (int i = 0; i < full->nM; ++i) EXPECT_EQ(dl->qM[i], df->qM[i]);
  for (int i = 0; i < full->nv; ++i) {
    EXPECT_EQ(dl->qfrc_bias[i], df->qfrc_bias[i]) << i;
    EXPECT_NEAR(dl->qacc[i], df->qacc[i], 1e-9 * (1.0 + std::abs(df->qacc[i]))) << i;
  }
}

TEST(MjcfLoad, ModelWhoseInertiaComesFromAVisualGeomIsLoadedWhole) {
  centaur_test::TempDir dir;
  const std::string path = dir.file("geom_inertia.xml");
  std::ofstream(path) << R"(<mujoco>
  <compiler inertiafromgeom="true"/>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1" mass="1"/>
      <geom type="box" size="0.2 0.1 0.1" mass="3" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
)";
  ModelPtr m(centaur::loadMjcf(path, true));
  ASSERT_TRUE(m);
  EXPECT_EQ(m->ngeom, 3);
  EXPECT_DOUBLE_EQ(m->body_mass[1], 4.0);
}

TEST(MjcfLoad, MissingFileIsAnInputErrorNamingIt) {
  const std::string path = "/nonexistent/robot.xml";
  try {
    centaur::loadMjcf(path, true);
    FAIL() << "no exception";
  } catch (const centaur::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
