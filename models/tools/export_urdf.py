#!/usr/bin/env python3
"""Writes the mesh objects of one of our object sets as URDF objects laid out the way the YCB objects
are published for simulators (../shared/ycb: NAME.urdf beside NAME/textured.obj, textured.mtl, a
texture image and a collision STL), with an object-set YAML naming them by `urdf:`.

Why: the import path (`urdf:` entries) should sort any such set with no code change; this gives a
second, different set to show it on (`sortcell sweep SPEC --set object_set=OUT/objects.yaml`).

Each object's textured visual mesh becomes the OBJ; its collision is that mesh again as one convex
piece (our produce collides as a primitive hull, which URDF cannot say for an ellipsoid); the mass is
the MJCF inertial's; the URDF's inertia is a placeholder, as in the YCB files.

    python3 models/tools/export_urdf.py scenes/objects/produce.yaml --out out/urdf_produce [--per-category 2]
"""
import argparse
import os
import shutil
import struct
import sys
import xml.etree.ElementTree as ET

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TEXTURES = os.path.join(REPO, "models", "objects", "textures")


def floats(text):
    return [float(x) for x in text.split()]


def visual_mesh(mjcf_path):
    """(vertices, faces, texcoords, texture file, mass) of the object's one textured mesh."""
    root = ET.parse(mjcf_path).getroot()
    meshes = root.findall("./asset/mesh")
    textures = root.findall("./asset/texture")
    inertial = root.find(".//body/inertial")
    if len(meshes) != 1 or len(textures) != 1 or inertial is None:
        raise ValueError(f"{mjcf_path}: expected one mesh, one texture and an inertial")
    m = meshes[0]
    v = floats(m.get("vertex"))
    f = [int(x) for x in m.get("face").split()]
    t = floats(m.get("texcoord", ""))
    if not t or len(t) // 2 != len(v) // 3:
        raise ValueError(f"{mjcf_path}: the mesh has no texture coordinate per vertex")
    texture = os.path.join(TEXTURES, os.path.basename(textures[0].get("file")))
    return v, f, t, texture, float(inertial.get("mass"))


def write_obj(folder, v, f, t):
    with open(os.path.join(folder, "textured.mtl"), "w") as out:
        out.write("newmtl material_0\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nmap_Kd texture_map.png\n")
    with open(os.path.join(folder, "textured.obj"), "w") as out:
        out.write("mtllib textured.mtl\nusemtl material_0\n")
        for i in range(0, len(v), 3):
            out.write(f"v {v[i]:.6f} {v[i + 1]:.6f} {v[i + 2]:.6f}\n")
        # MuJoCo's texcoord v runs down the image, OBJ's up it.
        for i in range(0, len(t), 2):
            out.write(f"vt {t[i]:.5f} {1.0 - t[i + 1]:.5f}\n")
        for i in range(0, len(f), 3):
            a, b, c = f[i] + 1, f[i + 1] + 1, f[i + 2] + 1
            out.write(f"f {a}/{a} {b}/{b} {c}/{c}\n")


def write_stl(path, v, f):
    """Binary STL of the mesh's non-degenerate triangles (normals left zero, as many tools do)."""
    tris = []
    for i in range(0, len(f), 3):
        p = [tuple(v[3 * f[i + k]:3 * f[i + k] + 3]) for k in range(3)]
        if len(set(p)) == 3:
            tris.append(p)
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(tris)))
        for p in tris:
            out.write(struct.pack("<12fH", 0, 0, 0, *p[0], *p[1], *p[2], 0))


URDF = """<robot name="{name}">
  <link name="base_link">
    <visual>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <geometry><mesh filename="{name}/textured.obj" scale="1 1 1"/></geometry>
    </visual>
    <collision>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <geometry><mesh filename="{name}/textured_hull.stl" scale="1 1 1"/></geometry>
    </collision>
    <inertial>
      <mass value="{mass!r}"/>
      <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/>
    </inertial>
  </link>
</robot>
"""


def export(entry, set_dir, out_dir):
    name = entry["name"]
    v, f, t, texture, mass = visual_mesh(os.path.join(set_dir, entry["model"]))
    folder = os.path.join(out_dir, name)
    os.makedirs(folder, exist_ok=True)
    write_obj(folder, v, f, t)
    write_stl(os.path.join(folder, "textured_hull.stl"), v, f)
    shutil.copyfile(texture, os.path.join(folder, "texture_map.png"))
    with open(os.path.join(out_dir, name + ".urdf"), "w") as out:
        out.write(URDF.format(name=name, mass=mass))
    return {"name": name, "category": entry["category"], "instance": entry.get("instance", name),
            "urdf": name + ".urdf"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("object_set", help="one of our object sets whose objects have a textured mesh")
    parser.add_argument("--out", required=True, help="folder for the URDF objects and objects.yaml")
    parser.add_argument("--per-category", type=int, default=0, help="the first N of each category (0: all)")
    args = parser.parse_args()
    with open(args.object_set) as f:
        spec = yaml.safe_load(f)
    set_dir = os.path.dirname(os.path.abspath(args.object_set))
    os.makedirs(args.out, exist_ok=True)
    taken, entries = {}, []
    for entry in spec["objects"]:
        n = taken.get(entry["category"], 0)
        if args.per_category and n >= args.per_category:
            continue
        taken[entry["category"]] = n + 1
        try:
            entries.append(export(entry, set_dir, args.out))
        except (ValueError, OSError) as e:
            sys.exit(f"export_urdf: {e}")
    with open(os.path.join(args.out, "objects.yaml"), "w") as out:
        out.write(f"# {spec['name']} as URDF objects, written by models/tools/export_urdf.py\n")
        yaml.safe_dump({"name": spec["name"] + "_urdf", "objects": entries}, out, sort_keys=False,
                       default_flow_style=None, width=200)
    print(f"{len(entries)} objects of {args.object_set} written to {args.out}")


if __name__ == "__main__":
    main()
