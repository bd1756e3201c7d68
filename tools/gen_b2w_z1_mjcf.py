#!/usr/bin/env python3
"""Generate models/b2w_z1/b2w_z1.xml (MJCF for MuJoCo 2.2.2): a Unitree B2W with two Unitree Z1 arms.

The B2W (wheeled quadruped) and the Z1 (6-DoF arm) are Unitree's; the two arms on the B2W's front top plate
are our design, not a Unitree product. The numeric tables below were typed in once from the facts of
Unitree's BSD-3 models (copyright notices: models/b2w_z1/LICENSE):
  - B2W: unitree_mujoco unitree_robots/b2w/b2w.xml (commit c598f10): masses, CoMs, principal inertias and
    their orientations, link offsets, joint axes and ranges, effort limits (its motor ctrlrange), armature,
    the IMU site, trunk / head / tail / lidar boxes, the tyre (radius 0.113 m, 0.05 m wide, centred 0.045816 m
    outboard of the wheel joint, as its wheel meshes give). Velocity limits: Unitree's b2w_description URDF
    (unitree_ros; hip and thigh 23, calf 14, wheel 50 rad/s).
  - Z1: mujoco_menagerie unitree_z1/z1.xml (commit a099b54, from Unitree's z1_description): masses, CoMs,
    principal inertias, link offsets, axes, ranges; effort limits 30 N m (joint2 60 N m) and 10 rad/s;
    the flange 0.051 m beyond joint6 and the cylinder sizes of the visual shapes (z1_description's
    collision cylinders).
The script never reads those files; the committed XML is the artifact.

Usage:  python3 tools/gen_b2w_z1_mjcf.py [--out models/b2w_z1/b2w_z1.xml] [--check]
  --check regenerates in memory, prints the model facts and fails (exit 1) if the file at --out differs.
Pure python3 standard library (helpers shared with the other generators: tools/mjcf_gen.py).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # mjcf_gen.py, from any working directory
sys.dont_write_bytecode = True  # no tools/__pycache__ left in the work tree
from mjcf_gen import (COMPILER_XML, IMU_SENSOR_XML, VISUAL_CLASS_XML, actuator_xml,  # noqa: E402
                      contact_class_xml, fmt, hinge_xml, home_keyframe_xml, identity, main, mmul, mvec, rot,
                      vadd)

X, Y, Z = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]

# ---------------------------------------------------------------- B2W facts (unitree_mujoco b2w.xml)
# Inertials are (mass [kg], CoM [m], principal-axes quat (w x y z), principal inertias [kg m^2]) in the body
# frame. All B2W and Z1 body frames are parallel to their parent's at q = 0 (the references use no body quats).
TRUNK_INERTIAL = (40.8426, [0.0212868, 0.0045819, 0.0106169], [0.00178111, 0.675412, -0.000262894, 0.737438],
                  [1.73786, 1.66448, 0.343734])
IMU_POS = [0.0, -0.02341, 0.04927]           # B2W imu site on the trunk, axes of the trunk
TRUNK_HALF = [0.25, 0.14, 0.075]             # Unitree's trunk box: the top plate is at z = +0.075

# Per leg, root to wheel: (body, joint, pos in parent [m], axis, (lower, upper) [rad] or None (continuous),
#  velocity limit [rad/s], effort limit [N m], inertial). Rows as in Unitree's file, leg by leg
# (RR_hip's inertial is Unitree's own entry, not the mirror of RL_hip's; kept as given).
LEG_HIP = (-0.87, 0.87)
LEG_THIGH = (-0.94, 4.69)
LEG_CALF = (-2.82, -0.43)
HIP_L = (2.5294, [-0.00829923, -0.00998502, 0.000235465], [0.525168, 0.518964, 0.477213, 0.476595],
         [0.00485541, 0.00370618, 0.00277182])
HIP_R = (2.5294, [-0.00829923, 0.00998502, 0.000235465], [0.476595, 0.477213, 0.518964, 0.525168],
         [0.00485541, 0.00370618, 0.00277182])
HIP_RL = (2.5294, [0.00829923, -0.00998502, 0.000235465], [0.477213, 0.476595, 0.525168, 0.518964],
          [0.00485541, 0.00370618, 0.00277182])
HIP_RR = (2.5294, [0.00829923, -0.00825992, 0.000235465], [0.524846, 0.53164, 0.469132, 0.470967],
          [0.0048658, 0.00378576, 0.00284106])
THIGH_L = (7.4554, [-0.00418663, -0.0366068, -0.0432737], [0.884916, 0.0880602, -0.00896728, 0.457262],
           [0.085057, 0.0842843, 0.0112538])
THIGH_R = (7.4554, [-0.00418663, 0.0366068, -0.0432737], [0.457262, -0.00896728, 0.0880602, 0.884916],
           [0.085057, 0.0842843, 0.0112538])
CALF_L = (0.679123, [0.0096848, 1.25758e-05, -0.158987], [0.70753, -0.00625821, -0.00634277, 0.706627],
          [0.0162494, 0.0161173, 0.000398115])
CALF_FR = (0.679123, [0.0096848, 0.0, -0.158987], [0.707079, -0.00630052, -0.00630052, 0.707079],
           [0.0162494, 0.0161173, 0.000398115])
CALF_RR = (0.679123, [0.0096848, -1.25756e-05, -0.158987], [0.706627, -0.00634277, -0.00625821, 0.70753],
           [0.0162494, 0.0161173, 0.000398115])
WHEEL_L = (0.918, [-0.00117, 0.051576, -0.001334], [0.661419, 0.248219, 0.250051, 0.662108],
           [0.00611012, 0.00328926, 0.00319322])
WHEEL_R = (0.918, [-0.00117, -0.051576, -0.001334], [0.661419, 0.248219, 0.250051, 0.662108],
           [0.00611012, 0.00328926, 0.00319322])


def leg_rows(leg, hip_pos, side, hip, thigh, calf, wheel):
    """The four rows of one leg (side +1 left, -1 right); the calf offsets are Unitree's (+-8.6984e-05 m)."""
    calf_y = -8.6984e-05 if side > 0 else 8.6986e-05
    return [
        (leg + '_hip', leg + '_hip_joint', hip_pos, X, LEG_HIP, 23.0, 200.0, hip),
        (leg + '_thigh', leg + '_thigh_joint', [0.0, side * 0.11973, 0.0], Y, LEG_THIGH, 23.0, 200.0, thigh),
        (leg + '_calf', leg + '_calf_joint', [0.0, calf_y, -0.35], Y, LEG_CALF, 14.0, 300.0, calf),
        (leg + '_foot', leg + '_foot_joint', [0.0, 0.0, -0.35], Y, None, 50.0, 20.0, wheel),
    ]


