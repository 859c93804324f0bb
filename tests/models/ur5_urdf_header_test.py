#!/usr/bin/env python3
"""models/tools/ur5_urdf_header.py: the shipped URDF gives a header with its collision capsules in their
D-H frames, and URDFs the code cannot read its numbers from are refused with a message naming the file
and the element, exit 1.

    ur5_urdf_header_test.py SOURCE_ROOT
"""
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(sys.argv[1])
TOOL = ROOT / "models/tools/ur5_urdf_header.py"
URDF = (ROOT / "models/ur5/ur5.urdf").read_text()
failures = []


def run(urdf_text, folder):
    urdf = folder / "arm.urdf"
    urdf.write_text(urdf_text)
    out = folder / "ur5_urdf.h"
    result = subprocess.run([sys.executable, str(TOOL), str(urdf), str(out)], capture_output=True, text=True)
    return result, out, urdf


def expect(condition, what):
    if not condition:
        failures.append(what)


def check_shipped(folder):
    result, out, _ = run(URDF, folder)
    expect(result.returncode == 0, f"the shipped URDF was refused: {result.stderr.strip()}")
    if result.returncode != 0:
        return
    header = out.read_text()
    rows = re.findall(r"\{(\d), \{([^}]*)\}, \{([^}]*)\}, ([0-9.e-]+)\}", header)
    expect(len(rows) == URDF.count("<collision name="), f"one capsule per <collision>: found {len(rows)}")
    # The upper arm's capsule in D-H frame 2 (at the elbow): from the shoulder (x = -a2) to the elbow,
    # 0.136 m along the joint axes, as cell/arm_view.cc's hand-written list had it.
    expect(("2", "0.425, 0.0, 0.136", "0.0, 0.0, 0.136", "0.06") in rows, f"the upper arm's capsule: {rows}")
    # The wrist capsules, through the turns by alpha: wrist 1 from frame 4's origin back along z3 (= +y4)
    # to 0.03 m before frame 3's origin (d4 + 0.03 = 0.13915); wrist 2 from frame 5's origin to frame
    # 4's, d5 along z4 (= -y5); wrist 3 from the flange (frame 6's origin) back to frame 5's, d6.
    expect(("4", "0.0, 0.0, 0.0", "0.0, -0.13915, 0.0", "0.045") in rows, f"the wrist-1 capsule: {rows}")
    expect(("5", "0.0, 0.0, 0.0", "0.0, 0.09465, 0.0", "0.045") in rows, f"the wrist-2 capsule: {rows}")
    expect(("6", "0.0, 0.0, 0.0", "0.0, 0.0, -0.0823", "0.045") in rows, f"the wrist-3 capsule: {rows}")


def check_refused(folder, name, text, message):
    result, _, urdf = run(text, folder)
    expect(result.returncode == 1, f"{name}: exit {result.returncode}, expected 1")
    expect(str(urdf) in result.stderr and message in result.stderr,
           f"{name}: expected a message naming {urdf} and saying {message!r}, got {result.stderr.strip()!r}")
    expect(result.stderr.count("\n") <= 1, f"{name}: expected one line, got {result.stderr!r}")


def main():
    collision_box = URDF.replace('<geometry><cylinder radius="0.045" length="0.0823"/>',
                                 '<geometry><box size="0.1 0.1 0.1"/>', 1)
    assert collision_box != URDF, "the test's edit no longer matches models/ur5/ur5.urdf"
    turned_joint = URDF.replace('<origin xyz="-0.425 0 0" rpy="0 0 0"/>',
                                '<origin xyz="-0.425 0.01 0" rpy="0 0 0"/>', 1)
    assert turned_joint != URDF, "the test's edit no longer matches models/ur5/ur5.urdf"
    off_diagonal = URDF.replace('ixx="0.0151" ixy="0"', 'ixx="0.0151" ixy="0.001"', 1)
    assert off_diagonal != URDF, "the test's edit no longer matches models/ur5/ur5.urdf"
    with tempfile.TemporaryDirectory(prefix="ur5_urdf_header_test_") as tmp:
        folder = pathlib.Path(tmp)
        check_shipped(folder)
        check_refused(folder, "a box collision", collision_box,
                      "link wrist_3_link: <collision> must be a <cylinder>")
        check_refused(folder, "a joint off the D-H line", turned_joint,
                      "joint elbow_joint: origin is not in D-H form")
        check_refused(folder, "an off-diagonal inertia", off_diagonal,
                      "link upper_arm_link: the inertia must be diagonal")
        check_refused(folder, "not XML", "<robot", "cannot read it as XML")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
