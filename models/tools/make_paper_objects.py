#!/usr/bin/env python3
"""Writes the printed surfaces of the paper's real-scene objects (models/objects/bottle1-3, cup and box
.inc.xml, textures in models/objects/textures/paper_*.png).

What makes them look like the real ones of the paper's section 3.3 without changing their physics:
- the bottles' labels are printed (a PNG wrapped round a visual-only tube mesh with texture coordinates,
  over the primitive colliders they always had): a panel with lines of text, an emblem, bands;
- the mug keeps its handle and gets a rounded rim (a ring of capsules along the wall's top);
- the tea box is printed on all six faces (one cube texture, six PNGs): a blue band with a title and
  lines of text round the sides, a logo, a barcode, a lid with a stripe.
Collision geoms, masses and inertias stay as they were. MuJoCo 2.2's texture rules (DESIGN.md section
5): 2d textures on meshes follow the texture coordinates ((0, 0) = the PNG's top-left for inline
texcoord); a cube texture's face images are not rotated for z-up objects, only 'down' (-y) and 'front'
(+z) come out upright, so 'right' (+x) is stored turned 90 degrees ccw, 'left' (-x) 90 degrees cw, 'up'
(+y) and 'back' (-z) 180 degrees.

Reproducible: one seeded generator per object. The outputs are committed; rerun after editing:
    python3 models/tools/make_paper_objects.py
Pure Python, sharing make_produce.py's PNG writer.
"""
import math
import os
import random

from make_produce import ROOT, OBJECTS, TEXTURES, mix, write_png

SEED = 20261201
LABEL_W, LABEL_H = 256, 128  # Round the bottle (u) by along it (v).
TUBE_SEGMENTS = 48


def blank(w, h, colour):
    return [[colour] * w for _ in range(h)]


def fill_rect(img, x0, y0, x1, y1, colour):
    h, w = len(img), len(img[0])
    for y in range(max(0, int(y0)), min(h, int(y1))):
        for x in range(max(0, int(x0)), min(w, int(x1))):
            img[y][x] = colour


def fill_ellipse(img, cx, cy, rx, ry, colour):
    h, w = len(img), len(img[0])
    for y in range(max(0, int(cy - ry)), min(h, int(cy + ry) + 1)):
        for x in range(max(0, int(cx - rx)), min(w, int(cx + rx) + 1)):
            if ((x - cx) / rx) ** 2 + ((y - cy) / ry) ** 2 <= 1:
                img[y][x] = colour


def text_lines(img, rng, x0, y0, x1, y1, colour, line_h=4, gap=3, word=(3, 9)):
    """Lines of 'words' (short bars) filling a box, ragged on the right: print seen at a distance."""
    y = y0
    while y + line_h <= y1:
        x = x0
        end = x1 - rng.uniform(0, (x1 - x0) * 0.3)
        while x < end:
            length = rng.randint(*word)
            fill_rect(img, x, y, min(x + length, end), y + line_h, colour)
            x += length + 2
        y += line_h + gap


def speckle(img, rng, amount):
    """Print and surface grain: a little brightness noise per pixel."""
    for row in img:
        for i, (r, g, b) in enumerate(row):
            f = 1 + rng.gauss(0, amount)
            row[i] = (r * f, g * f, b * f)


