#!/usr/bin/env python3
"""Writes the UR5's numbers as a C++ header from models/ur5/ur5.urdf, the one description of the arm.

The build runs it (robot/CMakeLists.txt) so that the D-H table, the links' masses, centres of mass and
inertias, the joints' limits and the arm's collision envelope in code are the URDF's: edit the URDF,
not the header.

    ur5_urdf_header.py URDF OUT_HEADER

The URDF must be in D-H form (see its header comment): six revolute joints shoulder_pan .. wrist_3 and a
fixed flange_joint, each joint i+1 at (a_i, 0, d_i) with rpy (alpha_i, 0, 0) in its parent link, and
diagonal link inertias; its <collision> elements are cylinders. Anything else is refused with a message
naming the URDF and the element, exit 1.
"""
import math
import sys
import xml.etree.ElementTree as ET

JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint",
          "wrist_3_joint"]
LINKS = ["shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "wrist_3_link"]


def fail(urdf, what):
    sys.exit(f"ur5_urdf_header: '{urdf}': {what}")


def numbers(urdf, element, attribute, count, default=None):
    text = element.get(attribute, default)
    try:
        values = [float(v) for v in text.split()]
    except (AttributeError, ValueError):
        fail(urdf, f"<{element.tag}> {attribute}: expected {count} numbers, found {text!r}")
    if len(values) != count:
        fail(urdf, f"<{element.tag}> {attribute}: expected {count} numbers, found {text!r}")
    return values


def find(urdf, root, tag, name):
    for element in root.findall(tag):
        if element.get("name") == name:
            return element
    fail(urdf, f"no <{tag} name=\"{name}\">")


def dh_rows(urdf, root):
    """(d, a, alpha) of each D-H row from the origin of the joint after it (the flange's for the last)."""
    rows = []
    for name in JOINTS[1:] + ["flange_joint"]:
        origin = find(urdf, root, "joint", name).find("origin")
        if origin is None:
            fail(urdf, f"joint {name}: no <origin>")
        x, y, z = numbers(urdf, origin, "xyz", 3, "0 0 0")
        roll, pitch, yaw = numbers(urdf, origin, "rpy", 3, "0 0 0")
        if y != 0 or pitch != 0 or yaw != 0:
            fail(urdf, f"joint {name}: origin is not in D-H form (y, pitch and yaw must be 0)")
        rows.append((z, x, roll))
    return rows


def link_inertials(urdf, root):
    inertials = []
    for name in LINKS:
        inertial = find(urdf, root, "link", name).find("inertial")
        if inertial is None or inertial.find("mass") is None or inertial.find("inertia") is None:
            fail(urdf, f"link {name}: no <inertial> with <mass> and <inertia>")
        origin = inertial.find("origin")
        com = numbers(urdf, origin, "xyz", 3, "0 0 0") if origin is not None else [0.0, 0.0, 0.0]
        if origin is not None and numbers(urdf, origin, "rpy", 3, "0 0 0") != [0.0, 0.0, 0.0]:
            fail(urdf, f"link {name}: the inertial frame must not be turned (rpy 0 0 0)")
        inertia = inertial.find("inertia")
        if any(float(inertia.get(k, "0")) != 0 for k in ("ixy", "ixz", "iyz")):
            fail(urdf, f"link {name}: the inertia must be diagonal")
        diagonal = [float(inertia.get(k)) for k in ("ixx", "iyy", "izz")]
        inertials.append((numbers(urdf, inertial.find("mass"), "value", 1)[0], com, diagonal))
    return inertials


def joint_limits(urdf, root):
    limits = []
    for name in JOINTS:
        joint = find(urdf, root, "joint", name)
        limit = joint.find("limit")
        if joint.get("type") != "revolute" or limit is None:
            fail(urdf, f"joint {name}: expected a revolute joint with a <limit>")
        limits.append([numbers(urdf, limit, key, 1)[0] for key in ("lower", "upper", "effort", "velocity")])
    return limits


def rpy_matrix(roll, pitch, yaw):
    """URDF's fixed-axis roll, pitch, yaw: Rz(yaw) Ry(pitch) Rx(roll), as rows."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def clean(x):
    # Rounded to 1e-12 m: the turns by pi/2 leave 1e-17 crumbs that are not the URDF's numbers.
    return round(x, 12) + 0.0


def collision_capsules(urdf, root, rows):
    """Each <collision> cylinder of base_link .. wrist_3_link as (D-H frame, end a, end b, radius), its
    ends in D-H frame i: link i's frame is D-H frame i-1 turned by joint i, so a point p of link i
    lies at Rx(alpha_i)^T (p - (a_i, 0, d_i)) in frame i (base_link is frame 0)."""
    capsules = []
    for frame, name in enumerate(["base_link"] + LINKS):
        for collision in find(urdf, root, "link", name).findall("collision"):
            cylinder = collision.find("geometry/cylinder")
            if cylinder is None:
                fail(urdf, f"link {name}: <collision> must be a <cylinder> "
                           "(it stands for the capsule around it)")
            origin = collision.find("origin")
            xyz = numbers(urdf, origin, "xyz", 3, "0 0 0") if origin is not None else [0.0, 0.0, 0.0]
            rpy = numbers(urdf, origin, "rpy", 3, "0 0 0") if origin is not None else [0.0, 0.0, 0.0]
            half = 0.5 * numbers(urdf, cylinder, "length", 1)[0]
            axis = [row[2] for row in rpy_matrix(*rpy)]
            ends = []
            for sign in (1, -1):
                p = [xyz[k] + sign * half * axis[k] for k in range(3)]
                if frame > 0:
                    d, a, alpha = rows[frame - 1]
                    p = [p[0] - a, p[1], p[2] - d]
                    c, s = math.cos(alpha), math.sin(alpha)
                    p = [p[0], c * p[1] + s * p[2], -s * p[1] + c * p[2]]
                ends.append([clean(v) for v in p])
            capsules.append((frame, ends[0], ends[1], numbers(urdf, cylinder, "radius", 1)[0]))
    if not capsules:
        fail(urdf, "no <collision> element: the arm's envelope is its links' collision cylinders")
    return capsules


def array(values):
    # repr(): the shortest text that reads back as the same double, so the code's numbers are the URDF's.
    return "{" + ", ".join(repr(v) if not isinstance(v, list) else array(v) for v in values) + "}"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: ur5_urdf_header.py URDF OUT_HEADER")
    urdf, out = sys.argv[1], sys.argv[2]
    try:
        root = ET.parse(urdf).getroot()
    except (OSError, ET.ParseError) as e:
        fail(urdf, f"cannot read it as XML ({e})")
    rows, inertials, limits = dh_rows(urdf, root), link_inertials(urdf, root), joint_limits(urdf, root)
    capsules = collision_capsules(urdf, root, rows)
    capsule_rows = ",\n    ".join(f"{{{f}, {array(a)}, {array(b)}, {r!r}}}" for f, a, b, r in capsules)
    text = f"""// Generated at build time from models/ur5/ur5.urdf by models/tools/ur5_urdf_header.py: edit the URDF.
#pragma once

namespace sortcell::robot::ur5_urdf {{

/// The D-H rows read from the joints' origins (joint i+1, the flange for the last, at (a_i, 0, d_i) with
/// rpy (alpha_i, 0, 0)): d (m), a (m), alpha (rad).
inline constexpr double kDhD[6] = {array([r[0] for r in rows])};
inline constexpr double kDhA[6] = {array([r[1] for r in rows])};
inline constexpr double kDhAlpha[6] = {array([r[2] for r in rows])};

/// The moving links (shoulder_link .. wrist_3_link): mass (kg), centre of mass in the link frame (m),
/// diagonal of the inertia about it (kg m^2).
inline constexpr double kLinkMass[6] = {array([i[0] for i in inertials])};
inline constexpr double kLinkCom[6][3] = {array([i[1] for i in inertials])};
inline constexpr double kLinkInertia[6][3] = {array([i[2] for i in inertials])};

/// The joints' limits: position (rad), effort (N m), velocity (rad/s).
inline constexpr double kJointLower[6] = {array([l[0] for l in limits])};
inline constexpr double kJointUpper[6] = {array([l[1] for l in limits])};
inline constexpr double kJointEffort[6] = {array([l[2] for l in limits])};
inline constexpr double kJointVelocity[6] = {array([l[3] for l in limits])};

/// The arm's collision envelope: each <collision> cylinder of the links, standing for the capsule
/// around it, as its D-H frame (0 = base_link .. 6), its axis' ends in that frame (m) and its radius (m).
struct CollisionCapsule {{
  int frame;
  double a[3];
  double b[3];
  double radius;
}};
inline constexpr CollisionCapsule kCollisionCapsules[] = {{
    {capsule_rows}}};

}}  // namespace sortcell::robot::ur5_urdf
"""
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
