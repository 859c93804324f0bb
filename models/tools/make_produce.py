#!/usr/bin/env python3
"""Writes the produce object models (models/objects/<instance>.inc.xml) and scenes/objects/produce.yaml.

The produce set follows the categories of the public RGB-D dataset used in the paper's experiments
1 and 2: apple, pepper, lemon, lime, orange, peach, pear, plate, potato, tomato. Instances of one
category differ subtly in size, proportions and colour, as real instances do. Every model is built
from MuJoCo primitives (ellipsoids, spheres, cylinders) with a speckled builtin texture, so nothing
needs mesh files. The outputs are committed; rerun this after editing the table below:
    python3 models/tools/make_produce.py
"""
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# name: (category, shape, size, mass kg, base rgb, mark rgb, mark fraction)
#   shape "ellipsoid": size = (rx, ry, rz) semi-axes; "pear": (bottom radius, top radius);
#   "plate": (radius, thickness).
PRODUCE = {
    "apple1": ("apple", "ellipsoid", (0.037, 0.037, 0.034), 0.18, (0.72, 0.10, 0.10), (0.85, 0.70, 0.20), 0.08),
    "apple2": ("apple", "ellipsoid", (0.039, 0.039, 0.036), 0.21, (0.50, 0.06, 0.08), (0.70, 0.15, 0.10), 0.10),
    "apple3": ("apple", "ellipsoid", (0.036, 0.036, 0.033), 0.17, (0.85, 0.45, 0.15), (0.75, 0.15, 0.10), 0.30),
    "apple4": ("apple", "ellipsoid", (0.038, 0.038, 0.035), 0.19, (0.55, 0.75, 0.25), (0.70, 0.80, 0.35), 0.10),
    "apple5": ("apple", "ellipsoid", (0.035, 0.035, 0.033), 0.16, (0.88, 0.78, 0.30), (0.80, 0.50, 0.20), 0.15),
    "orange1": ("orange", "ellipsoid", (0.038, 0.038, 0.037), 0.20, (0.95, 0.55, 0.08), (0.85, 0.45, 0.05), 0.20),
    "orange2": ("orange", "ellipsoid", (0.040, 0.040, 0.038), 0.23, (0.97, 0.50, 0.05), (0.88, 0.40, 0.04), 0.20),
    "orange3": ("orange", "ellipsoid", (0.036, 0.036, 0.036), 0.18, (0.93, 0.60, 0.12), (0.85, 0.50, 0.08), 0.25),
    "orange4": ("orange", "ellipsoid", (0.039, 0.039, 0.036), 0.21, (0.90, 0.48, 0.06), (0.95, 0.60, 0.15), 0.15),
    "lemon1": ("lemon", "ellipsoid", (0.040, 0.029, 0.029), 0.12, (0.95, 0.85, 0.20), (0.85, 0.75, 0.15), 0.15),
    "lemon2": ("lemon", "ellipsoid", (0.043, 0.030, 0.030), 0.13, (0.92, 0.80, 0.15), (0.98, 0.90, 0.35), 0.15),
    "lime1": ("lime", "ellipsoid", (0.031, 0.027, 0.027), 0.07, (0.35, 0.65, 0.15), (0.45, 0.72, 0.25), 0.15),
    "lime2": ("lime", "ellipsoid", (0.029, 0.026, 0.026), 0.06, (0.30, 0.55, 0.12), (0.40, 0.62, 0.18), 0.20),
    "peach1": ("peach", "ellipsoid", (0.034, 0.034, 0.033), 0.15, (0.95, 0.62, 0.40), (0.85, 0.30, 0.25), 0.30),
    "peach2": ("peach", "ellipsoid", (0.032, 0.032, 0.031), 0.13, (0.93, 0.70, 0.45), (0.80, 0.35, 0.28), 0.25),
    "pear1": ("pear", "pear", (0.034, 0.022), 0.18, (0.70, 0.75, 0.30), (0.60, 0.55, 0.25), 0.15),
    "pear2": ("pear", "pear", (0.032, 0.020), 0.16, (0.78, 0.68, 0.32), (0.65, 0.45, 0.22), 0.20),
    "pepper1": ("pepper", "ellipsoid", (0.040, 0.040, 0.042), 0.16, (0.80, 0.10, 0.08), (0.90, 0.25, 0.20), 0.05),
    "pepper2": ("pepper", "ellipsoid", (0.038, 0.038, 0.045), 0.15, (0.20, 0.55, 0.15), (0.30, 0.65, 0.22), 0.05),
    "plate1": ("plate", "plate", (0.110, 0.016), 0.40, (0.94, 0.94, 0.92), (0.85, 0.85, 0.82), 0.02),
    "plate2": ("plate", "plate", (0.100, 0.014), 0.35, (0.92, 0.88, 0.78), (0.80, 0.75, 0.65), 0.02),
    "potato1": ("potato", "ellipsoid", (0.045, 0.032, 0.027), 0.20, (0.65, 0.50, 0.30), (0.50, 0.38, 0.22), 0.30),
    "potato2": ("potato", "ellipsoid", (0.050, 0.030, 0.026), 0.21, (0.72, 0.58, 0.36), (0.55, 0.42, 0.26), 0.30),
    "tomato1": ("tomato", "ellipsoid", (0.034, 0.034, 0.028), 0.12, (0.85, 0.15, 0.10), (0.92, 0.30, 0.15), 0.10),
    "tomato2": ("tomato", "ellipsoid", (0.030, 0.030, 0.026), 0.10, (0.80, 0.20, 0.12), (0.90, 0.40, 0.15), 0.10),
}

STEMMED = {"apple", "pear", "pepper", "tomato"}


def rgb(c):
    return " ".join(f"{v:g}" for v in c)


