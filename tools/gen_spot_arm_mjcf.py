#!/usr/bin/env python3
"""Generate models/spot_arm/spot_arm.xml (MJCF for MuJoCo 2.2.2): a Boston Dynamics Spot with its arm, point feet.

Facts (masses, CoMs, principal inertias and their frames, joint axes and ranges, link offsets, the foot sphere, the
home posture) were typed in once as the numeric tables below from google-deepmind/mujoco_menagerie
`boston_dynamics_spot/spot_arm.xml` (and `spot.xml`, identical legs) at commit 4035abd (BSD-3-Clause per the folder's
README; notices in models/spot_arm/LICENSE). The menagerie file does not load in MuJoCo 2.2.2 (actuatorfrcrange,
inheritrange, <position kv>, ellipsoidinertia, implicitfast) and drives position servos with placeholder ranges;
this script never reads it and writes a 2.2.2 model with torque motors. The committed XML is the artifact.

Usage:  python3 tools/gen_spot_arm_mjcf.py [--out PATH]   write the MJCF (default models/spot_arm/spot_arm.xml)
        python3 tools/gen_spot_arm_mjcf.py --check        regenerate in memory, fail if the file at --out differs;
                                                          prints mass, base height and foot centres at home
Pure python3 standard library (helpers shared with the other generators: tools/mjcf_gen.py).

Effort limits [N m] (modelling choice: the menagerie has none, its position servos carry placeholder ranges):
  legs   hx 45, hy 45: the hip actuators' limit of Isaac Lab's Spot model (isaac-sim/IsaacLab,
         isaaclab_assets/robots/spot.py, SPOT_CFG "spot_hip": effort_limit 45), Spot's commonly cited hip peak.
         kn 113: the peak of the same model's knee torque table (angle -> torque, data collected by the Boston
         Dynamics AI Institute: 30.6 N m at -0.25 rad, 113.2 at -1.44, 106 at the home angle -1.8, 37.2 at
         -2.79). The knee's linkage makes its limit angle dependent; a motor's ctrlrange is constant, so this
         is the upper bound (robot.yaml `limits` can lower it).
  arm    sh0 90, sh1 90 (shoulder), el0 90 (elbow pitch, carries the payload moment with sh1), el1 60 (elbow
         roll), wr0 30 (wrist pitch), wr1 20 (wrist roll), f1x 15 (gripper): rough Spot Arm figures (shoulder
         ~90, elbow 60-90, wrist 20-30, gripper ~15 N m); no Boston Dynamics joint torque table was found.
         Check (this model): with the arm stretched out horizontally its own weight needs ~23 N m at sh1, a 5 kg
         load at the tip (0.955 m from sh1) another ~47 N m: 90 N m leaves margin for motion.
Velocity limits [rad/s] (joint `user`; modelling choice within the usual figures, legs 20-30, arm 5-10):
  hx, hy 30; kn 20 (more reduction); sh0, sh1, el0 8; el1, wr0, wr1, f1x 10.
Armature [kg m^2] (reflected rotor inertia, a modelling choice like CENTAURO's, docs/model.md): 0.01 on the hip
  joints, 0.02 on the knees, 0.005 on sh0/sh1/el0, 0.002 on el1/wr0/wr1, 0.001 on the gripper. It keeps the light
  arm links (principal inertias 1e-4..5e-3 kg m^2) well behaved under 2 kHz torque control.

What differs from the menagerie model:
  - no meshes: primitive visual shapes only (massless, collide with nothing); only the four foot spheres collide;
  - `arm_link_hr0` (a jointless 1e-6 kg placeholder between arm_link_sh1 and arm_link_el0 at zero offset) is
    dropped: arm_link_el0 hangs from arm_link_sh1 directly (mass changes by 1e-6 kg);
  - the free joint is `root`; sites `imu` (base origin), `fl_foot fr_foot hl_foot hr_foot` (foot-sphere centres)
    and `arm_ee` (gripper tip, see ARM_EE) are added; IMU sensors as CENTAURO's;
  - home keyframe: the menagerie's joint values (legs 0 1.04 -1.8, arm stowed 0 -3.14 3.06 0 0 0 0) with the base
    height computed here so that the lowest foot-sphere point is at z = 0.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # mjcf_gen.py, from any working directory
sys.dont_write_bytecode = True  # no tools/__pycache__ left in the work tree
from mjcf_gen import (COMPILER_XML, IMU_SENSOR_XML, VISUAL_CLASS_XML, actuator_xml,  # noqa: E402
                      contact_class_xml, fmt, hinge_xml, home_keyframe_xml, identity, main, mmul, mvec,
                      quat_attr, rot, vadd)

# (body, parent, pos in parent [m], joint, axis, (lower, upper) [rad],
#  (mass [kg], CoM [m], principal-axes quat (w x y z, not normalized, as typed), principal inertias [kg m^2]))
BASE = ('body', (32.86, [0.0063944, -9.81216e-05, 0.000911379], [1, 0, 0, 0], [0.13144, 0.13144, 0.13144]))
HIP_Q = [1, 1, -1, 1]
HIP_I = [0.00226544, 0.00211474, 0.00181296]
ULEG_I = [0.0275596, 0.0273549, 0.00284815]
LLEG = (0.35, [0.00225794, 4.6076e-05, -0.180082], [1, 0, 0, 1], [0.00405032, 0.00399902, 0.00014934])
BODIES = [
    # legs, body-tree order FL, FR, HL (rear left), HR (rear right)
    ('fl_hip', 'body', [0.29785, 0.055, 0], 'fl_hx', [1, 0, 0], (-0.785398, 0.785398),
     (1.68, [-0.00537435, 0.0128418, 9.87523e-05], HIP_Q, HIP_I)),
    ('fl_uleg', 'fl_hip', [0, 0.1108, 0], 'fl_hy', [0, 1, 0], (-0.898845, 2.29511),
     (2.34, [0.00514237, -0.00243237, -0.121009], [1, 0, 0, 0], ULEG_I)),
    ('fl_lleg', 'fl_uleg', [0.025, 0, -0.32], 'fl_kn', [0, 1, 0], (-2.7929, -0.254402), LLEG),
    ('fr_hip', 'body', [0.29785, -0.055, 0], 'fr_hx', [1, 0, 0], (-0.785398, 0.785398),
     (1.68, [-0.00537435, -0.0128418, -9.87523e-05], HIP_Q, HIP_I)),
    ('fr_uleg', 'fr_hip', [0, -0.1108, 0], 'fr_hy', [0, 1, 0], (-0.898845, 2.24363),
     (2.34, [0.00514237, 0.00243237, -0.121009], [1, 0, 0, 0], ULEG_I)),
    ('fr_lleg', 'fr_uleg', [0.025, 0, -0.32], 'fr_kn', [0, 1, 0], (-2.7929, -0.255648), LLEG),
    ('hl_hip', 'body', [-0.29785, 0.055, 0], 'hl_hx', [1, 0, 0], (-0.785398, 0.785398),
     (1.68, [0.00537435, 0.0128418, -9.87523e-05], HIP_Q, HIP_I)),
    ('hl_uleg', 'hl_hip', [0, 0.1108, 0], 'hl_hy', [0, 1, 0], (-0.898845, 2.29511),
     (2.34, [0.00514237, -0.00243237, -0.121009], [1, 0, 0, 0], ULEG_I)),
    ('hl_lleg', 'hl_uleg', [0.025, 0, -0.32], 'hl_kn', [0, 1, 0], (-2.7929, -0.247067), LLEG),
    ('hr_hip', 'body', [-0.29785, -0.055, 0], 'hr_hx', [1, 0, 0], (-0.785398, 0.785398),
     (1.68, [0.00537435, -0.0128418, 9.87523e-05], HIP_Q, HIP_I)),
    ('hr_uleg', 'hr_hip', [0, -0.1108, 0], 'hr_hy', [0, 1, 0], (-0.898845, 2.29511),
     (2.34, [0.00514237, 0.00243237, -0.121009], [1, 0, 0, 0], ULEG_I)),
    ('hr_lleg', 'hr_uleg', [0.025, 0, -0.32], 'hr_kn', [0, 1, 0], (-2.7929, -0.248282), LLEG),
    # arm: shoulder yaw/pitch, elbow pitch/roll, wrist pitch/roll, gripper finger (arm_link_hr0 dropped)
    ('arm_link_sh0', 'body', [0.292, 0, 0.188], 'arm_sh0', [0, 0, 1], (-2.61799, 3.14159),
     (2.3364, [-0.0123727, -4.52114e-05, -0.021032], [0.707107, 0.707107, 0, 0], [0.0090143, 0.00778748, 0.0058351])),
    ('arm_link_sh1', 'arm_link_sh0', [0, 0, 0], 'arm_sh1', [0, 1, 0], (-3.14159, 0.523599),
     (0.2596, [2.41764e-05, 2.41161e-06, -1.00591e-05], [1, 1, -1, 1], [0.00020385, 0.000202928, 0.000170786])),
    ('arm_link_el0', 'arm_link_sh1', [0.3385, 0, 0], 'arm_el0', [0, 1, 0], (0.0, 3.14159),
     (0.725, [0.0553741, 0.000236034, 0.048272], [1, 1, 1, 1], [0.00200479, 0.00197228, 0.000821537])),
    ('arm_link_el1', 'arm_link_el0', [0.4033, 0, 0.075], 'arm_el1', [1, 0, 0], (-2.79253, 2.79253),
     (0.725, [-0.125784, -0.0136845, 0.000101579], [0, 1, 0, 1], [0.00451592, 0.00440245, 0.000625481])),
    ('arm_link_wr0', 'arm_link_el1', [0, 0, 0], 'arm_wr0', [0, 1, 0], (-1.8326, 1.8326),
     (0.98, [0.00821068, -0.012051, 3.14348e-05], [1, 1, -1, 1], [0.00123549, 0.000985132, 0.000891615])),
    ('arm_link_wr1', 'arm_link_wr0', [0, 0, 0], 'arm_wr1', [1, 0, 0], (-2.87979, 2.87979),
     (0.785, [0.125168, 0.000101374, -0.013998], [1, 1, 1, 1], [0.00176281, 0.00168181, 0.000767414])),
    ('arm_link_fngr', 'arm_link_wr1', [0.11745, 0, 0.01482], 'arm_f1x', [0, 1, 0], (-1.57, 0.0),
     (0.2, [0.0478787, -0.000206768, -0.0162879], [0, 1, 0, 1], [0.000391278, 0.000300713, 0.000143996])),
]

# Per joint type (the joint name's suffix after the leg prefix, or the full arm joint name):
# (effort limit [N m], velocity limit [rad/s], armature [kg m^2]); sources in the docstring.
ACTUATION = {
    'hx': (45.0, 30.0, 0.01), 'hy': (45.0, 30.0, 0.01), 'kn': (113.0, 20.0, 0.02),
    'arm_sh0': (90.0, 8.0, 0.005), 'arm_sh1': (90.0, 8.0, 0.005), 'arm_el0': (90.0, 8.0, 0.005),
    'arm_el1': (60.0, 10.0, 0.002), 'arm_wr0': (30.0, 10.0, 0.002), 'arm_wr1': (20.0, 10.0, 0.002),
    'arm_f1x': (15.0, 10.0, 0.001),
}

FOOT_RADIUS = 0.036              # [m] menagerie's foot sphere
FOOT_POS = [0.0, 0.0, -0.3365]   # [m] sphere centre in the lower-leg frame
FOOT_SITES = {'fl_lleg': 'fl_foot', 'fr_lleg': 'fr_foot', 'hl_lleg': 'hl_foot', 'hr_lleg': 'hr_foot'}
# Gripper tip on the fixed jaw (arm_link_wr1, so the finger does not move it), on the wrist-roll axis (z = 0, so
# wrist roll only turns it): x = finger hinge x + twice the finger's CoM x = 0.11745 + 2 * 0.0478787 (an estimate
# of the jaw length; the menagerie has no tip frame).
ARM_EE = ('arm_link_wr1', [0.21321, 0.0, 0.0])

# menagerie's home keyframe (joint values; the base height is computed by home_base_height())
HOME = {'hx': 0.0, 'hy': 1.04, 'kn': -1.8,
        'arm_sh0': 0.0, 'arm_sh1': -3.14, 'arm_el0': 3.06, 'arm_el1': 0.0, 'arm_wr0': 0.0, 'arm_wr1': 0.0,
        'arm_f1x': 0.0}

# Visual shapes per body (massless primitives): (type, size, placement attribute, value, material).
VISUALS = {
    'body': [('box', [0.42, 0.1, 0.08], 'pos', [0, 0, 0], 'shell'),
             ('box', [0.44, 0.08, 0.05], 'pos', [0, 0, 0.035], 'dark')],
    'hip': [('cylinder', [0.045], 'fromto', [-0.06, 0, 0, 0.06, 0, 0], 'dark')],
    'uleg': [('cylinder', [0.045], 'fromto', [0, -0.04, 0, 0, 0.04, 0], 'dark'),
             ('capsule', [0.032], 'fromto', [0, 0, 0, 0.025, 0, -0.32], 'shell')],
    'lleg': [('capsule', [0.016], 'fromto', [0, 0, 0, 0, 0, -0.3365], 'dark')],
    'arm_link_sh0': [('cylinder', [0.05], 'fromto', [0, 0, -0.05, 0, 0, 0], 'dark')],
    'arm_link_sh1': [('cylinder', [0.045], 'fromto', [0, -0.05, 0, 0, 0.05, 0], 'dark'),
                     ('capsule', [0.035], 'fromto', [0, 0, 0, 0.3385, 0, 0], 'shell')],
    'arm_link_el0': [('cylinder', [0.04], 'fromto', [0, -0.045, 0, 0, 0.045, 0], 'dark'),
                     ('capsule', [0.03], 'fromto', [0, 0, 0, 0.1, 0, 0.075], 'dark')],
    'arm_link_el1': [('capsule', [0.03], 'fromto', [-0.3033, 0, 0, 0, 0, 0], 'shell')],
    'arm_link_wr0': [('sphere', [0.04], 'pos', [0, 0, 0], 'dark')],
    'arm_link_wr1': [('box', [0.06, 0.04, 0.035], 'pos', [0.07, 0, 0], 'dark'),
                     ('capsule', [0.012], 'fromto', [0.12, 0, -0.02, ARM_EE[1][0], 0, -0.005], 'shell')],
    'arm_link_fngr': [('capsule', [0.012], 'fromto', [0, 0, 0, 0.0958, 0, -0.0326], 'shell')],
}


# ---------------------------------------------------------------- small helpers (no numpy)
def normalized(q):
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def joint_kind(joint):
    """Key of ACTUATION / HOME: 'hx', 'hy', 'kn' for legs, the full name for arm joints."""
    return joint if joint.startswith('arm_') else joint.split('_', 1)[1]


def children_of(parent):
    return [row for row in BODIES if row[1] == parent]


# ---------------------------------------------------------------- forward kinematics (home height, checks)
def fk(joint_q):
    """Pose (R, p) of every body in the base frame, and the total mass, for joint values {joint: q}.
    Body frames carry no rotation of their own (as in the menagerie): only the joints rotate."""
    poses = {'body': (identity(), [0.0, 0.0, 0.0])}
    mass = BASE[1][0]
    for (body, parent, pos, joint, axis, _, inertial) in BODIES:  # parents precede children in BODIES
        R0, p0 = poses[parent]
        poses[body] = (mmul(R0, rot(axis, joint_q.get(joint, 0.0))), vadd(p0, mvec(R0, pos)))
        mass += inertial[0]
    return poses, mass


def home_joints():
    return {row[3]: HOME[joint_kind(row[3])] for row in BODIES}


def foot_centres(joint_q):
    """Foot-sphere centres in the base frame, FL FR HL HR."""
    poses, _ = fk(joint_q)
    out = []
    for body in FOOT_SITES:
        R, p = poses[body]
        out.append(vadd(p, mvec(R, FOOT_POS)))
    return out


def home_base_height():
    """Base z (base level) such that the lowest foot-sphere point touches z = 0 at home."""
    return FOOT_RADIUS - min(c[2] for c in foot_centres(home_joints()))


# ---------------------------------------------------------------- MJCF writer
def inertial_xml(inertial):
    m, com, quat, diag = inertial
    qa = quat_attr(normalized(quat), 12)
    return '<inertial pos="%s"%s mass="%s" diaginertia="%s"/>' % (fmt(com), qa, fmt([m]), fmt(diag))


def visual_xml(body):
    """The body's visual primitives (class visual: massless, no collision)."""
    key = body
    if body[:3] in ('fl_', 'fr_', 'hl_', 'hr_'):
        key = body[3:]  # the four legs share their shapes: 'hip', 'uleg', 'lleg'
    out = []
    for (typ, size, where, value, mat) in VISUALS.get(key, []):
        out.append('<geom class="visual" type="%s" size="%s" %s="%s" material="%s"/>'
                   % (typ, fmt(size), where, fmt(value), mat))
    return out