LEGS = [  # body-tree order FL, FR, RL, RR (Unitree's motor order FR, FL, RR, RL is not used: actuators by name)
    ('FL', +1, leg_rows('FL', [0.3285, 0.072, 0.0], +1, HIP_L, THIGH_L, CALF_L, WHEEL_L)),
    ('FR', -1, leg_rows('FR', [0.3285, -0.072, 0.0], -1, HIP_R, THIGH_R, CALF_FR, WHEEL_R)),
    ('RL', +1, leg_rows('RL', [-0.3285, 0.072, 0.0], +1, HIP_RL, THIGH_L, CALF_L, WHEEL_L)),
    ('RR', -1, leg_rows('RR', [-0.3285, -0.072, 0.0], -1, HIP_RR, THIGH_R, CALF_RR, WHEEL_R)),
]
B2W_ARMATURE = 0.1          # [kg m^2] Unitree's b2w.xml joint armature (reflected rotor inertia), every joint
WHEEL_RADIUS = 0.113        # [m] tyre radius (Unitree's wheel mesh)
WHEEL_HALF_WIDTH = 0.025    # [m] half of the 0.05 m tyre width
WHEEL_TYRE_Y = 0.045816     # [m] tyre centre outboard of the wheel joint origin (along the wheel axis)

# ---------------------------------------------------------------- Z1 facts (menagerie unitree_z1 z1.xml)
# Left arm, in the frame of its mount. (body, joint or None, pos in parent, axis, range, velocity, effort,
# inertial); link00 is the base, welded to the trunk.
Z1_ROWS = [
    ('link00', None, [0.0, 0.0, 0.0], None, None, None, None,
     (0.472475, [-0.00334984, -0.00013615, 0.0249584], [-0.00692194, 0.682592, 0.00133293, 0.730766],
      [0.000531375, 0.000415207, 0.000378658])),
    ('link01', 'joint1', [0.0, 0.0, 0.0585], Z, (-2.61799, 2.61799), 10.0, 30.0,
     (0.673326, [2.47e-06, -0.00025198, 0.0231717], [0.708578, 0.705633, 0.000281462, -0.000355927],
      [0.00128328, 0.000839362, 0.000719308])),
    ('link02', 'joint2', [0.0, 0.0, 0.045], Y, (0.0, 2.96706), 10.0, 60.0,
     (1.19132, [-0.110126, 0.00240029, 0.00158266], [0.00748058, 0.707092, -0.0114473, 0.70699],
      [0.0246612, 0.0243113, 0.00100468])),
    ('link03', 'joint3', [-0.35, 0.0, 0.0], Y, (-2.87979, 0.0), 10.0, 30.0,
     (0.839409, [0.106092, -0.00541815, 0.0347638], [0.540557, 0.443575, 0.426319, 0.573839],
      [0.00954365, 0.00938711, 0.000558432])),
    ('link04', 'joint4', [0.218, 0.0, 0.057], Y, (-1.51844, 1.51844), 10.0, 30.0,
     (0.564046, [0.0436668, 0.00364738, -0.00170192], [0.0390835, 0.726445, -0.0526787, 0.684087],
      [0.000981656, 0.00094053, 0.000302655])),
    ('link05', 'joint5', [0.07, 0.0, 0.0], Z, (-1.3439, 1.3439), 10.0, 30.0,
     (0.389385, [0.0312153, 0.0, 0.00646316], [0.462205, 0.535209, 0.53785, 0.45895],
      [0.000558961, 0.000547317, 0.000167332])),
    ('link06', 'joint6', [0.0492, 0.0, 0.0], X, (-2.79253, 2.79253), 10.0, 30.0,
     (0.288758, [0.0241569, -0.00017355, -0.00143876], [0.998779, 0.0457735, -0.00663717, 0.0173548],
      [0.00018333, 0.000147464, 0.000146786])),
]
Z1_FLANGE = [0.051, 0.0, 0.0]   # end-effector site on link06: the flange (end of its 0.051 m cylinder)
Z1_ARMATURE = 0.01              # [kg m^2] our choice (the Z1 reference has none): keeps the light wrist stable
# Visual shapes per link, left arm: (type, radius, from, to) in the link frame (z1_description's cylinders).
Z1_SHAPES = {
    'link00': [('cylinder', 0.0325, [0, 0, 0], [0, 0, 0.051])],
    'link01': [('cylinder', 0.0325, [0, 0, 0], [0, 0, 0.045])],
    'link02': [('cylinder', 0.0325, [0, -0.051, 0], [0, 0.051, 0]), ('cylinder', 0.0225, [-0.045, 0, 0],
               [-0.28, 0, 0]), ('cylinder', 0.0325, [-0.35, -0.0255, 0], [-0.35, 0.0255, 0])],
    'link03': [('capsule', 0.02, [0, 0, 0], [0.07, 0, 0.055]), ('cylinder', 0.02, [0.07, 0, 0.055],
               [0.186, 0, 0.055]), ('cylinder', 0.0325, [0.2205, -0.0295, 0.055], [0.2205, 0.0295, 0.055])],
    'link04': [('capsule', 0.02, [0, 0, 0], [0.072, 0, 0]), ('cylinder', 0.0325, [0.072, 0, -0.0335],
               [0.072, 0, 0.0335])],
    'link05': [('capsule', 0.025, [0, 0, 0], [0.0492, 0, 0])],
    'link06': [('cylinder', 0.0325, [0, 0, 0], [0.051, 0, 0])],
}

