#!/usr/bin/env python3
"""Generate models/centauro/centauro.xml (MJCF for MuJoCo 2.2.2) for the paper-era CENTAURO robot.

The numeric tables below were typed in once from the reference model facts
(/work/shared/reference/centauro/MODEL.md and the paper-era URDF it describes, commit de6896b minus head:
39 actuated joints, 93.113 kg). This script never reads the URDF; the committed XML is the artifact.

Usage:  python3 tools/gen_centauro_mjcf.py [--out models/centauro/centauro.xml] [--check]
  --check regenerates in memory, prints mass, CoM and wheel centres, fails (exit 1) if the file at --out differs.
Pure python3 standard library (helpers shared with the other generators: tools/mjcf_gen.py).
See docs/model.md for conventions and what differs from the URDF.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # mjcf_gen.py, from any working directory
sys.dont_write_bytecode = True  # no tools/__pycache__ left in the work tree
from mjcf_gen import (COMPILER_XML, IMU_SENSOR_XML, VISUAL_CLASS_XML, actuator_xml,  # noqa: E402
                      contact_class_xml, fmt, hinge_xml, home_keyframe_xml, identity, main, mmul, mvec,
                      quat_attr, vadd)

PI = math.pi

# (link, parent link, joint, joint type, origin xyz [m], origin rpy [rad] (URDF fixed-axis roll-pitch-yaw),
#  axis, (lower, upper, velocity [rad/s], effort [Nm]) or None, (mass [kg], CoM xyz [m],
#  [ixx, ixy, ixz, iyy, iyz, izz] [kg m^2] about the CoM in link axes) or None)
PELVIS_INERTIAL = (16.097574, [0.0013890071, -0.0015989148, 0.063101012],
                   [0.23912627, -0.0050541269, -0.019746055, 0.71430078, 0.0002131204, 0.81870448])
LINKS = [
    ('imu_link', 'pelvis', 'imu_joint', 'fixed', [0.248316, 0.0, 0.015], [0.0, 0.0, 0.0], None, None, None),
    ('base_link', 'pelvis', 'base_joint', 'fixed', [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], None, None, None),
    ('torso_2', 'pelvis', 'torso_yaw', 'revolute', [0.2, 0.0, 0.256], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.618, 2.618, 5.7, 147.0), (11.492689, [-0.019497794, 0.0045317835, 0.13768283], [0.063643392, 8.939e-05, -0.00086873, 0.02680235, -4.657e-05, 0.04743015])),
    ('arm1_1', 'torso_2', 'j_arm1_1', 'revolute', [0.0457475, 0.169137, 0.116626], [0.174533, 0.0, -0.5235988], [0.0, 1.0, 0.0], (-3.312, 1.615, 3.86, 147.0), (1.9628675, [-0.0074457212, 0.03410796, 0.00010978102], [0.0053547717, 0.00036428926, 1.5089568e-05, 0.0033923328, 5.5692312e-05, 0.0068921413])),
    ('arm1_2', 'arm1_1', 'j_arm1_2', 'revolute', [-0.09015, 0.062, 0.0], [-0.1745327, 0.0, 0.0], [1.0, 0.0, 0.0], (0.02, 3.431, 3.86, 147.0), (1.8595811, [0.058142302, 5.7450803e-05, -0.077477683], [0.013776643, 3.7788675e-05, 0.0037690171, 0.015677464, -9.4893549e-06, 0.0046317657])),
    ('arm1_3', 'arm1_2', 'j_arm1_3', 'revolute', [0.09015, 0.0, -0.21815], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.552, 2.566, 6.06, 147.0), (1.6678109, [0.014625194, 0.0008172672, -0.028333545], [0.0064480435, -0.00015639093, 0.0012205359, 0.0073372077, 8.9941532e-05, 0.0036738448])),
    ('arm1_4', 'arm1_3', 'j_arm1_4', 'revolute', [0.045, 0.05515, -0.074], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], (-2.465, 0.28, 6.06, 147.0), (1.3157289, [-0.0076833067, -0.040302205, -0.043492779], [0.004330394, -0.00011737391, -0.00041923199, 0.0038539919, -0.00079573038, 0.0017594689])),
    ('arm1_5', 'arm1_4', 'j_arm1_5', 'revolute', [-0.015, -0.05515, -0.095], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.569, 2.562, 11.72, 55.0), (1.4908547, [-0.00011079615, 0.011590836, -0.07816026], [0.0085692128, 1.7856252e-05, 1.9379365e-05, 0.0077454159, -0.00032860094, 0.0027441921])),
    ('arm1_6', 'arm1_5', 'j_arm1_6', 'revolute', [0.0, 0.049, -0.156], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], (-1.529, 1.509, 11.72, 55.0), (1.1263612, [-4.6502396e-06, -0.038014094, -0.069926878], [0.0051871784, 2.724437e-05, 2.2833496e-06, 0.0048037789, -0.00072165653, 0.0012771388])),
    ('arm1_7', 'arm1_6', 'j_arm1_7', 'revolute', [0.0, -0.049, -0.174], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.565, 2.569, 20.35, 28.32), (0.27966428, [0.0, 0.0, 0.03127057], [0.00014415192, 9.8651826e-08, 0.0, 0.0001441701, 0.0, 6.0500616e-05])),
    ('ft_arm1', 'arm1_7', 'j_ft_1', 'fixed', [0.0, 0.0, -0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], None, (0.37827821, [8.2161929e-05, 0.0026334189, -0.016465877], [0.00023321716, 2.3681435e-06, -1.8039102e-06, 0.00020626291, 3.158829e-05, 0.00027399881])),
    ('arm2_1', 'torso_2', 'j_arm2_1', 'revolute', [0.0457475, -0.169137, 0.116626], [-0.174533, 0.0, 0.5235988], [0.0, 1.0, 0.0], (-3.3458, 1.6012, 3.86, 147.0), (1.9628675, [-0.0074457212, -0.03410796, 0.00010978102], [0.0053547717, -0.00036428926, 1.5089568e-05, 0.0033923328, -5.5692312e-05, 0.0068921413])),
    ('arm2_2', 'arm2_1', 'j_arm2_2', 'revolute', [-0.09015, -0.062, 0.0], [0.1745327, 0.0, 0.0], [1.0, 0.0, 0.0], (-3.4258, -0.0138, 3.86, 147.0), (1.8595811, [0.058142302, -5.7450803e-05, -0.077477683], [0.013776643, -3.7788675e-05, 0.0037690171, 0.015677464, 9.4893549e-06, 0.0046317657])),
    ('arm2_3', 'arm2_2', 'j_arm2_3', 'revolute', [0.09015, 0.0, -0.21815], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.5614, 2.5606, 6.06, 147.0), (1.6678109, [0.014625194, -0.0008172672, -0.028333545], [0.0064480435, 0.00015639093, 0.0012205359, 0.0073372077, -8.9941532e-05, 0.0036738448])),
    ('arm2_4', 'arm2_3', 'j_arm2_4', 'revolute', [0.045, -0.05515, -0.074], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], (-2.4794, 0.2886, 6.06, 147.0), (1.3157289, [-0.0076833067, 0.040302205, -0.043492779], [0.004330394, 0.00011737391, -0.00041923199, 0.0038539919, 0.00079573038, 0.0017594689])),
    ('arm2_5', 'arm2_4', 'j_arm2_5', 'revolute', [-0.015, 0.05515, -0.095], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.5394, 2.5546, 11.72, 55.0), (1.4908547, [-0.00011079615, -0.011590836, -0.07816026], [0.0085692128, -1.7856252e-05, 1.9379365e-05, 0.0077454159, 0.00032860094, 0.0027441921])),
    ('arm2_6', 'arm2_5', 'j_arm2_6', 'revolute', [0.0, -0.049, -0.156], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], (-1.5154, 1.5156, 11.72, 55.0), (1.1263612, [-4.6502396e-06, 0.038014094, -0.069926878], [0.0051871784, -2.724437e-05, 2.2833496e-06, 0.0048037789, 0.00072165653, 0.0012771388])),
    ('arm2_7', 'arm2_6', 'j_arm2_7', 'revolute', [0.0, 0.049, -0.174], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.5554, 2.5686, 20.35, 28.32), (0.27966428, [0.0, -0.0, 0.03127057], [0.00014415192, -9.8651826e-08, 0.0, 0.0001441701, 0.0, 6.0500616e-05])),
    ('ft_arm2', 'arm2_7', 'j_ft_2', 'fixed', [0.0, 0.0, -0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], None, (0.37827821, [8.2161929e-05, -0.0026334189, -0.016465877], [0.00023321716, -2.3681435e-06, -1.8039102e-06, 0.00020626291, -3.158829e-05, 0.00027399881])),
    ('ball1', 'arm1_7', 'j_arm1_8', 'fixed', [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], None, None, (1.27, [-1.0072498e-05, 3.7590658e-05, 0.019772332], [0.0023061092, 2.9181758e-07, -2.1246683999999997e-07, 0.0023053155000000002, 7.9290978e-07, 0.0030675615999999997])),
    ('ball1_tip', 'ball1', 'j_ball1_tip', 'fixed', [0.0, 0.0, -0.07], [0.0, 0.0, 0.0], None, None, None),
    ('arm1_8', 'ball1', 'j_ball1_fixed', 'fixed', [0, 0, 0], [0, 0, 0], None, None, None),
    ('ball2', 'arm2_7', 'j_arm2_8', 'fixed', [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], None, None, (1.27, [-1.0072498e-05, 3.7590658e-05, 0.019772332], [0.0023061092, 2.9181758e-07, -2.1246683999999997e-07, 0.0023053155000000002, 7.9290978e-07, 0.0030675615999999997])),
    ('ball2_tip', 'ball2', 'j_ball2_tip', 'fixed', [0.0, 0.0, -0.07], [0.0, 0.0, 0.0], None, None, None),
    ('arm2_8', 'ball2', 'j_ball2_fixed', 'fixed', [0, 0, 0], [0, 0, 0], None, None, None),
    ('hip1_1', 'pelvis', 'hip_yaw_1', 'revolute', [0.25, 0.125, -0.0566], [3.141592653589793, 0.0, 0.461416123228], [0.0, 0.0, 1.0], (-2.03, 2.51, 8.8, 304.0), (1.9194403, [0.010214199, -0.018348359, 0.038090987], [0.0047439572, 0.0005747047, -0.0003784138, 0.0040551878, 0.0007407508, 0.0034146219])),
    ('hip2_1', 'hip1_1', 'hip_pitch_1', 'revolute', [0.0, 0.0, 0.0625], [1.57079632679, 0.0, 0.46141612323000025], [0.0, 0.0, 1.0], (-2.0226, 2.02748, 8.8, 304.0), (2.7264471, [2.57966e-05, 0.1810266, 0.085669756], [0.04851869, -4.11894e-05, -1.68778e-05, 0.004242055, 0.0032243188, 0.04825583])),
    ('knee_1', 'hip2_1', 'knee_pitch_1', 'revolute', [0.0, 0.3, -0.0036], [3.14159265358979, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.4056, 2.3994, 8.8, 304.0), (1.9356754, [0.10881667, 0.0001089081, -0.022638996], [0.0030534242, -4.22079e-05, 0.0013679297, 0.019603321, 6.9941e-06, 0.019849817])),
    ('ankle1_1', 'knee_1', 'ankle_pitch_1', 'revolute', [0.2, 0.0, -0.10015], [3.141592653589793, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.4056, 2.3184, 8.1, 147.0), (1.2380744, [0.032137318, 9.73572e-05, -0.0044222206], [0.0015610452, 3.30597e-05, -0.0001314174, 0.0037423211, -2.12589e-05, 0.0038312442])),
    ('ankle2_1', 'ankle1_1', 'ankle_yaw_1', 'revolute', [0.0, 0.0, 0.0], [1.5707963267948966, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.5626, 2.5384, 20.0, 35.0), (1.1565926, [0.0004435803, 0.0004389911, 0.19392092], [0.0049019475, 4.3032e-06, 3.46491e-05, 0.0038724162, 1.7099e-05, 0.0021783198])),
    ('wheel_1', 'ankle2_1', 'j_wheel_1', 'continuous', [0.0, 0.00085, 0.23735], [1.5707963267948966, 0.0, 3.14159265359], [0.0, 0.0, 1.0], (None, None, 20.0, 35.0), (1.7289003, [0.0, 0.0, 0.0024271906], [0.0046864297, 0.0, 0.0, 0.0046713489, 0.0, 0.0053126029])),
    ('hip1_2', 'pelvis', 'hip_yaw_2', 'revolute', [0.25, -0.125, -0.0566], [3.141592653589793, 0.0, -0.461416123228], [0.0, 0.0, 1.0], (-2.51, 2.03, 8.8, 304.0), (1.9194403, [0.010214199, 0.018348359, 0.038090987], [0.0047439572, -0.0005747047, -0.0003784138, 0.0040551878, -0.0007407508, 0.0034146219])),
    ('hip2_2', 'hip1_2', 'hip_pitch_2', 'revolute', [0.0, 0.0, 0.0625], [1.57079632679, 0.0, 2.68017653036], [0.0, 0.0, 1.0], (-2.0156, 2.0354, 8.8, 304.0), (2.7264471, [2.57966e-05, 0.1810266, 0.085669756], [0.04851869, -4.11894e-05, -1.68778e-05, 0.004242055, 0.0032243188, 0.04825583])),
    ('knee_2', 'hip2_2', 'knee_pitch_2', 'revolute', [0.0, 0.3, -0.0036], [3.14159265358979, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.4006, 2.4034, 8.8, 304.0), (1.9356754, [0.10881667, 0.0001089081, -0.022638996], [0.0030534242, -4.22079e-05, 0.0013679297, 0.019603321, 6.9941e-06, 0.019849817])),
    ('ankle1_2', 'knee_2', 'ankle_pitch_2', 'revolute', [0.2, 0.0, -0.10015], [3.141592653589793, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.3266, 2.3914, 8.1, 147.0), (1.2380744, [0.032137318, 9.73572e-05, -0.0044222206], [0.0015610452, 3.30597e-05, -0.0001314174, 0.0037423211, -2.12589e-05, 0.0038312442])),
    ('ankle2_2', 'ankle1_2', 'ankle_yaw_2', 'revolute', [0.0, 0.0, 0.0], [1.5707963267948966, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.5546, 2.5484, 20.0, 35.0), (1.1565926, [0.0004435803, 0.0004389911, 0.19392092], [0.0049019475, 4.3032e-06, 3.46491e-05, 0.0038724162, 1.7099e-05, 0.0021783198])),
    ('wheel_2', 'ankle2_2', 'j_wheel_2', 'continuous', [0.0, 0.00085, 0.23735], [1.5707963267948966, 0.0, 3.14159265359], [0.0, 0.0, 1.0], (None, None, 20.0, 35.0), (1.7289003, [0.0, 0.0, 0.0024271906], [0.0046864297, 0.0, 0.0, 0.0046713489, 0.0, 0.0053126029])),
    ('hip1_3', 'pelvis', 'hip_yaw_3', 'revolute', [-0.25, 0.125, -0.0566], [3.141592653589793, 0.0, 2.680176530362], [0.0, 0.0, 1.0], (-2.51, 2.03, 8.8, 304.0), (1.9194403, [0.010214199, 0.018348359, 0.038090987], [0.0047439572, -0.0005747047, -0.0003784138, 0.0040551878, -0.0007407508, 0.0034146219])),
    ('hip2_3', 'hip1_3', 'hip_pitch_3', 'revolute', [0.0, 0.0, 0.0625], [1.57079632679, 0.0, 2.68017653036], [0.0, 0.0, 1.0], (-2.0126, 2.0384, 8.8, 304.0), (2.7264471, [2.57966e-05, 0.1810266, 0.085669756], [0.04851869, -4.11894e-05, -1.68778e-05, 0.004242055, 0.0032243188, 0.04825583])),
    ('knee_3', 'hip2_3', 'knee_pitch_3', 'revolute', [0.0, 0.3, -0.0036], [3.14159265358979, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.4056, 2.4064, 8.8, 304.0), (1.9356754, [0.10881667, 0.0001089081, -0.022638996], [0.0030534242, -4.22079e-05, 0.0013679297, 0.019603321, 6.9941e-06, 0.019849817])),
    ('ankle1_3', 'knee_3', 'ankle_pitch_3', 'revolute', [0.2, 0.0, -0.10015], [3.141592653589793, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.4696, 2.4464, 8.1, 147.0), (1.2380744, [0.032137318, 9.73572e-05, -0.0044222206], [0.0015610452, 3.30597e-05, -0.0001314174, 0.0037423211, -2.12589e-05, 0.0038312442])),
    ('ankle2_3', 'ankle1_3', 'ankle_yaw_3', 'revolute', [0.0, 0.0, 0.0], [1.5707963267948966, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.5606, 2.5454, 20.0, 35.0), (1.1565926, [0.0004435803, 0.0004389911, 0.19392092], [0.0049019475, 4.3032e-06, 3.46491e-05, 0.0038724162, 1.7099e-05, 0.0021783198])),
    ('wheel_3', 'ankle2_3', 'j_wheel_3', 'continuous', [0.0, 0.00085, 0.23735], [1.5707963267948966, 0.0, 3.14159265359], [0.0, 0.0, 1.0], (None, None, 20.0, 35.0), (1.7289003, [0.0, 0.0, 0.0024271906], [0.0046864297, 0.0, 0.0, 0.0046713489, 0.0, 0.0053126029])),
    ('hip1_4', 'pelvis', 'hip_yaw_4', 'revolute', [-0.25, -0.125, -0.0566], [3.141592653589793, 0.0, 3.603008776818], [0.0, 0.0, 1.0], (-2.03, 2.51, 8.8, 304.0), (1.9194403, [0.010214199, -0.018348359, 0.038090987], [0.0047439572, 0.0005747047, -0.0003784138, 0.0040551878, 0.0007407508, 0.0034146219])),
    ('hip2_4', 'hip1_4', 'hip_pitch_4', 'revolute', [0.0, 0.0, 0.0625], [1.57079632679, 0.0, 0.46141612323000025], [0.0, 0.0, 1.0], (-2.0326, 2.0524, 8.8, 304.0), (2.7264471, [2.57966e-05, 0.1810266, 0.085669756], [0.04851869, -4.11894e-05, -1.68778e-05, 0.004242055, 0.0032243188, 0.04825583])),
    ('knee_4', 'hip2_4', 'knee_pitch_4', 'revolute', [0.0, 0.3, -0.0036], [3.14159265358979, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.4176, 2.3884, 8.8, 304.0), (1.9356754, [0.10881667, 0.0001089081, -0.022638996], [0.0030534242, -4.22079e-05, 0.0013679297, 0.019603321, 6.9941e-06, 0.019849817])),
    ('ankle1_4', 'knee_4', 'ankle_pitch_4', 'revolute', [0.2, 0.0, -0.10015], [3.141592653589793, 0.0, 0.0], [0.0, 0.0, 1.0], (-2.3426, 2.3934, 8.1, 147.0), (1.2380744, [0.032137318, 9.73572e-05, -0.0044222206], [0.0015610452, 3.30597e-05, -0.0001314174, 0.0037423211, -2.12589e-05, 0.0038312442])),
    ('ankle2_4', 'ankle1_4', 'ankle_yaw_4', 'revolute', [0.0, 0.0, 0.0], [1.5707963267948966, 0.0, 1.5707963267948966], [0.0, 0.0, 1.0], (-2.6046, 2.5514, 20.0, 35.0), (1.1565926, [0.0004435803, 0.0004389911, 0.19392092], [0.0049019475, 4.3032e-06, 3.46491e-05, 0.0038724162, 1.7099e-05, 0.0021783198])),
    ('wheel_4', 'ankle2_4', 'j_wheel_4', 'continuous', [0.0, 0.00085, 0.23735], [1.5707963267948966, 0.0, 3.14159265359], [0.0, 0.0, 1.0], (None, None, 20.0, 35.0), (1.7289003, [0.0, 0.0, 0.0024271906], [0.0046864297, 0.0, 0.0, 0.0046713489, 0.0, 0.0053126029])),
]

# SRDF group_state "home" (chains), 39 joints [rad].
HOME = {
    'hip_yaw_1': -0.746874, 'hip_pitch_1': -1.25409, 'knee_pitch_1': -1.55576, 'ankle_pitch_1': -0.301666,
    'ankle_yaw_1': 0.746874, 'hip_yaw_2': 0.746874, 'hip_pitch_2': 1.25409, 'knee_pitch_2': 1.55576,
    'ankle_pitch_2': 0.301666, 'ankle_yaw_2': -0.746874, 'hip_yaw_3': 0.746874, 'hip_pitch_3': 1.25409,
    'knee_pitch_3': 1.55576, 'ankle_pitch_3': 0.301667, 'ankle_yaw_3': -0.746874, 'hip_yaw_4': -0.746874,
    'hip_pitch_4': -1.25409, 'knee_pitch_4': -1.55576, 'ankle_pitch_4': -0.301667, 'ankle_yaw_4': 0.746874,
    'torso_yaw': 0.0, 'j_arm1_1': 0.520149, 'j_arm1_2': 0.320865, 'j_arm1_3': 0.274669, 'j_arm1_4': -2.23604,
    'j_arm1_5': 0.0500815, 'j_arm1_6': -0.781461, 'j_arm1_7': -0.0567608, 'j_arm2_1': 0.520149,
    'j_arm2_2': -0.320865, 'j_arm2_3': -0.274669, 'j_arm2_4': -2.23604, 'j_arm2_5': -0.0500815,
    'j_arm2_6': -0.781461, 'j_arm2_7': 0.0567608,
}

WHEEL_RADIUS = 0.078      # [m] collision cylinder radius (URDF de6896b "fixed wheel radius")
WHEEL_HALF_LENGTH = 0.03  # [m] half of the 0.06 m collision cylinder length
WALL_X = -0.578           # [m] default x of the wall's front face (normal +x), behind the robot
WALL_HALF_THICKNESS = 0.05

# Reflected rotor inertia [kg m^2] added as joint armature, by effort class (see docs/model.md).
ARMATURE = {304.0: 0.05, 147.0: 0.05, 55.0: 0.02, 35.0: 0.01, 28.32: 0.01}

# Massless fixed links kept as sites (frames); other massless fixed links (base_link = pelvis origin,
# arm1_8/arm2_8 = ball origins) are dropped.
SITE_LINKS = {'imu_link', 'ball1_tip', 'ball2_tip'}


# ---------------------------------------------------------------- quaternions and URDF rpy (no numpy)
def qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def qaxis(axis, angle):
    s = math.sin(angle / 2.0)
    return (math.cos(angle / 2.0), axis[0] * s, axis[1] * s, axis[2] * s)


def rpy_to_quat(rpy):
    """URDF rpy = rotations about the FIXED axes X (roll), then Y (pitch), then Z (yaw): R = Rz Ry Rx."""
    r, p, y = rpy
    return qmul(qaxis((0, 0, 1), y), qmul(qaxis((0, 1, 0), p), qaxis((1, 0, 0), r)))


def qmat(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def rpy_mat(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = [[1, 0, 0], [0, cr, -sr], [0, sr, cr]]
    ry = [[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]]
    rz = [[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]
    return mmul(rz, mmul(ry, rx))


# ---------------------------------------------------------------- forward kinematics (for the checks)
def children_of(parent):
    return [row for row in LINKS if row[1] == parent]


def fk(joint_q):
    """Pose (R, p) of every link in the pelvis frame, and total mass and CoM."""
    poses = {'pelvis': (identity(), [0.0, 0.0, 0.0])}
    mass = PELVIS_INERTIAL[0]
    mc = [PELVIS_INERTIAL[0] * c for c in PELVIS_INERTIAL[1]]
    stack = ['pelvis']
    while stack:
        parent = stack.pop()
        for (link, _, joint, jtype, xyz, rpy, axis, _, inertial) in children_of(parent):
            R0, p0 = poses[parent]
            R = mmul(R0, rpy_mat(rpy))
            p = vadd(p0, mvec(R0, xyz))
            if jtype != 'fixed':
                R = mmul(R, qmat(qaxis(axis, joint_q.get(joint, 0.0))))
            poses[link] = (R, p)
            if inertial:
                m, com, _ = inertial
                c = vadd(p, mvec(R, com))
                mass += m
                mc = [mc[i] + m * c[i] for i in range(3)]
            stack.append(link)
    return poses, mass, [x / mass for x in mc]


# ---------------------------------------------------------------- visual shapes (simple, visual only)
GREY = 'light'
def visual_geoms(link, children):
    """Simple visual shapes: pelvis and torso boxes, a capsule from the link origin to each child joint,
    a motor cylinder along each joint axis, a sphere for the ball hands."""
    g = []
    if link == 'pelvis':
        g.append('<geom class="visual" type="box" size="0.30 0.17 0.055" pos="0 0 0.03" material="shell"/>')
        g.append('<geom class="visual" type="box" size="0.12 0.12 0.04" pos="-0.05 0 0.12" material="dark"/>')
    elif link == 'torso_2':
        g.append('<geom class="visual" type="box" size="0.085 0.13 0.13" pos="-0.02 0 0.12" material="shell"/>')
        g.append('<geom class="visual" type="box" size="0.06 0.07 0.055" pos="0.0 0 0.31" material="dark"/>')
    elif link.startswith('ball') and '_' not in link:
        g.append('<geom class="visual" type="sphere" size="0.05" pos="0 0 -0.02" material="dark"/>')
    elif link.startswith('ft_arm'):
        g.append('<geom class="visual" type="cylinder" size="0.035 0.012" pos="0 0 -0.0" material="dark"/>')
    elif link.startswith('wheel_'):
        g.append('<geom class="visual" type="cylinder" size="0.05 0.032" material="shell"/>')
    rad = 0.04 if (link.startswith('hip') or link.startswith('knee') or link.startswith('ankle')) else 0.035
    if link in ('pelvis', 'torso_2'):
        rad = 0.0
    for (child, _, _, jtype, xyz, _, _, _, _) in children:
        if rad > 0 and math.sqrt(sum(c * c for c in xyz)) > 0.02:
            g.append('<geom class="visual" type="capsule" size="%g" fromto="0 0 0 %s" material="limb"/>'
                     % (rad, fmt(xyz, 6)))
    return g


def motor_geom(link, axis):
    big = link.startswith(('hip', 'knee', 'torso')) or link in ('arm1_1', 'arm2_1', 'arm1_2', 'arm2_2')
    r, h = (0.055, 0.045) if big else (0.045, 0.035)
    if link.startswith('wheel_'):
        return None
    a = [c * h for c in axis]
    return ('<geom class="visual" type="cylinder" size="%g" fromto="%s %s" material="dark"/>'
            % (r, fmt([-c for c in a], 6), fmt(a, 6)))


# ---------------------------------------------------------------- MJCF writer
def inertial_xml(inertial):
    m, com, (ixx, ixy, ixz, iyy, iyz, izz) = inertial
    # MJCF fullinertia order: ixx iyy izz ixy ixz iyz
    return '<inertial pos="%s" mass="%s" fullinertia="%s"/>' % (
        fmt(com), fmt([m]), fmt([ixx, iyy, izz, ixy, ixz, iyz]))


def body_xml(link, indent, out):
    pad = ' ' * indent
    kids = children_of(link)
    for g in visual_geoms(link, kids):
        out.append(pad + g)
    for (child, _, joint, jtype, xyz, rpy, axis, lim, inertial) in kids:
        q = rpy_to_quat(rpy)
        if jtype == 'fixed' and inertial is None:
            if child in SITE_LINKS:
                out.append(pad + '<site name="%s" pos="%s"%s/>' % (child, fmt(xyz), quat_attr(q)))
                if child == 'imu_link':
                    out.append(pad + '<site name="imu" pos="%s"%s size="0.01" rgba="1 0.2 0.2 1"/>'
                               % (fmt(xyz), quat_attr(q)))
            continue
        if jtype == 'continuous' and child.startswith('wheel_'):
            # non-spinning wheel-centre frame on the ankle (z = wheel axis)
            out.append(pad + '<site name="wheel_centre_%s" pos="%s"%s/>' % (child[-1], fmt(xyz), quat_attr(q)))
        out.append(pad + '<body name="%s" pos="%s"%s>' % (child, fmt(xyz), quat_attr(q)))
        p2 = pad + '  '
        out.append(p2 + inertial_xml(inertial))
        if jtype != 'fixed':
            lower, upper, vel, effort = lim
            rng = None if jtype == 'continuous' else (lower, upper)
            out.append(p2 + hinge_xml(joint, axis, rng, ARMATURE[effort], vel))
            mg = motor_geom(child, axis)
            if mg:
                out.append(p2 + mg)
        if child.startswith('wheel_'):
            out.append(p2 + '<geom name="%s" class="wheel" type="cylinder" size="%g %g"/>'
                       % (child, WHEEL_RADIUS, WHEEL_HALF_LENGTH))
        body_xml(child, indent + 2, out)
        out.append(pad + '</body>')


def actuated():
    """Hinge joints in MJCF depth-first order (= MuJoCo's joint order)."""
    order = []
    def rec(link):
        for row in children_of(link):
            if row[3] != 'fixed':
                order.append(row)
            rec(row[0])
    rec('pelvis')
    return order


def generate():
    joints = actuated()
    poses, _, _ = fk(HOME)
    wheel_z = [poses['wheel_%d' % k][1][2] for k in range(1, 5)]
    base_z = WHEEL_RADIUS - min(wheel_z)
    o = []
    o.append('<!-- CENTAURO (paper-era model, 39 actuated DoF, 93.113 kg) for MuJoCo 2.2.2.')
    o.append('     GENERATED by tools/gen_centauro_mjcf.py -- edit the generator, not this file.')
    o.append('     Conventions and differences from the URDF: docs/model.md.')
    o.append('     Wall: body "wall" (geom "wall"); its front face (normal +x) is at body_pos.x; a scenario moves')
    o.append('     it by setting model->body_pos[3*id+0] (id = mj_name2id(m, mjOBJ_BODY, "wall")) before stepping. -->')
    o.append('<mujoco model="centauro">')
    o.append(COMPILER_XML)
    # jacobian="sparse": the same contact solution (peak pitches of the jumps agree to 1e-11 deg) ~5 % faster
    # physics than MuJoCo's "auto" (dense below 60 dofs) on this 45-dof tree (docs/sim.md)
    o.append('  <option timestep="0.0005" integrator="Euler" solver="Newton" cone="elliptic" jacobian="sparse"'
             ' iterations="50" tolerance="1e-10" gravity="0 0 -9.81"/>')
    o.append('  <size njmax="500" nconmax="100" nuser_jnt="1"/>')
    o.append('  <visual>')
    o.append('    <global offwidth="1280" offheight="720"/>')
    o.append('    <quality shadowsize="4096"/>')
    o.append('    <headlight ambient="0.3 0.3 0.3" diffuse="0.5 0.5 0.5" specular="0.1 0.1 0.1"/>')
    o.append('  </visual>')
    o.append('  <asset>')
    o.append('    <texture name="grid" type="2d" builtin="checker" rgb1="0.75 0.78 0.8" rgb2="0.6 0.63 0.66"'
             ' width="512" height="512"/>')
    o.append('    <material name="grid" texture="grid" texrepeat="8 8" reflectance="0.05"/>')
    o.append('    <material name="shell" rgba="0.92 0.92 0.9 1"/>')
    o.append('    <material name="limb" rgba="0.75 0.76 0.78 1"/>')
    o.append('    <material name="dark" rgba="0.2 0.2 0.22 1"/>')
    o.append('    <material name="tyre" rgba="0.08 0.08 0.08 1"/>')
    o.append('    <material name="wall" rgba="0.7 0.55 0.4 1"/>')
    o.append('  </asset>')
    o.append('  <default>')
    o.append('    <joint damping="0" frictionloss="0"/>')
    o.append('    <geom contype="0" conaffinity="0"/>')
    o += VISUAL_CLASS_XML
    o += contact_class_xml('wheel', 'material="tyre"',
                           'wheels collide with the environment only (contype 1 & environment conaffinity 1)')
    o.append('    <default class="env">')
    o.append('      <geom contype="0" conaffinity="1" condim="3" friction="1.0 0.005 0.0001"/>')
    o.append('    </default>')
    o.append('  </default>')
    o.append('  <worldbody>')
    o.append('    <light name="sun" directional="true" pos="0 0 5" dir="-0.3 0.4 -1" diffuse="0.7 0.7 0.7"'
             ' castshadow="true"/>')
    o.append('    <geom name="ground" class="env" type="plane" size="20 20 0.1" material="grid"/>')
    o.append('    <body name="wall" pos="%s 0 0">' % fmt([WALL_X]))
    o.append('      <geom name="wall" class="env" type="box" size="%g 1 1" pos="%g 0 1" material="wall"/>'
             % (WALL_HALF_THICKNESS, -WALL_HALF_THICKNESS))
    o.append('    </body>')
    o.append('    <camera name="side" mode="trackcom" pos="0.1 -3.2 0.9" xyaxes="1 0 0 0 0.15 1"/>')
    o.append('    <body name="pelvis" pos="0 0 %s">' % fmt([base_z], 8))
    o.append('      <freejoint name="reference"/>')
    o.append('      ' + inertial_xml(PELVIS_INERTIAL))
    body_xml('pelvis', 6, o)
    o.append('    </body>')
    o.append('  </worldbody>')
    o += actuator_xml((j[2], j[7][3]) for j in joints)
    o += IMU_SENSOR_XML
    o += home_keyframe_xml('SRDF home posture, wheels touching the ground (pelvis z = wheel radius + wheel-centre'
                           ' depth)', base_z, [HOME.get(j[2], 0.0) for j in joints], 8, 8)
    o.append('</mujoco>')
    return '\n'.join(o) + '\n'


def print_facts():
    """Print the model facts the tests assert (mass, wheel centres and CoM in the pelvis frame)."""
    for name, q in (('home', HOME), ('zero', {})):
        poses, mass, com = fk(q)
        print('%s: mass %.4f kg, CoM %s' % (name, mass, fmt(com, 5)))
        for k in range(1, 5):
            R, p = poses['wheel_%d' % k]
            print('  wheel_%d centre %s  axis %s' % (k, fmt(p, 5), fmt([R[i][2] for i in range(3)], 4)))
    print('actuated joints:', len(actuated()))


if __name__ == '__main__':
    sys.exit(main(__file__, __doc__, 'models/centauro/centauro.xml', generate, print_facts))
