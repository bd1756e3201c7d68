#pragma once
// A small robot whose derived facts can be computed by hand: a 10 kg base, a 2 kg torso, two mirrored 2-joint
// arms of 0.5 kg links, four 1.5 kg point-footed legs (a 1 kg hip link on a pitch hinge, a welded 0.5 kg foot
// 0.4 m below with a 0.05 m sphere). At home every joint is at 0 and the base 0.45 m high (feet on the ground).
// The MJCF and robot.yaml texts are given as strings so that each test can break one thing.
#include <fstream>
#include <string>

namespace centaur_test {

inline std::string legXml(const char* name, double x, double y) {
  const std::string p = std::to_string(x) + " " + std::to_string(y);
  return std::string("      <body name=\"") + name + "_hip\" pos=\"" + p + " 0\">\n" +
         "        <joint name=\"" + name + "_pitch\" axis=\"0 1 0\" range=\"-2 2\" user=\"20\"/>\n" +
         "        <inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"0.01 0.01 0.01\"/>\n" +
         "        <body name=\"" + name + "_foot\" pos=\"0 0 -0.4\">\n" +
         "          <inertial pos=\"0 0 0\" mass=\"0.5\" diaginertia=\"0.001 0.001 0.001\"/>\n" +
         "          <geom name=\"" + name + "_sphere\" type=\"sphere\" size=\"0.05\" contype=\"1\" conaffinity=\"0\"/>\n" +
         "          <site name=\"" + name + "_centre\"/>\n" +
         "        </body>\n      </body>\n";
}

inline std::string armXml(const char* side, double y, const char* second_axis) {
  const std::string s(side);
  return "      <body name=\"" + s + "1\" pos=\"0 " + std::to_string(y) + " 0.1\">\n" +
         "        <joint name=\"" + s + "_j1\" axis=\"0 1 0\" range=\"-3 3\"/>\n" +
         "        <inertial pos=\"0 0 0\" mass=\"0.5\" diaginertia=\"0.01 0.01 0.01\"/>\n" +
         "        <body name=\"" + s + "2\" pos=\"0 0 -0.2\">\n" +
         "          <joint name=\"" + s + "_j2\" axis=\"" + second_axis + "\" range=\"-3 3\"/>\n" +
         "          <inertial pos=\"0 0 0\" mass=\"0.5\" diaginertia=\"0.01 0.01 0.01\"/>\n" +
         "          <site name=\"" + s + "_tip\" pos=\"0 0 -0.1\"/>\n" +
         "        </body>\n      </body>\n";
}

/// The MJCF; `actuator` is the element used for every joint ("motor" by default).
inline std::string syntheticMjcf(const std::string& actuator = "motor") {
  std::string x = R"(<mujoco model="synthetic">
  <compiler angle="radian" inertiafromgeom="false" autolimits="true"/>
  <option timestep="0.0005"/>
  <size nuser_jnt="1"/>
  <worldbody>
    <body name="base" pos="0 0 0.45">
      <freejoint name="root"/>
      <inertial pos="0 0 0" mass="10" diaginertia="1 2 3"/>
      <site name="imu" pos="0.1 0 0"/>
      <body name="torso" pos="0.1 0 0.2">
        <inertial pos="0 0 0" mass="2" diaginertia="0.1 0.2 0.3"/>
      </body>
)";
  x += armXml("left", 0.3, "1 0 0") + armXml("right", -0.3, "1 0 0");
  x += legXml("fl", 0.3, 0.2) + legXml("fr", 0.3, -0.2) + legXml("rl", -0.3, 0.2) + legXml("rr", -0.3, -0.2);
  x += "    </body>\n  </worldbody>\n  <actuator>\n";
  for (const char* j : {"left_j1", "left_j2", "right_j1", "right_j2", "fl_pitch", "fr_pitch", "rl_pitch", "rr_pitch"}) {
    x += std::string("    <") + actuator + " name=\"" + j + "\" joint=\"" + j + "\" ctrlrange=\"-50 50\"/>\n";
  }
  x += R"(  </actuator>
  <sensor>
    <framequat name="imu_quat" objtype="site" objname="imu"/>
    <gyro name="imu_gyro" site="imu"/>
    <accelerometer name="imu_acc" site="imu"/>
  </sensor>
  <keyframe>
    <key name="home" qpos="0 0 0.45 1 0 0 0 0 0 0 0 0 0 0 0"/>
  </keyframe>
</mujoco>
)";
  return x;
}

inline std::string syntheticYaml() {
  return R"(name: synthetic
mjcf: synthetic.xml
base: base
home: home
imu: {site: imu, orientation: imu_quat, gyro: imu_gyro, accelerometer: imu_acc}
feet:
  FL: {root: fl_hip, contact: fl_foot, centre: fl_centre, type: point, radius: auto}
  FR: {root: fr_hip, contact: fr_foot, centre: fr_centre, type: point, radius: auto}
  RL: {root: rl_hip, contact: rl_foot, centre: rl_centre, type: point, radius: auto}
  RR: {root: rr_hip, contact: rr_foot, centre: rr_centre, type: point, radius: auto}
upper_body:
  torso_joints: []
  arms:
    - {name: left, joints: [left_j1, left_j2], end_effector: left_tip}
    - {name: right, joints: [right_j1, right_j2], end_effector: right_tip, mirrors: left}
stabilizers:
  raibert: [left_j1, right_j1]
  angmom: [left_j1, left_j2, right_j1, right_j2]
gains:
  - {group: leg, joints: ["*_pitch"], kp: 100.0, kd: 1.0}
  - {group: other, joints: ["*"], kp: 10.0, kd: 0.1}
limits:
  left_j1: {qd_max: 4.0}
)";
}

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace centaur_test
