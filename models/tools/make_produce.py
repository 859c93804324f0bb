#!/usr/bin/env python3
"""Writes the produce object models (models/objects/<instance>.inc.xml with their textures in
models/objects/textures/) and scenes/objects/produce.yaml and scenes/produce.xml.

The produce set follows the categories of the public RGB-D dataset used in the paper's experiments
1 and 2: apple, lemon, lime, orange, peach, pear, pepper, plate, potato, tomato. Each category has
seven instances drawn from the category's real range of size, proportions, shape details (stems,
dimples, lobes, ribs, creases, bumps, tips, elongation) and colour. The colour varies over the
surface as real produce does (gradients, blush, streaks, spots, speckle) through a latitude-longitude
texture on a visual mesh; the object touches the world through a simple primitive under it
(an ellipsoid, a cylinder for plates), so the physics stays as it was with primitives.

Reproducible: everything is drawn from one seeded generator per instance. The outputs are committed;
rerun this after editing the tables below:
    python3 models/tools/make_produce.py
Pure Python (no numpy or imaging library): PNGs are written with zlib.
"""
import colorsys
import math
import os
import random
import struct
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OBJECTS = os.path.join(ROOT, "models", "objects")
TEXTURES = os.path.join(OBJECTS, "textures")
INSTANCES = 7
SEED = 13
N_LAT, N_LON = 20, 28       # mesh rings (pole to pole) and meridians
TEX_W, TEX_H = 128, 64      # texture: longitude across, latitude down (top row = top of the object)
DENSITY = 850.0             # kg/m^3, produce is a little lighter than water

# Per category: size ranges (m), colour palettes (HSV, h in degrees), surface details, material.
#   width: (min, max) diameter across; aspect: height / width; palettes: list of (base, second) HSV
#   where "second" is the blush or gradient colour; spots: (count range, HSV); gloss: (specular, shininess)
CATEGORIES = {
    "apple": dict(width=(0.066, 0.082), aspect=(0.80, 0.95),
                  palettes=[((358, 0.80, 0.62), (45, 0.70, 0.85)), ((350, 0.75, 0.45), (10, 0.80, 0.60)),
                            ((85, 0.65, 0.72), (40, 0.55, 0.80)), ((50, 0.60, 0.88), (5, 0.70, 0.78)),
                            ((20, 0.70, 0.75), (355, 0.75, 0.60))],
                  spots=((40, 90), (50, 0.25, 0.92)), gloss=(0.5, 0.5)),
    "orange": dict(width=(0.066, 0.080), aspect=(0.90, 1.0),
                   palettes=[((28, 0.92, 0.95), (24, 0.95, 0.88)), ((32, 0.90, 0.97), (38, 0.85, 0.92)),
                             ((22, 0.95, 0.90), (30, 0.90, 0.95))],
                   spots=((250, 400), (26, 0.95, 0.78)), gloss=(0.35, 0.35)),
    "lemon": dict(width=(0.050, 0.060), aspect=(1.35, 1.6),
                  palettes=[((52, 0.85, 0.95), (65, 0.80, 0.80)), ((48, 0.80, 0.92), (58, 0.85, 0.88)),
                            ((55, 0.75, 0.96), (70, 0.70, 0.75))],
                  spots=((200, 320), (50, 0.90, 0.80)), gloss=(0.4, 0.4)),
    "lime": dict(width=(0.044, 0.054), aspect=(1.05, 1.2),
                 palettes=[((95, 0.75, 0.60), (80, 0.70, 0.72)), ((100, 0.80, 0.50), (90, 0.65, 0.65)),
                           ((85, 0.70, 0.68), (70, 0.65, 0.78))],
                 spots=((200, 320), (100, 0.80, 0.45)), gloss=(0.4, 0.4)),
    "peach": dict(width=(0.060, 0.074), aspect=(0.92, 1.02),
                  palettes=[((32, 0.65, 0.95), (5, 0.80, 0.78)), ((38, 0.60, 0.93), (355, 0.75, 0.70)),
                            ((28, 0.55, 0.96), (10, 0.70, 0.85))],
                  spots=((30, 70), (0, 0.75, 0.60)), gloss=(0.08, 0.15)),
    "pear": dict(width=(0.060, 0.072), aspect=(1.35, 1.6),
                 palettes=[((70, 0.65, 0.75), (55, 0.70, 0.78)), ((60, 0.70, 0.80), (10, 0.60, 0.70)),
                           ((35, 0.70, 0.60), (30, 0.60, 0.48)), ((80, 0.55, 0.70), (60, 0.60, 0.80))],
                 spots=((120, 220), (30, 0.60, 0.45)), gloss=(0.25, 0.3)),
    "pepper": dict(width=(0.068, 0.082), aspect=(0.90, 1.15),
                   palettes=[((358, 0.90, 0.72), (5, 0.85, 0.55)), ((110, 0.85, 0.45), (100, 0.80, 0.35)),
                             ((48, 0.95, 0.92), (40, 0.95, 0.85)), ((28, 0.95, 0.92), (20, 0.95, 0.80))],
                   spots=((0, 0), (0, 0, 0)), gloss=(0.8, 0.8)),
    "plate": dict(width=(0.19, 0.23), aspect=(0.08, 0.10),
                  palettes=[((45, 0.05, 0.95), (210, 0.45, 0.55)), ((40, 0.12, 0.92), (0, 0.55, 0.60)),
                            ((0, 0.0, 0.95), (120, 0.35, 0.50)), ((35, 0.08, 0.90), (35, 0.08, 0.90))],
                  spots=((0, 0), (0, 0, 0)), gloss=(0.6, 0.6)),
    "potato": dict(width=(0.050, 0.064), aspect=(0.55, 0.75),
                   palettes=[((30, 0.58, 0.55), (26, 0.60, 0.45)), ((24, 0.55, 0.50), (20, 0.58, 0.40)),
                             ((15, 0.60, 0.42), (10, 0.62, 0.35)), ((36, 0.50, 0.62), (30, 0.52, 0.50))],
                   spots=((25, 60), (25, 0.55, 0.35)), gloss=(0.05, 0.1)),
    "tomato": dict(width=(0.056, 0.072), aspect=(0.72, 0.86),
                   palettes=[((2, 0.88, 0.80), (10, 0.85, 0.78)), ((6, 0.90, 0.85), (25, 0.85, 0.85)),
                             ((355, 0.85, 0.70), (5, 0.85, 0.75))],
                   spots=((0, 0), (0, 0, 0)), gloss=(0.7, 0.7)),
}
# Potatoes and lemons are long: `width` is the short side across, the long side is aspect x width
# lying on the table (lemons, limes) or the footprint's length (potatoes: aspect is height/width,
# elongation separate).