def joint_xml(joint, axis, rng):
    effort, vel, arm = ACTUATION[joint_kind(joint)]
    return hinge_xml(joint, axis, rng, arm, vel)


def body_xml(parent, indent, out):
    """Child bodies of `parent`, recursively: inertial, joint, visuals, then foot / end-effector extras."""
    for (body, _, pos, joint, axis, rng, inertial) in children_of(parent):
        pad = ' ' * indent
        p2 = pad + '  '
        out.append(pad + '<body name="%s" pos="%s">' % (body, fmt(pos)))
        out.append(p2 + inertial_xml(inertial))
        out.append(p2 + joint_xml(joint, axis, rng))
        out.extend(p2 + g for g in visual_xml(body))
        if body in FOOT_SITES:
            # the only colliding geoms: the foot spheres (named FL FR HL HR as in the menagerie)
            out.append(p2 + '<geom name="%s" class="foot" type="sphere" size="%g" pos="%s"/>'
                       % (body[:2].upper(), FOOT_RADIUS, fmt(FOOT_POS)))
            out.append(p2 + '<site name="%s" pos="%s" size="0.01"/>' % (FOOT_SITES[body], fmt(FOOT_POS)))
        if body == ARM_EE[0]:
            out.append(p2 + '<site name="arm_ee" pos="%s" size="0.01"/>' % fmt(ARM_EE[1]))
        body_xml(body, indent + 2, out)
        out.append(pad + '</body>')