def resize_square(img, n):
    """Nearest-neighbour resample to n x n: MuJoCo's cube faces are square images, stretched over the
    face they cover."""
    h, w = len(img), len(img[0])
    return [[img[y * h // n][x * w // n] for x in range(n)] for y in range(n)]


def rotate_ccw(img):
    h, w = len(img), len(img[0])
    return [[img[y][w - 1 - x] for y in range(h)] for x in range(w)]


def rotate_cw(img):
    h, w = len(img), len(img[0])
    return [[img[h - 1 - y][x] for y in range(h)] for x in range(w)]


def rotate_180(img):
    return [list(reversed(row)) for row in reversed(img)]


# ---------------------------------------------------------------------------------------------------
# Bottle labels: the image wraps once round the bottle; its top row is the label's top edge.

BOTTLES = {
    # name: (radius, half height and centre z of the label band, the bottle's own geoms, colours)
    "bottle1": {
        "what": "green tea PET bottle (category bottle). Height 0.224 m, diameter 0.066 m, 0.35 kg",
        "radius": 0.0334, "half": 0.056, "z": 0.080,
        "pet": "0.3 0.55 0.28 1", "cap": "0.9 0.92 0.88 1",
        "inertial": '<inertial pos="0 0 0.0896" mass="0.35" diaginertia="0.001559 0.001559 0.000191"/>',
        "body": (0.033, 0.0800), "shoulder": (0.033, 0.035, 0.1600), "neck": 0.1960, "capz": 0.2145,
        "base": (0.12, 0.45, 0.18), "panel": (0.95, 0.95, 0.9), "ink": (0.07, 0.3, 0.12),
        "band": (0.78, 0.65, 0.28), "emblem": (0.55, 0.78, 0.35),
    },
    "bottle2": {
        "what": "same shape as bottle1, other colour: amber bottle with a red printed label (category others). "
                "Height 0.224 m, diameter 0.066 m, 0.35 kg",
        "radius": 0.0334, "half": 0.056, "z": 0.080,
        "pet": "0.45 0.26 0.1 1", "cap": "0.8 0.1 0.08 1",
        "inertial": '<inertial pos="0 0 0.0896" mass="0.35" diaginertia="0.001559 0.001559 0.000191"/>',
        "body": (0.033, 0.0800), "shoulder": (0.033, 0.035, 0.1600), "neck": 0.1960, "capz": 0.2145,
        "base": (0.78, 0.12, 0.1), "panel": (0.96, 0.9, 0.72), "ink": (0.45, 0.05, 0.05),
        "band": (0.95, 0.78, 0.2), "emblem": (0.98, 0.85, 0.3),
    },
    "bottle3": {
        "what": "similar shape and colour to bottle1: a little slimmer and taller, yellower green, its own "
                "printed label (category others). Height 0.229 m, diameter 0.062 m, 0.32 kg",
        "radius": 0.0314, "half": 0.0595, "z": 0.085,
        "pet": "0.4 0.62 0.26 1", "cap": "0.2 0.5 0.2 1",
        "inertial": '<inertial pos="0 0 0.0916" mass="0.32" diaginertia="0.001475 0.001475 0.000154"/>',
        "body": (0.031, 0.0850), "shoulder": (0.031, 0.030, 0.1700), "neck": 0.2010, "capz": 0.2195,
        "base": (0.5, 0.66, 0.2), "panel": (0.93, 0.95, 0.85), "ink": (0.15, 0.35, 0.1),
        "band": (0.25, 0.5, 0.18), "emblem": (0.85, 0.88, 0.4),
    },
}


def bottle_label(name, spec):
    rng = random.Random(f"{SEED}-{name}")
    img = blank(LABEL_W, LABEL_H, spec["base"])
    # Bands at the label's top and bottom edges.
    fill_rect(img, 0, 0, LABEL_W, 7, spec["band"])
    fill_rect(img, 0, LABEL_H - 7, LABEL_W, LABEL_H, spec["band"])
    if name == "bottle3":
        # A light band across the whole label with the brand on it.
        fill_rect(img, 0, 34, LABEL_W, 62, spec["panel"])
        text_lines(img, rng, 12, 38, 110, 60, spec["ink"], line_h=8, gap=4, word=(6, 16))
        text_lines(img, rng, 140, 72, 240, 116, spec["panel"], line_h=3, gap=3)
        fill_ellipse(img, 190, 48, 22, 10, spec["emblem"])
    else:
        # A light panel (the front) with the name and lines of text; an emblem on the back.
        fill_rect(img, 20, 16, 108, 112, spec["panel"])
        text_lines(img, rng, 28, 22, 100, 44, spec["ink"], line_h=9, gap=4, word=(8, 20))
        text_lines(img, rng, 28, 56, 100, 106, spec["ink"], line_h=3, gap=3)
        fill_ellipse(img, 190, 60, 26, 34, spec["emblem"])
        fill_ellipse(img, 190, 60, 12, 24, spec["base"])
        text_lines(img, rng, 150, 100, 236, 116, spec["panel"], line_h=3, gap=2)
    speckle(img, rng, 0.02)
    write_png(os.path.join(TEXTURES, f"paper_{name}_label.png"), LABEL_W, LABEL_H, img)


def tube_mesh(radius, half):
    """An open tube about z (centred on the origin) with outward normals and texture coordinates: u
    once round, v from the top edge (0) to the bottom (1). A seam column so the image wraps once."""
    verts, normals, uvs, faces = [], [], [], []
    for j in range(TUBE_SEGMENTS + 1):
        phi = 2 * math.pi * j / TUBE_SEGMENTS
        c, s = math.cos(phi), math.sin(phi)
        for k, z in enumerate((half, -half)):
            verts.append((radius * c, radius * s, z))
            normals.append((c, s, 0.0))
            uvs.append((j / TUBE_SEGMENTS, float(k)))
    for j in range(TUBE_SEGMENTS):
        top, bottom, top_next, bottom_next = 2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3
        faces += [(top, bottom, bottom_next), (top, bottom_next, top_next)]
    return verts, normals, uvs, faces


def numbers(values, fmt):
    return " ".join(fmt.format(c) for v in values for c in v)


def write_bottle(name, spec):
    bottle_label(name, spec)
    verts, normals, uvs, faces = tube_mesh(spec["radius"], spec["half"])
    r, h = spec["body"]
    sr, sh, sz = spec["shoulder"]
    text = f"""<!-- {name}: {spec["what"]}.
     Written by models/tools/make_paper_objects.py: the printed label is a visual tube mesh with a texture
     over the primitive colliders (body, shoulder, neck, cap), which roll (condim 6) when it lies. -->
<mujoco>
  <asset>
    <material name="{name}_pet" rgba="{spec["pet"]}" specular="0.5" shininess="0.6"/>
    <material name="{name}_cap" rgba="{spec["cap"]}" specular="0.3"/>
    <!-- The path is relative to scenes/; sortcell finds the texture by its name from anywhere. -->
    <texture name="{name}_label" type="2d" file="../models/objects/textures/paper_{name}_label.png"/>
    <material name="{name}_label" texture="{name}_label" specular="0.2" shininess="0.3"/>
    <mesh name="{name}_label"
          vertex="{numbers(verts, "{:.5f}")}"
          normal="{numbers(normals, "{:.4f}")}"
          texcoord="{numbers(uvs, "{:.4f}")}"
          face="{numbers(faces, "{}")}"/>
  </asset>
  <worldbody>
    <body name="{name}" pos="{BOTTLE_POSES[name]}" childclass="object_roll">
      <freejoint name="{name}_free"/>
      {spec["inertial"]}
      <geom name="{name}_body" type="cylinder" size="{r} {h:.4f}" pos="0 0 {h:.4f}" material="{name}_pet"/>
      <geom name="{name}_shoulder" type="ellipsoid" size="{sr} {sr} {sh}" pos="0 0 {sz:.4f}" material="{name}_pet"/>
      <geom name="{name}_neck" type="cylinder" size="0.0135 0.0110" pos="0 0 {spec["neck"]:.4f}" material="{name}_pet"/>
      <geom name="{name}_cap" type="cylinder" size="0.0155 0.0095" pos="0 0 {spec["capz"]:.4f}" material="{name}_cap"/>
      <!-- Open mesh: no volume of its own (the body's inertial says the mass). -->
      <geom name="{name}_label" class="object_visual" type="mesh" mesh="{name}_label" mass="0" pos="0 0 {spec["z"]:.4f}" material="{name}_label"/>
    </body>
  </worldbody>
</mujoco>
"""
    with open(os.path.join(OBJECTS, f"{name}.inc.xml"), "w") as out:
        out.write(text)


BOTTLE_POSES = {"bottle1": "0.35 0.15 0", "bottle2": "0.35 0.0 0", "bottle3": "0.35 -0.15 0"}


# ---------------------------------------------------------------------------------------------------
# The tea box: 0.06 (x) x 0.09 (y) x 0.12 (z) m; every face image is drawn upright (its top row at the
# box's top), then turned as MuJoCo 2.2's cube map wants it.

BOX_CARD, BOX_BLUE, BOX_INK = (0.92, 0.91, 0.87), (0.22, 0.4, 0.72), (0.1, 0.16, 0.35)
BOX_ORANGE = (0.92, 0.55, 0.15)
BOX_PX_PER_M = 1000  # Drawn at 1 px per mm, then stretched to BOX_FACE_PX square.
BOX_FACE_PX = 128


def box_side(rng, width_m, front):
    w, h = int(width_m * BOX_PX_PER_M), int(0.12 * BOX_PX_PER_M)
    img = blank(w, h, BOX_CARD)
    # The blue band round the box at 48-92 mm from the bottom (what the flat-coloured box had).
    fill_rect(img, 0, h - 92, w, h - 48, BOX_BLUE)
    if front:
        text_lines(img, rng, 6, h - 88, w - 6, h - 70, BOX_CARD, line_h=7, gap=3, word=(8, 18))
        text_lines(img, rng, 6, h - 64, w - 10, h - 52, BOX_CARD, line_h=2, gap=2)
        fill_ellipse(img, w / 2, 20, 12, 12, BOX_ORANGE)
        fill_ellipse(img, w / 2, 20, 6, 6, BOX_CARD)
        text_lines(img, rng, 6, h - 40, w - 6, h - 6, BOX_INK, line_h=2, gap=3)
    else:
        text_lines(img, rng, 4, h - 86, w - 4, h - 54, BOX_CARD, line_h=2, gap=3)
        text_lines(img, rng, 4, 8, w - 4, 26, BOX_INK, line_h=2, gap=2)
        for x in range(6, min(w - 6, 40)):  # A barcode.
            if rng.random() < 0.55:
                fill_rect(img, x, h - 30, x + 1, h - 10, BOX_INK)
    speckle(img, rng, 0.015)
    return img


def box_lid(rng, wx, wy):
    """The top or bottom: x across the image, y down it."""
    img = blank(int(wx * BOX_PX_PER_M), int(wy * BOX_PX_PER_M), BOX_CARD)
    fill_rect(img, 0, len(img) / 2 - 6, len(img[0]), len(img) / 2 + 6, BOX_BLUE)
    text_lines(img, rng, 6, 8, len(img[0]) - 6, len(img) / 2 - 12, BOX_INK, line_h=2, gap=3)
    speckle(img, rng, 0.015)
    return img


def write_box():
    rng = random.Random(f"{SEED}-box")
    def sq(img):
        return resize_square(img, BOX_FACE_PX)

    faces = {
        "right": rotate_ccw(sq(box_side(rng, 0.09, front=False))),  # +x, 90 x 120 mm
        "left": rotate_cw(sq(box_side(rng, 0.09, front=False))),  # -x
        "up": rotate_180(sq(box_side(rng, 0.06, front=True))),  # +y, 60 x 120 mm
        "down": sq(box_side(rng, 0.06, front=True)),  # -y
        "front": sq(box_lid(rng, 0.06, 0.09)),  # +z, the lid
        "back": rotate_180(sq(box_lid(rng, 0.06, 0.09))),  # -z
    }
    for face, img in faces.items():
        write_png(os.path.join(TEXTURES, f"paper_box_{face}.png"), len(img[0]), len(img), img)
    files = " ".join(f'file{f}="../models/objects/textures/paper_box_{f}.png"' for f in faces)
    text = f"""<!-- box: a white tea box printed with a blue band, its name, text, a logo and a barcode (category
     others). 0.06 x 0.09 x 0.12 m, 0.15 kg. Written by models/tools/make_paper_objects.py: one box, a
     cube texture of six printed faces. -->
<mujoco>
  <asset>
    <!-- Paths relative to scenes/; sortcell finds the files by their names from anywhere. -->
    <texture name="box_print" type="cube" {files}/>
    <material name="box_print" texture="box_print" specular="0.2"/>
  </asset>
  <worldbody>
    <body name="box" pos="0.58 -0.15 0" childclass="object">
      <freejoint name="box_free"/>
      <inertial pos="0 0 0.06" mass="0.15" diaginertia="0.000306 0.000225 0.000146"/>
      <geom name="box" type="box" size="0.03 0.045 0.06" pos="0 0 0.06" material="box_print"/>
    </body>
  </worldbody>
</mujoco>
"""
    with open(os.path.join(OBJECTS, "box.inc.xml"), "w") as out:
        out.write(text)


# ---------------------------------------------------------------------------------------------------
# The mug: white glaze, a wall of 16 thin boxes (hollow to the camera), a handle of capsules and a
# rounded rim.

CUP_WALL = 16


def write_cup():
    wall = []
    for k in range(CUP_WALL):
        phi = 2 * math.pi * k / CUP_WALL
        c, s = math.cos(phi), math.sin(phi)
        wall.append(f'<geom class="object_visual" type="box" pos="{0.0345 * c:.5f} {0.0345 * s:.5f} 0.0505" '
                    f'quat="{math.cos(phi / 2):.6f} 0 0 {math.sin(phi / 2):.6f}" size="0.0035 0.00746 0.045" '
                    f'material="cup_glaze"/>')
    rim = []
    for k in range(CUP_WALL):
        a0, a1 = 2 * math.pi * k / CUP_WALL, 2 * math.pi * (k + 1) / CUP_WALL
        rim.append(f'<geom class="object_visual" type="capsule" size="0.0037" fromto="{0.0345 * math.cos(a0):.5f} '
                   f'{0.0345 * math.sin(a0):.5f} 0.0955 {0.0345 * math.cos(a1):.5f} {0.0345 * math.sin(a1):.5f} 0.0955" '
                   f'material="cup_glaze"/>')
    body = "\n      ".join(wall + rim)
    text = f"""<!-- cup: a white glazed ceramic mug with a handle and a rounded rim (category cup). Outer diameter
     0.076 m, height 0.0955 m, 0.28 kg. The wall is a ring of 16 thin boxes (seen, hollow to the camera)
     under a rim of capsules; the collision hull is a solid cylinder (the gripper only ever touches the
     outside) plus the handle. Written by models/tools/make_paper_objects.py. -->
<mujoco>
  <asset>
    <material name="cup_glaze" rgba="0.93 0.92 0.88 1" specular="0.6" shininess="0.7"/>
    <material name="cup_inside" rgba="0.85 0.84 0.8 1" specular="0.3"/>
  </asset>
  <worldbody>
    <body name="cup" pos="0.58 0.15 0" childclass="object">
      <freejoint name="cup_free"/>
      <inertial pos="0.004 0 0.042" mass="0.28" diaginertia="0.00039 0.00039 0.00036"/>
      <geom name="cup_hull" class="object_collision" type="cylinder" size="0.038 0.04775" pos="0 0 0.04775"/>
      <geom name="cup_bottom" class="object_visual" type="cylinder" size="0.038 0.00275" pos="0 0 0.00275" material="cup_inside"/>
      {body}
      <geom name="cup_handle_top" type="capsule" fromto="0.036 0 0.074 0.058 0 0.07" size="0.0055" material="cup_glaze"/>
      <geom name="cup_handle_side" type="capsule" fromto="0.058 0 0.07 0.058 0 0.032" size="0.0055" material="cup_glaze"/>
      <geom name="cup_handle_bottom" type="capsule" fromto="0.058 0 0.032 0.036 0 0.026" size="0.0055" material="cup_glaze"/>
    </body>
  </worldbody>
</mujoco>
"""
    with open(os.path.join(OBJECTS, "cup.inc.xml"), "w") as out:
        out.write(text)


def main():
    os.makedirs(TEXTURES, exist_ok=True)
    for name, spec in BOTTLES.items():
        write_bottle(name, spec)
    write_box()
    write_cup()


if __name__ == "__main__":
    main()