# ---------------------------------------------------------------- our design choices
ARM_MOUNT = [0.25, 0.15, TRUNK_HALF[2]]   # left Z1 base on the front top plate; the right one at y -> -y
# Home: Unitree's B2W stand (unitree_rl_lab: hip 0, thigh 0.8, calf -1.5); arms folded forward-down: upper arm
# 13 deg forward of vertical, forearm 46 deg below horizontal, hand pointing down (left; right = mirror), every
# pitch joint >= 0.75 rad inside its range (room for the stabilizers both ways).
HOME_LEG = {'hip': 0.0, 'thigh': 0.8, 'calf': -1.5, 'foot': 0.0}
HOME_ARM = {'joint1': 0.0, 'joint2': 1.8, 'joint3': -1.0, 'joint4': 0.75, 'joint5': 0.0, 'joint6': 0.0}

RGBA = {'shell': '0.78 0.79 0.8 1', 'dark': '0.16 0.16 0.17 1', 'arm': '0.88 0.88 0.86 1',
        'hub': '0.45 0.46 0.48 1', 'tyre': '0.05 0.05 0.05 1'}


# ---------------------------------------------------------------- sagittal mirror (y -> -y)
def mirror_vec(v):
    return [v[0], -v[1], v[2]]


def mirror_quat(q):
    """Orientation R -> S R S with S = diag(1, -1, 1): quaternion (w, x, y, z) -> (w, -x, y, -z)."""
    return [q[0], -q[1], q[2], -q[3]]