def header_xml():
    """Provenance comment, compiler/option/size, materials and the geom classes."""
    return [
        '<!-- Boston Dynamics Spot with arm (12 leg + 6 arm + 1 gripper joints, point feet) for MuJoCo 2.2.2.',
        '     GENERATED by tools/gen_spot_arm_mjcf.py from facts of mujoco_menagerie\'s boston_dynamics_spot',
        '     (commit 4035abd; BSD-3-Clause per its folder, notices in models/spot_arm/LICENSE).',
        '     Edit the generator, not this file. The robot alone: the simulator adds ground, lights and cameras. -->',
        '<mujoco model="spot_arm">',
        COMPILER_XML,
        '  <option timestep="0.0005" integrator="Euler"/>',
        '  <size nuser_jnt="1"/>',
        '  <asset>',
        '    <material name="shell" rgba="0.88 0.67 0.23 1"/>',
        '    <material name="dark" rgba="0.12 0.12 0.12 1"/>',
        '  </asset>',
        '  <default>',
        '    <geom contype="0" conaffinity="0"/>',
    ] + VISUAL_CLASS_XML + contact_class_xml(
        'foot', 'material="dark"',
        'feet collide with the environment only (contype 1 & environment conaffinity 1);',
        'friction, solref, solimp as CENTAURO\'s wheels (models/centauro/centauro.xml)') + [
        '  </default>']


