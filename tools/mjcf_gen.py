"""What the MJCF generators tools/gen_*_mjcf.py share (pure python3 standard library, no numpy).

  - 3x3 matrix and 3-vector math on nested lists (row-major): identity, mmul, mvec, vadd, rot;
  - number formatting for XML attributes: fmt, quat_attr;
  - MJCF pieces every generated model writes alike: the compiler line, the visual geom class, the class of the
    geoms that touch the environment, hinges, torque motors, the IMU sensors, the home keyframe;
  - the command line: main() writes the model through a temporary file and a rename, or with --check prints
    the model's facts and compares the regeneration with the file on disk.

Nothing here is particular to one robot: each generator keeps its facts tables, its kinematic tree and its
own writer. Changing a piece here changes every model that uses it: run every generator's --check after.
"""
import argparse
import math
import os
import sys


# ---------------------------------------------------------------- 3x3 matrices and 3-vectors
def identity():
    """A new 3x3 identity matrix (floats)."""
    return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]


def mmul(a, b):
    """Matrix product a b."""
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mvec(a, v):
    """Matrix times vector a v."""
    return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]


def vadd(a, b):
    """Vector sum a + b."""
    return [a[i] + b[i] for i in range(3)]


def rot(axis, angle):
    """Rotation matrix by `angle` [rad] about a unit axis (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return [[c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t]]


# ---------------------------------------------------------------- numbers as attribute text
def fmt(v, digits=10):
    """Numbers as %g with `digits` significant digits, space separated; '-0' is written '0'."""
    out = []
    for x in v:
        s = '%.*g' % (digits, x)
        out.append('0' if s == '-0' else s)
    return ' '.join(out)


def quat_attr(q, digits=15):
    """' quat="w x y z"' for a unit quaternion, w >= 0 (q and -q are the same rotation); '' for the identity,
    MJCF's default, so that unrotated frames carry no attribute."""
    if abs(q[0] - 1.0) < 1e-15:
        return ''
    if q[0] < 0:
        q = [-c for c in q]
    return ' quat="%s"' % fmt(q, digits)


# ---------------------------------------------------------------- MJCF pieces the models share
def xml_comment(indent, lines):
    """An XML comment over one or more lines, indented by `indent`, continuation lines aligned with the text."""
    pad = ' ' * indent
    out = [pad + '<!-- ' + lines[0]] + [pad + '     ' + line for line in lines[1:]]
    out[-1] += ' -->'
    return out


# Angles in radians, inertias as written (never computed from the geoms), ranges imply limited="true".
COMPILER_XML = '  <compiler angle="radian" inertiafromgeom="false" autolimits="true"/>'

# Visual shapes: massless and colliding with nothing (group 1, hidden in MuJoCo's collision view).
VISUAL_CLASS_XML = ['    <default class="visual">',
                    '      <geom contype="0" conaffinity="0" group="1" mass="0"/>',
                    '    </default>']


def contact_class_xml(name, look, *comment):
    """Default class of the geoms that touch the environment (wheels, feet): contype 1 against the
    environment's conaffinity 1, so they collide with it only; the same friction and contact softness in
    every model. `look`: its material or rgba attribute; `comment`: the lines of the class's XML comment."""
    return (['    <default class="%s">' % name] + xml_comment(6, comment) +
            ['      <geom contype="1" conaffinity="0" condim="3" friction="1.0 0.005 0.0001" solref="0.005 1"'
             ' solimp="0.9 0.95 0.001" group="0" %s/>' % look,
             '    </default>'])


def hinge_xml(name, axis, rng, armature, vel):
    """A hinge with its velocity limit [rad/s] in `user` (nuser_jnt="1"); rng None (a wheel) is written
    explicitly unlimited."""
    limits = 'limited="false"' if rng is None else 'range="%s"' % fmt(rng)
    return '<joint name="%s" axis="%s" %s armature="%g" user="%g"/>' % (name, fmt(axis), limits, armature, vel)


def actuator_xml(efforts):
    """One torque motor per (joint, effort limit [N m]), named as its joint, control clamped to +-effort."""
    o = ['  <actuator>']
    for joint, effort in efforts:
        o.append('    <motor name="%s" joint="%s" gear="1" ctrllimited="true" ctrlrange="%s"/>'
                 % (joint, joint, fmt([-effort, effort])))
    return o + ['  </actuator>']


# Orientation, angular velocity and linear acceleration of the site "imu" (the state estimator's inputs).
IMU_SENSOR_XML = ['  <sensor>',
                  '    <framequat name="imu_quat" objtype="site" objname="imu"/>',
                  '    <gyro name="imu_gyro" site="imu"/>',
                  '    <accelerometer name="imu_acc" site="imu"/>',
                  '  </sensor>']


def home_keyframe_xml(comment, base_z, hinge_q, z_digits=10, q_digits=10):
    """Keyframe "home": the free joint at (0, 0, base_z), level, then the hinge angles in joint order."""
    return (['  <keyframe>'] + xml_comment(4, [comment]) +
            ['    <key name="home" qpos="0 0 %s 1 0 0 0 %s"/>' % (fmt([base_z], z_digits), fmt(hinge_q, q_digits)),
             '  </keyframe>'])


# ---------------------------------------------------------------- command line
def parse_args(script, doc, default_out):
    """--out (default: `default_out`, relative to the repository root above the script's folder), --check."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    root = os.path.join(os.path.dirname(os.path.abspath(script)), '..')
    ap.add_argument('--out', default=os.path.join(root, default_out))
    ap.add_argument('--check', action='store_true',
                    help='regenerate in memory, print the model facts, fail if the file at --out differs')
    return ap.parse_args()


def check_file(text, path, script):
    """0 if the file at `path` holds exactly `text`, else 1 with the reason on stderr."""
    shown = os.path.normpath(path)
    try:
        with open(path) as f:
            same = f.read() == text
    except OSError as e:
        print('%s: cannot read (%s)' % (shown, e.strerror), file=sys.stderr)
        return 1
    if not same:
        print('%s: DIFFERS from the generator output; rewrite it with python3 tools/%s'
              % (shown, os.path.basename(script)), file=sys.stderr)
        return 1
    print('%s: up to date' % shown)
    return 0


def write_file(text, path):
    """Write through a temporary file and a rename, so that a reader never sees half a model."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        f.write(text)
    os.replace(tmp, path)
    print('wrote', os.path.normpath(path))


def main(script, doc, default_out, generate, print_facts):
    """A generator's command line: `script` its __file__, `doc` its docstring (first line = description),
    `generate()` the MJCF text, `print_facts()` the model facts printed by --check. Returns the exit code."""
    args = parse_args(script, doc, default_out)
    text = generate()
    if not args.check:
        write_file(text, args.out)
        return 0
    print_facts()
    return check_file(text, args.out, script)