def mirror_sign(axis):
    """The mirror image of a rotation by q about `axis` is a rotation by sign * q about the same axis:
    +1 for pitch (y) axes, -1 for roll (x) and yaw (z) axes."""
    return -(axis[0] ** 2 - axis[1] ** 2 + axis[2] ** 2)


def mirror_inertial(inertial):
    m, com, quat, diag = inertial
    return (m, mirror_vec(com), mirror_quat(quat), diag)


# ---------------------------------------------------------------- the model tree (one record per body)
def body(name, parent, pos, inertial, joint=None, geoms=(), sites=()):
    return {'name': name, 'parent': parent, 'pos': pos, 'inertial': inertial, 'joint': joint,
            'geoms': list(geoms), 'sites': list(sites)}


def joint(name, axis, rng, vel, effort, armature):
    return {'name': name, 'axis': axis, 'range': rng, 'vel': vel, 'effort': effort, 'armature': armature}


def shape(kind, radius, a, b, color, cls='visual'):
    return '<geom class="%s" type="%s" size="%g" fromto="%s %s" rgba="%s"/>' % (
        cls, kind, radius, fmt(a, 6), fmt(b, 6), RGBA[color])


def trunk_body():
    """The B2W trunk with Unitree's trunk, head, tail and lidar boxes as visuals and the IMU site."""
    geoms = ['<geom class="visual" type="box" size="%s" rgba="%s"/>' % (fmt(TRUNK_HALF), RGBA['shell']),
             '<geom class="visual" type="box" size="0.02 0.06 0.07" pos="0.41 0 0.005" rgba="%s"/>' % RGBA['dark'],
             '<geom class="visual" type="box" size="0.0125 0.06 0.07" pos="-0.405 0 0.005" rgba="%s"/>'
             % RGBA['dark'],
             '<geom class="visual" type="cylinder" size="0.076 0.08" pos="0.34218 0 0.15851" rgba="%s"/>'
             % RGBA['dark']]
    sites = ['<site name="imu" pos="%s" size="0.01" rgba="1 0.2 0.2 1"/>' % fmt(IMU_POS)]
    return body('base', None, [0.0, 0.0, 0.0], TRUNK_INERTIAL, None, geoms, sites)


def wheel_extras(leg, side):
    """Collision tyre (class wheel), hub and axle visuals, and the wheel-centre site (z axis = wheel axis,
    on the spinning wheel body but on its axis, so its position and z axis do not change as it spins)."""
    y0, h = side * WHEEL_TYRE_Y, side * WHEEL_HALF_WIDTH
    geoms = ['<geom name="%s_wheel" class="wheel" type="cylinder" size="%g" fromto="0 %s 0 0 %s 0"/>'
             % (leg, WHEEL_RADIUS, fmt([y0 - h], 8), fmt([y0 + h], 8)),
             shape('cylinder', 0.065, [0, y0 - 1.1 * h, 0], [0, y0 + 1.1 * h, 0], 'hub'),
             shape('cylinder', 0.03, [0, 0, 0], [0, y0 - h, 0], 'dark')]
    s = math.sqrt(0.5)
    sites = ['<site name="%s_wheel_centre" pos="0 %s 0" quat="%s" size="0.015"/>'
             % (leg, fmt([y0], 8), fmt([s, -s, 0.0, 0.0], 15))]
    return geoms, sites


def leg_bodies(leg, side, rows):
    """hip -> thigh -> calf -> foot (the wheel) of one leg, and the leg's home joint angles."""
    out, home, parent = [], {}, 'base'
    for i, (name, jname, pos, axis, rng, vel, effort, inertial) in enumerate(rows):
        child_pos = rows[i + 1][2] if i + 1 < len(rows) else None
        part = name.split('_')[1]
        geoms, sites = [], []
        if part == 'hip':
            geoms.append(shape('cylinder', 0.07, [0, side * 0.095, 0], [0, side * 0.145, 0], 'dark'))
        elif part in ('thigh', 'calf'):
            geoms.append(shape('capsule', 0.03 if part == 'thigh' else 0.02, [0, 0, 0], child_pos, 'shell'))
        else:
            geoms, sites = wheel_extras(leg, side)
        out.append(body(name, parent, pos, inertial, joint(jname, axis, rng, vel, effort, B2W_ARMATURE),
                        geoms, sites))
        home[jname] = HOME_LEG[part]
        parent = name
    return out, home