def footer_xml(base_z):
    """Actuators (torque motors), IMU sensors and the home keyframe."""
    home = home_joints()
    return (actuator_xml((row[3], ACTUATION[joint_kind(row[3])][0]) for row in BODIES) + IMU_SENSOR_XML +
            home_keyframe_xml('menagerie home posture (legs 0 1.04 -1.8, arm stowed), lowest foot-sphere point at'
                              ' z = 0', base_z, [home[row[3]] for row in BODIES]) + ['</mujoco>'])


def generate():
    base_z = home_base_height()
    o = header_xml()
    o.append('  <worldbody>')
    o.append('    <body name="body" pos="0 0 %s">' % fmt([base_z], 10))
    o.append('      <freejoint name="root"/>')
    o.append('      ' + inertial_xml(BASE[1]))
    o.extend('      ' + g for g in visual_xml('body'))
    o.append('      <site name="imu" pos="0 0 0" size="0.01"/>')
    body_xml('body', 6, o)
    o.append('    </body>')
    o.append('  </worldbody>')
    o += footer_xml(base_z)
    return '\n'.join(o) + '\n'


def print_facts():
    _, mass = fk(home_joints())
    print('mass %.4f kg, %d hinge joints, home base height %.6f m' % (mass, len(BODIES), home_base_height()))
    for name, c in zip(FOOT_SITES.values(), foot_centres(home_joints())):
        print('  %s centre (base frame) %s' % (name, fmt(c, 6)))


if __name__ == '__main__':
    sys.exit(main(__file__, __doc__, 'models/spot_arm/spot_arm.xml', generate, print_facts))