def body_geoms(name, category, shape, size):
    """Returns (geom lines, height, inertia diagonal per unit mass, com z)."""
    g = []
    if shape == "ellipsoid":
        rx, ry, rz = size
        g.append(f'<geom name="{name}" class="object_roll" type="ellipsoid" size="{rx} {ry} {rz}" '
                 f'pos="0 0 {rz}" material="{name}"/>')
        height = 2 * rz
        unit = ((ry * ry + rz * rz) / 5, (rx * rx + rz * rz) / 5, (rx * rx + ry * ry) / 5)
        com = rz
    elif shape == "pear":
        rb, rt = size
        zt = 2 * rb + 0.2 * rt
        g.append(f'<geom name="{name}" class="object_roll" type="sphere" size="{rb}" pos="0 0 {rb}" material="{name}"/>')
        g.append(f'<geom name="{name}_top" class="object_roll" type="ellipsoid" size="{rt} {rt} {1.4 * rt:.4f}" '
                 f'pos="0 0 {zt - 0.4 * rt:.4f}" material="{name}"/>')
        height = zt + rt
        unit = (0.4 * rb * rb + 0.02 * height * height,) * 2 + (0.4 * rb * rb,)
        com = 0.8 * rb
    elif shape == "plate":
        r, t = size
        g.append(f'<geom name="{name}" type="cylinder" size="{r} {t / 2}" pos="0 0 {t / 2}" material="{name}"/>')
        g.append(f'<geom name="{name}_well" class="object_visual" type="cylinder" size="{0.7 * r:.4f} 0.0008" '
                 f'pos="0 0 {t + 0.0002:.4f}" rgba="{rgb((0.97, 0.97, 0.95))} 1"/>')
        height = t
        unit = ((3 * r * r + t * t) / 12,) * 2 + (r * r / 2,)
        com = t / 2
    else:
        raise ValueError(shape)
    if category in STEMMED:
        g.append(f'<geom name="{name}_stem" class="object_visual" type="capsule" size="0.0025" '
                 f'fromto="0 0 {height - 0.004:.4f} 0.002 0 {height + 0.01:.4f}" '
                 f'rgba="{"0.25 0.45 0.15" if category != "apple" else "0.35 0.25 0.12"} 1"/>')
    return g, height, unit, com


def default_pose(index):
    """A grid on the table workspace so that scenes/produce.xml shows every instance; plates aside."""
    col, row = index % 6, index // 6
    return 0.30 + 0.09 * row, -0.225 + 0.09 * col


def main():
    objects_dir = os.path.join(ROOT, "models", "objects")
    yaml_lines = ["# The produce set, after the categories of the public RGB-D dataset in the paper's",
                  "# experiments 1 and 2. Written by models/tools/make_produce.py.",
                  "name: produce", "objects:"]
    grid_index = 0
    plate_index = 0
    for name, (category, shape, size, mass, base, mark, frac) in PRODUCE.items():
        geoms, height, unit, com = body_geoms(name, category, shape, size)
        if category == "plate":
            x, y = 0.78, -0.3 + 0.6 * plate_index
            plate_index += 1
        else:
            x, y = default_pose(grid_index)
            grid_index += 1
        inertia = " ".join(f"{mass * u:.3g}" for u in unit)
        dims = {"ellipsoid": lambda s: f"{2 * s[0]:.3f} x {2 * s[1]:.3f} x {2 * s[2]:.3f} m",
                "pear": lambda s: f"{2 * s[0]:.3f} m wide, {height:.3f} m tall",
                "plate": lambda s: f"{2 * s[0]:.3f} m across, {s[1]:.3f} m thick"}[shape](size)
        body = "\n      ".join(geoms)
        text = f"""<!-- {name}: {category} instance ({dims}, {mass} kg). Written by models/tools/make_produce.py. -->
<mujoco>
  <asset>
    <texture name="{name}" type="cube" builtin="flat" rgb1="{rgb(base)}" mark="random" markrgb="{rgb(mark)}"
             random="{frac}" width="128" height="128"/>
    <material name="{name}" texture="{name}" specular="0.35" shininess="0.4"/>
  </asset>
  <worldbody>
    <body name="{name}" pos="{x:.3f} {y:.3f} 0" childclass="object">
      <freejoint name="{name}_free"/>
      <inertial pos="0 0 {com:.4f}" mass="{mass}" diaginertia="{inertia}"/>
      {body}
    </body>
  </worldbody>
</mujoco>
"""
        with open(os.path.join(objects_dir, f"{name}.inc.xml"), "w") as f:
            f.write(text)
        yaml_lines += [f"  - name: {name}", f"    category: {category}", f"    instance: {name}",
                       f"    model: ../../models/objects/{name}.inc.xml"]
    with open(os.path.join(ROOT, "scenes", "objects", "produce.yaml"), "w") as f:
        f.write("\n".join(yaml_lines) + "\n")

    includes = "\n".join(f'  <include file="../models/objects/{n}.inc.xml"/>' for n in PRODUCE)
    scene = f"""<!--
  The cell with every produce instance on the table (plates beside the grid): for viewing the set.
    mujoco-simulate scenes/produce.xml
  Written by models/tools/make_produce.py. Object set: scenes/objects/produce.yaml.
-->
<mujoco model="sortcell_produce">
  <compiler angle="radian" autolimits="true"/>
  <include file="../models/cell/cell.inc.xml"/>
  <include file="../models/gripper/gripper.inc.xml"/>
  <include file="../models/ur5/ur5.inc.xml"/>
  <include file="../models/objects/objects.inc.xml"/>

{includes}
</mujoco>
"""
    with open(os.path.join(ROOT, "scenes", "produce.xml"), "w") as f:
        f.write(scene)


if __name__ == "__main__":
    main()