def arm_bodies(prefix, side):
    """The Z1 chain (link00 welded to the trunk) for side +1 (left, as typed) or -1 (right, mirror image:
    positions, CoMs and inertia orientations mirrored y -> -y; the same joint axes, so a joint whose mirror
    sign is -1 gets the mirrored range and home angle)."""
    out, home, parent = [], {}, 'base'
    for name, jname, pos, axis, rng, vel, effort, inertial in Z1_ROWS:
        if name == 'link00':
            pos = ARM_MOUNT
        jnt = None
        shapes = Z1_SHAPES[name]
        if side < 0:
            pos, inertial = mirror_vec(pos), mirror_inertial(inertial)
            shapes = [(k, r, mirror_vec(a), mirror_vec(b)) for (k, r, a, b) in shapes]
        if jname:
            sgn = mirror_sign(axis) if side < 0 else 1.0
            lo, hi = (rng[0], rng[1]) if sgn > 0 else (-rng[1], -rng[0])
            jnt = joint(prefix + jname, axis, (lo, hi), vel, effort, Z1_ARMATURE)
            home[prefix + jname] = sgn * HOME_ARM[jname]
        geoms = [shape(k, r, a, b, 'dark' if k == 'cylinder' and r > 0.03 else 'arm') for (k, r, a, b) in shapes]
        sites = []
        if name == 'link06':
            sites.append('<site name="%see" pos="%s" size="0.012" rgba="0.2 0.8 0.2 1"/>' % (prefix, fmt(Z1_FLANGE)))
        out.append(body(prefix + name, parent, pos, inertial, jnt, geoms, sites))
        parent = prefix + name
    return out, home


def build_model():
    """All bodies in write order (trunk, legs FL FR RL RR, left arm, right arm) and the home joint angles."""
    bodies, home = [trunk_body()], {}
    for leg, side, rows in LEGS:
        b, h = leg_bodies(leg, side, rows)
        bodies += b
        home.update(h)
    for prefix, side in (('left_', +1), ('right_', -1)):
        b, h = arm_bodies(prefix, side)
        bodies += b
        home.update(h)
    return bodies, home


# ---------------------------------------------------------------- forward kinematics (base frame)
def fk(bodies, q):
    """Pose (R, p) of every body in the base frame at joint angles q (missing joints: 0); mass and CoM."""
    poses, mass, mc = {}, 0.0, [0.0, 0.0, 0.0]
    for b in bodies:  # parents come before their children
        if b['parent'] is None:
            R, p = identity(), [0.0, 0.0, 0.0]
        else:
            R0, p0 = poses[b['parent']]
            p = vadd(p0, mvec(R0, b['pos']))
            R = R0
            if b['joint']:
                R = mmul(R0, rot(b['joint']['axis'], q.get(b['joint']['name'], 0.0)))
        poses[b['name']] = (R, p)
        m, com = b['inertial'][0], b['inertial'][1]
        c = vadd(p, mvec(R, com))
        mass += m
        mc = [mc[i] + m * c[i] for i in range(3)]
    return poses, mass, [x / mass for x in mc]


def wheel_centres(poses):
    """Per leg: wheel centre and axis (base frame) and the lowest point of the tyre cylinder."""
    out = {}
    for leg, side, _ in LEGS:
        R, p = poses[leg + '_foot']
        c = vadd(p, mvec(R, [0.0, side * WHEEL_TYRE_Y, 0.0]))
        a = mvec(R, Y)
        az = abs(a[2])
        lowest = c[2] - WHEEL_RADIUS * math.sqrt(max(0.0, 1.0 - az * az)) - WHEEL_HALF_WIDTH * az
        out[leg] = (c, a, lowest)
    return out


def home_base_height(bodies, home):
    """Base height that puts the lowest tyre point at z = 0 (the base level, not rotated)."""
    poses, _, _ = fk(bodies, home)
    return -min(low for (_, _, low) in wheel_centres(poses).values())


# ---------------------------------------------------------------- MJCF writer
def inertial_xml(inertial):
    m, com, quat, diag = inertial
    return '<inertial pos="%s" quat="%s" mass="%s" diaginertia="%s"/>' % (fmt(com), fmt(quat), fmt([m]), fmt(diag))