def hsv(h, s, v):
    return colorsys.hsv_to_rgb((h % 360) / 360.0, max(0.0, min(1.0, s)), max(0.0, min(1.0, v)))


def jitter_hsv(rng, c, dh=6, ds=0.06, dv=0.06):
    return (c[0] + rng.uniform(-dh, dh), c[1] + rng.uniform(-ds, ds), c[2] + rng.uniform(-dv, dv))


def mix(a, b, w):
    return tuple(x + (y - x) * w for x, y in zip(a, b))


def smoothstep(e0, e1, x):
    t = max(0.0, min(1.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


def write_png(path, width, height, rows):
    """rows: height lists of width (r, g, b) in [0, 1], top row first."""
    raw = bytearray()
    for row in rows:
        raw.append(0)
        for r, g, b in row:
            raw += bytes((int(max(0, min(255, round(255 * c)))) for c in (r, g, b)))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


# ---------------------------------------------------------------------------------------------------
# Shapes: a profile (rho, z) from the bottom pole (t = 0) to the top pole (t = 1), swept about z and
# modulated around it (phi). Each returns a function (t, phi) -> (x, y, z) in the object's frame.

def shape_apple(rng, w, h):
    r = w / 2
    dimple, bottom, taper = rng.uniform(0.10, 0.22) * h, rng.uniform(0.03, 0.08) * h, rng.uniform(0.05, 0.18)
    lobes, lobe = rng.choice((5, 5, 6)), rng.uniform(0.0, 0.05)
    def f(t, phi):
        a = math.pi * t
        rho = r * math.sin(a) * (1 + taper * (t - 0.5)) * (1 + lobe * math.cos(lobes * phi) * (1 - t))
        z = h / 2 * (1 - math.cos(a)) - dimple * math.exp(-((1 - t) / 0.16) ** 2) + bottom * math.exp(-(t / 0.12) ** 2)
        return rho * math.cos(phi), rho * math.sin(phi), z
    return f


def shape_round(rng, w, h, navel=0.0, crease=0.0, tip=0.0):
    r = w / 2
    phi0 = rng.uniform(0, 2 * math.pi)
    def f(t, phi):
        a = math.pi * t
        s = 1 - crease * math.exp(-(math.atan2(math.sin(phi - phi0), math.cos(phi - phi0)) / 0.18) ** 2) * math.sin(a)
        rho = r * math.sin(a) * s
        z = h / 2 * (1 - math.cos(a)) + navel * math.exp(-(t / 0.1) ** 2) + tip * math.exp(-((1 - t) / 0.1) ** 2)
        return rho * math.cos(phi), rho * math.sin(phi), z
    return f


def shape_lying(rng, w, length, tip):
    """Lemon, lime: a body of revolution about its long axis, lying along x, with pointed ends."""
    r = w / 2
    def f(t, phi):
        a = math.pi * t
        rho = r * math.sin(a) ** 0.85
        along = length / 2 * -math.cos(a)
        along += math.copysign(tip * math.exp(-(min(t, 1 - t) / 0.07) ** 2), along)
        return along, rho * math.cos(phi), r + rho * math.sin(phi)
    return f


def shape_pear(rng, w, h):
    rb = w / 2
    rn = rb * rng.uniform(0.45, 0.6)
    waist = rng.uniform(0.45, 0.6)
    lean = rng.uniform(0.0, 0.08) * w
    def f(t, phi):
        a = math.pi * t
        g = smoothstep(waist - 0.2, waist + 0.25, t)
        rho = math.sin(a) ** 0.7 * (rb * (1 - g) + rn * g)
        z = h * (0.5 - 0.5 * math.cos(a)) ** 0.9
        return rho * math.cos(phi) + lean * g * g, rho * math.sin(phi), z
    return f


def shape_pepper(rng, w, h):
    r = w / 2
    lobes = rng.choice((3, 4, 4))
    lobe = rng.uniform(0.06, 0.12)
    shoulder = rng.uniform(0.15, 0.3)
    def f(t, phi):
        a = math.pi * t
        rho = r * math.sin(a) ** 0.55 * (1 + lobe * math.cos(lobes * phi)) * (1 - shoulder * t ** 4)
        z = h / 2 * (1 - math.cos(a)) - 0.12 * h * math.exp(-((1 - t) / 0.12) ** 2) \
            + 0.04 * h * math.cos(lobes * phi) * math.exp(-(t / 0.2) ** 2)
        return rho * math.cos(phi), rho * math.sin(phi), z
    return f


def shape_potato(rng, w, h, length):
    bumps = [(rng.uniform(0.02, 0.07), rng.randint(1, 3), rng.randint(1, 3), rng.uniform(0, 6.3), rng.uniform(0, 6.3))
             for _ in range(5)]
    def f(t, phi):
        a = math.pi * t
        s = 1 + sum(amp * math.sin(k1 * a + p1) * math.cos(k2 * phi + p2) for amp, k1, k2, p1, p2 in bumps)
        x, y = length / 2 * math.sin(a) * math.cos(phi) * s, w / 2 * math.sin(a) * math.sin(phi) * s
        return x, y, h / 2 * (1 - math.cos(a) * s)
    return f


def shape_tomato(rng, w, h):
    r = w / 2
    ribs, rib = rng.randint(5, 7), rng.uniform(0.02, 0.06)
    def f(t, phi):
        a = math.pi * t
        rho = r * math.sin(a) * (1 + rib * abs(math.cos(ribs * phi / 2)) * math.sin(a) ** 2)
        z = h / 2 * (1 - math.cos(a)) - 0.1 * h * math.exp(-((1 - t) / 0.15) ** 2)
        return rho * math.cos(phi), rho * math.sin(phi), z
    return f


def shape_plate(rng, w, h):
    """A closed profile: foot ring on the table, the well, the rim rising to the edge."""
    R = w / 2
    well, foot = R * rng.uniform(0.55, 0.7), R * rng.uniform(0.4, 0.55)
    rim, t0 = h, 0.006
    pts = [(0, 0.002), (foot, 0.002), (foot + 0.004, 0.0), (well, 0.0015), (R, rim - 0.004), (R, rim),
           (R - 0.006, rim), (well, t0 + 0.002), (0, t0 + 0.002)]
    # Arc length parameterisation of the polyline.
    lengths = [0.0]
    for (r0, z0), (r1, z1) in zip(pts, pts[1:]):
        lengths.append(lengths[-1] + math.hypot(r1 - r0, z1 - z0))
    def f(t, phi):
        s = t * lengths[-1]
        k = max(i for i in range(len(lengths) - 1) if lengths[i] <= s) if s < lengths[-1] else len(pts) - 2
        u = (s - lengths[k]) / max(1e-9, lengths[k + 1] - lengths[k])
        rho = pts[k][0] + u * (pts[k + 1][0] - pts[k][0])
        z = pts[k][1] + u * (pts[k + 1][1] - pts[k][1])
        return rho * math.cos(phi), rho * math.sin(phi), z
    return f


# ---------------------------------------------------------------------------------------------------
# Textures: colour at (u = longitude / 2pi, t = bottom 0 .. top 1).

def make_colour(rng, category, spec):
    base_hsv, second_hsv = rng.choice(spec["palettes"])
    base, second = hsv(*jitter_hsv(rng, base_hsv)), hsv(*jitter_hsv(rng, second_hsv))
    n_lo, n_hi = spec["spots"][0]
    spots = [(rng.random(), rng.uniform(0.05, 0.95), rng.uniform(0.004, 0.012)) for _ in range(rng.randint(n_lo, n_hi))]
    spot_colour = hsv(*jitter_hsv(rng, spec["spots"][1], 4, 0.05, 0.05))
    blush_u, blush_t, blush = rng.random(), rng.uniform(0.35, 0.7), rng.uniform(0.3, 0.9)
    speckle = {"orange": 0.05, "lemon": 0.05, "lime": 0.05, "potato": 0.08, "pear": 0.05}.get(category, 0.03)
    streaks = rng.uniform(20, 40)
    rim_band = category == "plate" and rng.random() < 0.6

    def colour(u, t, noise):
        c = base
        if category in ("apple", "peach"):
            d = min(abs(u - blush_u), 1 - abs(u - blush_u))
            w = blush * math.exp(-(d / 0.22) ** 2 - ((t - blush_t) / 0.45) ** 2)
            if category == "apple":
                w *= 0.75 + 0.25 * math.sin(streaks * 2 * math.pi * u + 3 * noise)
            c = mix(c, second, max(0.0, min(1.0, w)))
        elif category in ("pear", "lemon", "lime", "tomato", "pepper", "orange", "potato"):
            # Towards the stem (top; lemons: both ends) the colour turns to the second one.
            ends = max(t, 1 - t) if category in ("lemon", "lime") else t
            c = mix(c, second, smoothstep(0.55, 1.0, ends) * blush)
        elif category == "plate" and rim_band:
            c = mix(c, second, smoothstep(0.74, 0.76, t) * (1 - smoothstep(0.80, 0.82, t)))
        for su, st, sr in spots:
            du = min(abs(u - su), 1 - abs(u - su)) * math.sin(math.pi * max(0.05, min(0.95, t))) * 2
            if du * du + (t - st) ** 2 < sr * sr:
                c = spot_colour
                break
        k = 1 + speckle * noise
        return tuple(max(0.0, min(1.0, x * k)) for x in c)

    return colour, base


def texture_rows(rng, colour):
    rows = []
    for row in range(TEX_H):
        t = 1 - (row + 0.5) / TEX_H
        rows.append([colour((col + 0.5) / TEX_W, t, rng.gauss(0, 1)) for col in range(TEX_W)])
    return rows


# ---------------------------------------------------------------------------------------------------

def mesh(f):
    """Vertices, texture coordinates and faces of a lat-long grid (a seam column and pole rows)."""
    verts, uvs, faces = [], [], []
    for i in range(N_LAT + 1):
        t = i / N_LAT
        for j in range(N_LON + 1):
            verts.append(f(t, 2 * math.pi * j / N_LON))
            uvs.append((j / N_LON, t))
    row = N_LON + 1
    for i in range(N_LAT):
        for j in range(N_LON):
            a, b, c, d = i * row + j, i * row + j + 1, (i + 1) * row + j + 1, (i + 1) * row + j
            if i > 0:
                faces.append((a, b, c))
            if i < N_LAT - 1:
                faces.append((a, c, d))
    return verts, uvs, faces


def place_on_table(verts):
    """Shifts the vertices so the lowest is at z = 0 and the footprint is centred on the origin."""
    xs, ys, zs = zip(*verts)
    cx, cy, z0 = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2, min(zs)
    verts = [(x - cx, y - cy, z - z0) for x, y, z in verts]
    xs, ys, zs = zip(*verts)
    return verts, (max(xs) - min(xs), max(ys) - min(ys), max(zs))


def details(name, category, rng, size, spec):
    """Visual stems and calyxes: (XML lines)."""
    sx, sy, h = size
    g = []
    def capsule(suffix, a, b, radius, rgba):
        g.append(f'<geom name="{name}_{suffix}" class="object_visual" type="capsule" size="{radius:.4f}" '
                 f'fromto="{a[0]:.4f} {a[1]:.4f} {a[2]:.4f} {b[0]:.4f} {b[1]:.4f} {b[2]:.4f}" rgba="{rgba} 1"/>')
    if category in ("apple", "pear"):
        top = h - (0.12 * h if category == "apple" else 0.0)
        lean = rng.uniform(-0.004, 0.004)
        capsule("stem", (0, 0, top - 0.004), (lean, 0.002, top + rng.uniform(0.008, 0.016)), 0.0022, "0.33 0.23 0.12")
    elif category == "pepper":
        capsule("stem", (0, 0, h - 0.012), (0.003, 0, h + 0.012), 0.005, "0.25 0.45 0.15")
    elif category == "tomato":
        top = h - 0.1 * h
        for k in range(5):
            a = 2 * math.pi * k / 5 + rng.uniform(0, 0.4)
            capsule(f"sepal{k}", (0, 0, top + 0.002), (0.012 * math.cos(a), 0.012 * math.sin(a), top - 0.001), 0.0018,
                    "0.22 0.42 0.12")
        capsule("stem", (0, 0, top), (0, 0, top + 0.008), 0.002, "0.22 0.42 0.12")
    return g


def make_instance(name, category, index):
    rng = random.Random(f"{SEED}-{name}")
    spec = CATEGORIES[category]
    w = rng.uniform(*spec["width"])
    aspect = rng.uniform(*spec["aspect"])
    h = w * aspect
    if category == "apple":
        f = shape_apple(rng, w, h)
    elif category in ("orange", "peach"):
        f = shape_round(rng, w, h, navel=0.003 if category == "orange" else 0.0,
                        crease=rng.uniform(0.04, 0.08) if category == "peach" else 0.0,
                        tip=rng.uniform(0.001, 0.004) if category == "peach" else 0.0)
    elif category in ("lemon", "lime"):
        f = shape_lying(rng, w, h, tip=rng.uniform(0.003, 0.007) if category == "lemon" else rng.uniform(0.0, 0.002))
    elif category == "pear":
        f = shape_pear(rng, w, h)
    elif category == "pepper":
        f = shape_pepper(rng, w, h)
    elif category == "potato":
        f = shape_potato(rng, w, h, w * rng.uniform(1.3, 1.8))
    elif category == "tomato":
        f = shape_tomato(rng, w, h)
    else:
        f = shape_plate(rng, w, h)
    verts, uvs, faces = mesh(f)
    verts, size = place_on_table(verts)
    colour, base = make_colour(rng, category, spec)
    write_png(os.path.join(TEXTURES, f"produce_{name}.png"), TEX_W, TEX_H, texture_rows(rng, colour))

    sx, sy, sz = size
    if category == "plate":
        collision = (f'<geom name="{name}_hull" class="object_collision" type="cylinder" '
                     f'size="{max(sx, sy) / 2:.4f} {sz / 2:.4f}" pos="0 0 {sz / 2:.4f}"/>')
        volume = math.pi * (sx / 2) ** 2 * 0.006
        unit = ((3 * (sx / 2) ** 2 + sz ** 2) / 12,) * 2 + ((sx / 2) ** 2 / 2,)
        mass = round(rng.uniform(0.30, 0.45), 3)
    else:
        collision = (f'<geom name="{name}_hull" class="object_collision" type="ellipsoid" condim="6" '
                     f'friction="1 0.01 0.0005" size="{sx / 2:.4f} {sy / 2:.4f} {sz / 2:.4f}" pos="0 0 {sz / 2:.4f}"/>')
        volume = 4 / 3 * math.pi * sx * sy * sz / 8 * 0.92
        unit = ((sy * sy + sz * sz) / 20, (sx * sx + sz * sz) / 20, (sx * sx + sy * sy) / 20)
        mass = round(DENSITY * volume, 3)
    spec_gloss, shininess = spec["gloss"]
    vertex = " ".join(f"{c:.5f}" for v in verts for c in v)
    texcoord = " ".join(f"{c:.4f}" for uv in uvs for c in uv)
    face = " ".join(str(i) for tri in faces for i in tri)
    geoms = [f'<geom name="{name}" class="object_visual" type="mesh" mesh="{name}" material="{name}"/>', collision]
    geoms += details(name, category, rng, size, spec)
    body = "\n      ".join(geoms)
    dims = f"{sx:.3f} x {sy:.3f} x {sz:.3f} m"
    x, y, z = default_pose(category, index)
    text = f"""<!-- {name}: {category} instance ({dims}, {mass} kg). Written by models/tools/make_produce.py. -->
<mujoco>
  <asset>
    <!-- The path is relative to scenes/; sortcell finds the texture by its name from anywhere. -->
    <texture name="{name}" type="2d" file="../models/objects/textures/produce_{name}.png"/>
    <material name="{name}" texture="{name}" specular="{spec_gloss}" shininess="{shininess}"/>
    <mesh name="{name}"
          vertex="{vertex}"
          texcoord="{texcoord}"
          face="{face}"/>
  </asset>
  <worldbody>
    <body name="{name}" pos="{x:.3f} {y:.3f} {z:.3f}" childclass="object">
      <freejoint name="{name}_free"/>
      <inertial pos="0 0 {sz / 2:.4f}" mass="{mass}" diaginertia="{' '.join(f'{mass * u:.3g}' for u in unit)}"/>
      {body}
    </body>
  </worldbody>
</mujoco>
"""
    with open(os.path.join(OBJECTS, f"{name}.inc.xml"), "w") as out:
        out.write(text)
    return dims, mass


def default_pose(category, index):
    """scenes/produce.xml: an 8 x 8 grid of the produce on the table between the bins, apart (the
    widest, 85 mm, 9 cm apart; lemons lie along x, 97 mm apart), plates stacked in two piles beyond
    the bins."""
    categories = [c for c in CATEGORIES if c != "plate"]
    if category == "plate":
        return 0.76, -0.6 if index % 2 == 0 else 0.6, 0.025 * (index // 2)
    k = categories.index(category) * INSTANCES + index
    return 0.2 + 0.097 * (k // 8), -0.315 + 0.09 * (k % 8), 0.0


def main():
    os.makedirs(TEXTURES, exist_ok=True)
    yaml_lines = ["# The produce set, after the categories of the public RGB-D dataset in the paper's",
                  "# experiments 1 and 2: seven instances per category. Written by models/tools/make_produce.py.",
                  "name: produce", "objects:"]
    names = []
    for category in CATEGORIES:
        for i in range(INSTANCES):
            name = f"{category}{i + 1}"
            make_instance(name, category, i)
            names.append(name)
            yaml_lines += [f"  - name: {name}", f"    category: {category}", f"    instance: {name}",
                           f"    model: ../../models/objects/{name}.inc.xml"]
    with open(os.path.join(ROOT, "scenes", "objects", "produce.yaml"), "w") as out:
        out.write("\n".join(yaml_lines) + "\n")
    includes = "\n".join(f'  <include file="../models/objects/{n}.inc.xml"/>' for n in names)
    scene = f"""<!--
  The cell with every produce instance (a grid over the table and beyond it, plates beside it): for
  viewing the set.
    mujoco-simulate scenes/produce.xml
  Written by models/tools/make_produce.py. Object set: scenes/objects/produce.yaml.
-->
<mujoco model="sortcell_produce">
  <compiler angle="radian" autolimits="true"/>
  <include file="../models/cell/cell.inc.xml"/>
  <include file="../models/cell/bins.inc.xml"/>
  <!-- Seventy objects resting on the table need more contacts and constraint rows than MuJoCo's
       default budget. -->
  <size nconmax="500" njmax="4000"/>
  <include file="../models/gripper/gripper.inc.xml"/>
  <include file="../models/ur5/ur5.inc.xml"/>
  <include file="../models/objects/objects.inc.xml"/>

{includes}
</mujoco>
"""
    with open(os.path.join(ROOT, "scenes", "produce.xml"), "w") as out:
        out.write(scene)


if __name__ == "__main__":
    main()
