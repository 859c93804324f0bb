#!/usr/bin/env python3
"""Writes the UR5's numbers as a C++ header from models/ur5/ur5.urdf, the one description of the arm.

The build runs it (robot/CMakeLists.txt) so that the D-H table, the links' masses, centres of mass and
inertias, and the joints' limits in code are the URDF's: edit the URDF, not the header.

    ur5_urdf_header.py URDF OUT_HEADER

The URDF must be in D-H form (see its header comment): six revolute joints shoulder_pan .. wrist_3 and a
fixed flange_joint, each joint i+1 at (a_i, 0, d_i) with rpy (alpha_i, 0, 0) in its parent link, and
diagonal link inertias. Anything else is refused with a message naming the URDF and the element, exit 1.
"""
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

}}  // namespace sortcell::robot::ur5_urdf
"""
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