def body_xml(bodies, b, indent, out, base_z):
    pad = ' ' * indent
    pos = [0.0, 0.0, base_z] if b['parent'] is None else b['pos']
    out.append(pad + '<body name="%s" pos="%s">' % (b['name'], fmt(pos, 12)))
    p2 = pad + '  '
    if b['parent'] is None:
        out.append(p2 + '<freejoint name="root"/>')
    out.append(p2 + inertial_xml(b['inertial']))
    j = b['joint']
    if j:  # a joint without range (the wheels) is written unlimited
        out.append(p2 + hinge_xml(j['name'], j['axis'], j['range'], j['armature'], j['vel']))
    out += [p2 + g for g in b['geoms']]
    out += [p2 + s for s in b['sites']]
    for child in bodies:
        if child['parent'] == b['name']:
            body_xml(bodies, child, indent + 2, out, base_z)
    out.append(pad + '</body>')


def header_xml(n_hinges, mass):
    return [
        '<!-- GENERATED by tools/gen_b2w_z1_mjcf.py from facts of Unitree\'s BSD-3 models (unitree_mujoco b2w,',
        '     mujoco_menagerie unitree_z1); copyright notices in models/b2w_z1/LICENSE. Edit the generator, not this.',
        '     Unitree B2W wheeled quadruped with two Unitree Z1 arms on its front top plate (the arm mounts are',
        '     our design, not a Unitree product), for MuJoCo 2.2.2: %d hinge joints, %.1f kg, the robot alone. -->'
        % (n_hinges, mass),
        '<mujoco model="b2w_z1">',
        COMPILER_XML,
        '  <option timestep="0.0005" integrator="Euler" solver="Newton" cone="elliptic" jacobian="sparse"'
        ' iterations="50" tolerance="1e-10" gravity="0 0 -9.81"/>',
        '  <size njmax="500" nconmax="100" nuser_jnt="1"/>',
        '  <default>',
        '    <joint damping="0" frictionloss="0"/>',
        '    <geom contype="0" conaffinity="0"/>',
    ] + VISUAL_CLASS_XML + contact_class_xml(
        'wheel', 'rgba="%s"' % RGBA['tyre'],
        'only the tyres collide, and only with the environment (its geoms: contype 0, conaffinity 1)') + [
        '  </default>']


def generate():
    bodies, home = build_model()
    base_z = home_base_height(bodies, home)
    hinges = [b['joint'] for b in bodies if b['joint']]  # = MuJoCo's joint order (depth-first = write order)
    o = header_xml(len(hinges), sum(b['inertial'][0] for b in bodies))
    o.append('  <worldbody>')
    body_xml(bodies, bodies[0], 4, o, base_z)
    o.append('  </worldbody>')
    o += actuator_xml((j['name'], j['effort']) for j in hinges)
    o += IMU_SENSOR_XML
    o += home_keyframe_xml('B2W stand (thigh 0.8, calf -1.5), arms folded forward-down; the lowest tyre points at'
                           ' z = 0', base_z, [home[j['name']] for j in hinges], z_digits=12)
    o.append('</mujoco>')
    return '\n'.join(o) + '\n'


def print_facts():
    """Model facts from the generator's own kinematics: mass, joints, home height, wheels, CoM, arm tips."""
    bodies, home = build_model()
    base_z = home_base_height(bodies, home)
    hinges = [b['joint'] for b in bodies if b['joint']]
    for label, q in (('home', home), ('zero', {})):
        poses, mass, com = fk(bodies, q)
        print('%s: mass %.4f kg, CoM (base frame) %s' % (label, mass, fmt(com, 5)))
        for leg, (c, a, low) in wheel_centres(poses).items():
            print('  %s wheel centre %s  axis %s  lowest %.6f' % (leg, fmt(c, 6), fmt(a, 4), low))
        for prefix in ('left_', 'right_'):
            R, p = poses[prefix + 'link06']
            print('  %see %s' % (prefix, fmt(vadd(p, mvec(R, Z1_FLANGE)), 5)))
    print('hinge joints: %d (%d limited), home base height %.9f m' % (
        len(hinges), sum(1 for j in hinges if j['range']), base_z))


if __name__ == '__main__':
    sys.exit(main(__file__, __doc__, 'models/b2w_z1/b2w_z1.xml', generate, print_facts))
