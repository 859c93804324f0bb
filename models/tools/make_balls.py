#!/usr/bin/env python3
"""Writes the ball variety (models/objects/ballv<k>.inc.xml with their textures in
models/objects/textures/) and scenes/objects/ball_variety.yaml.

Why: the recognition model is trained in simulation only and must name real balls of any kind
"ball" (a toy soccer ball, a tennis ball, a rubber ball seen by a Kinect v1). One ball model teaches
it one colour; this set teaches it the category: fourteen balls of the common kinds, each drawn from
the kind's range of size, colour (hue, saturation and brightness, dark ones too), panel layout and
surface, none tuned to one real ball. They are training variety only, never placed in episodes.

  soccer      truncated icosahedron panels (12 pentagons, 20 hexagons), classic, coloured and dark;
              the panels pillowed so the seams are shallow grooves (1-2 mm)
  tennis      felt in optic yellow or another colour, the curved seam band, fuzz
  baseball    white leather or optic yellow (softball), the curved seam with red V-stitches
  plain       solid colours, glossy rubber, matte plastic (a faint mould line), solid rubber
  beach       coloured gores about an axis with caps at its poles
  basketball  orange to brown, dark lines, pebbled (bumps under 0.5 mm)
  volleyball  eighteen curved panels in six sections of three strips, white or coloured

Each ball is a UV sphere displaced radially by its kind (pillowed panels, grooves, pebbles, fuzz)
with a latitude-longitude texture on the visual mesh, its mean surface touching z = 0 of the body
frame; it touches the world through one sphere of its mean radius under the mesh, with the produce's
rolling friction. Mass from the kind's build: a hollow shell (areal density; tennis ball 58 g at
6.7 cm) or solid (density; softball 180 g at 9.7 cm).

Reproducible: everything is drawn from one seeded generator per instance. The outputs are committed;
rerun this after editing the tables below:
    python3 models/tools/make_balls.py
Pure Python (no numpy or imaging library): PNGs are written with zlib (texture_tools.py).
"""
import colorsys
import math
import os
import random

from texture_tools import hsv, jitter_hsv, mix, smoothstep, write_png

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OBJECTS = os.path.join(ROOT, "models", "objects")
TEXTURES = os.path.join(OBJECTS, "textures")
SEED = 29
TEX_W, TEX_H = 256, 128     # texture: longitude across, latitude down (top row = top of the ball)
AA = 0.012                  # rad, soft edge of painted lines and panel borders (about half a texel)

# Per kind: diameter range (m), mesh (rings, meridians), build: ("hollow", areal density kg/m^2 range)
# or ("solid", density kg/m^3 range).
KINDS = {
    "soccer": dict(diameter=(0.058, 0.092), mesh=(32, 48), build=("hollow", (2.0, 3.5))),
    "tennis": dict(diameter=(0.060, 0.070), mesh=(24, 36), build=("hollow", (3.8, 4.3))),
    "baseball": dict(diameter=(0.070, 0.076), mesh=(24, 36), build=("solid", (640, 700))),
    "softball": dict(diameter=(0.088, 0.095), mesh=(24, 36), build=("solid", (360, 400))),
    "plain_rubber": dict(diameter=(0.060, 0.090), mesh=(24, 36), build=("hollow", (2.0, 3.5))),
    "plain_plastic": dict(diameter=(0.065, 0.095), mesh=(24, 36), build=("hollow", (0.8, 1.5))),
    "plain_solid": dict(diameter=(0.055, 0.065), mesh=(24, 36), build=("solid", (1050, 1200))),
    "beach": dict(diameter=(0.075, 0.095), mesh=(32, 48), build=("hollow", (0.4, 0.7))),
    "basketball": dict(diameter=(0.060, 0.085), mesh=(32, 48), build=("hollow", (3.0, 4.0))),
    "volleyball": dict(diameter=(0.065, 0.090), mesh=(32, 48), build=("hollow", (2.0, 3.0))),
}

# The fourteen instances: (kind, style). Styles pick the palette within a kind.
INSTANCES = [
    ("soccer", "classic"), ("tennis", "classic"), ("plain_rubber", "warm"), ("baseball", "white"),
    ("soccer", "colour"), ("basketball", ""), ("plain_plastic", "dark"), ("beach", ""),
    ("tennis", "colour"), ("volleyball", "white"), ("softball", "yellow"), ("soccer", "dark"),
    ("plain_solid", "cool"), ("volleyball", "colour"),
]

# Palettes, HSV with h in degrees.
WHITE = (45, 0.04, 0.93)
PALETTES = {
    "soccer_light": [(55, 0.85, 0.95), (30, 0.85, 0.97), (200, 0.45, 0.95), (90, 0.7, 0.85), (0, 0.0, 0.93)],
    "soccer_dark_panel": [(225, 0.85, 0.45), (355, 0.85, 0.6), (0, 0.0, 0.08), (140, 0.8, 0.4), (275, 0.7, 0.45)],
    "soccer_dark_hex": [(225, 0.8, 0.25), (350, 0.8, 0.3), (0, 0.0, 0.15), (150, 0.7, 0.22)],
    "soccer_bright_pent": [(0, 0.0, 0.92), (52, 0.85, 0.95), (0, 0.0, 0.7), (25, 0.9, 0.95)],
    "felt": [(330, 0.55, 0.9), (210, 0.7, 0.75), (355, 0.8, 0.75), (125, 0.6, 0.45), (275, 0.5, 0.55)],
    "warm": [(0, 0.85, 0.8), (330, 0.6, 0.9), (25, 0.9, 0.95), (350, 0.9, 0.5)],
    "dark": [(225, 0.8, 0.35), (280, 0.6, 0.45), (140, 0.7, 0.3), (200, 0.5, 0.25)],
    "cool": [(110, 0.7, 0.6), (150, 0.75, 0.5), (170, 0.75, 0.6), (300, 0.6, 0.7), (0, 0.0, 0.12)],
    "beach": [(0, 0.85, 0.9), (50, 0.9, 0.97), (215, 0.85, 0.85), (120, 0.75, 0.7), (28, 0.9, 0.97),
              (280, 0.6, 0.75)],
    "volley": [((215, 0.85, 0.6), (52, 0.9, 0.95), WHITE), ((0, 0.85, 0.75), WHITE, (220, 0.8, 0.55)),
               ((52, 0.9, 0.95), (215, 0.8, 0.45), WHITE), ((130, 0.7, 0.5), WHITE, (355, 0.8, 0.7))],
}


def pick(rng, palette, **jitter):
    return hsv(*jitter_hsv(rng, rng.choice(palette), **jitter))


def scale(c, k):
    return tuple(max(0.0, min(1.0, x * k)) for x in c)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(v):
    n = math.sqrt(dot(v, v))
    return (v[0] / n, v[1] / n, v[2] / n)


def line(dist, half_width):
    """1 on a painted line of `half_width` (rad) about dist = 0, 0 away from it, soft edges."""
    return 1 - smoothstep(half_width - AA, half_width + AA, abs(dist))


# ---------------------------------------------------------------------------------------------------
# Directions on the unit sphere: d(t, phi) with t = 0 at the bottom pole, 1 at the top (as produce).

def direction(t, phi):
    a = math.pi * t
    return (math.sin(a) * math.cos(phi), math.sin(a) * math.sin(phi), -math.cos(a))


def random_rotation(rng):
    """A uniformly random rotation (Shoemake), as a function of a direction."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    w, x = math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2)
    y, z = math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3)
    m = ((1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
         (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
         (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)))
    return lambda d: (dot(m[0], d), dot(m[1], d), dot(m[2], d))


def make_bumps(rng, n, freq):
    """Smooth noise over the sphere, about unit spread: a sum of plane waves of frequency `freq`."""
    waves = [(normalize((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))), rng.uniform(0, 2 * math.pi),
              freq * rng.uniform(0.7, 1.3)) for _ in range(n)]
    k = math.sqrt(2.0 / n)
    return lambda d: k * sum(math.sin(f * dot(d, v) + p) for v, p, f in waves)


def make_smudges(rng, count, strength):
    """Wear and dirt: a brightness factor with a few soft blobs."""
    blobs = [(normalize((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))), rng.uniform(0.2, 0.6),
              rng.uniform(-strength, strength)) for _ in range(count)]
    def f(d):
        k = 1.0
        for v, r, s in blobs:
            c = dot(d, v)
            if c > 0:
                k += s * math.exp(-((1 - c) / (r * r / 2)))
        return k
    return f


# ---------------------------------------------------------------------------------------------------
# Panel layouts.

PHI = (1 + math.sqrt(5)) / 2


def truncated_icosahedron():
    """Faces of the truncated icosahedron as (unit normal, distance of the face plane for edge 1,
    is pentagon); and |n_i/h_i - n_j/h_j| for every pair."""
    pents, hexes = [], [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    for a in (-1, 1):
        for b in (-PHI, PHI):
            pents += [(0, a, b), (a, b, 0), (b, 0, a)]
    for a in (-1 / PHI, 1 / PHI):   # the dual's: icosahedron face centres
        for b in (-PHI, PHI):
            hexes += [(0, b, a), (b, a, 0), (a, 0, b)]
    h5, h6 = math.sqrt((125 + 41 * math.sqrt(5)) / 10) / 2, math.sqrt(1.5 * (7 + 3 * math.sqrt(5))) / 2
    faces = [(normalize(p), h5, True) for p in pents] + [(normalize(p), h6, False) for p in hexes]
    scaled = [tuple(c / h for c in n) for n, h, _ in faces]
    norms = [[math.sqrt(sum((a - b) ** 2 for a, b in zip(si, sj))) for sj in scaled] for si in scaled]
    return faces, scaled, norms


TI_FACES, TI_SCALED, TI_NORMS = truncated_icosahedron()


def soccer_panel(d):
    """(face index, is pentagon, angular distance to the panel's border)."""
    s = [dot(d, n) for n in TI_SCALED]
    i = max(range(len(s)), key=s.__getitem__)
    gap = min((s[i] - s[j]) / TI_NORMS[i][j] for j in range(len(s)) if j != i)
    return i, TI_FACES[i][2], math.asin(max(-1.0, min(1.0, gap)))


class SeamCurve:
    """The tennis-ball curve (two congruent halves): x = a cos u + b cos 3u, y = a sin u - b sin 3u,
    z = 2 sqrt(ab) sin 2u with a + b = 1, on the unit sphere. nearest(d): angular distance (signed by
    side) and arc length of the nearest point."""
    FINE, COARSE = 720, 72

    def __init__(self, b):
        a = 1 - b
        self.points = [(a * math.cos(u) + b * math.cos(3 * u), a * math.sin(u) - b * math.sin(3 * u),
                        2 * math.sqrt(a * b) * math.sin(2 * u))
                       for u in (2 * math.pi * k / self.FINE for k in range(self.FINE))]
        n = self.FINE
        self.sides = [normalize(cross(self.points[k], normalize(tuple(q - p for p, q in zip(
            self.points[k - 1], self.points[(k + 1) % n]))))) for k in range(n)]
        self.arc = [0.0]
        for k in range(1, n + 1):
            p, q = self.points[k - 1], self.points[k % n]
            self.arc.append(self.arc[-1] + math.sqrt(sum((x - y) ** 2 for x, y in zip(p, q))))
        self.length = self.arc[-1]

    def nearest(self, d):
        step = self.FINE // self.COARSE
        k0 = max(range(0, self.FINE, step), key=lambda k: dot(d, self.points[k]))
        k = max(((k0 + o) % self.FINE for o in range(-step - 2, step + 3)), key=lambda k: dot(d, self.points[k]))
        ang = math.acos(max(-1.0, min(1.0, dot(d, self.points[k]))))
        return math.copysign(ang, dot(d, self.sides[k])), self.arc[k]


# ---------------------------------------------------------------------------------------------------
# Kinds: each returns (radial(d) -> displacement in m, colour(d, noise) -> rgb, (specular, shininess),
# a short description of its colours).

def colour_name(c):
    h, s, v = colorsys.rgb_to_hsv(*c)
    if v < 0.2:
        return "black"
    if s < 0.18:
        return "white" if v > 0.75 else "grey"
    names = [(15, "red"), (40, "orange"), (70, "yellow"), (160, "green"), (195, "cyan"), (250, "blue"), (290, "purple"),
             (345, "pink"), (360, "red")]
    name = next(n for limit, n in names if h * 360 < limit)
    return ("dark " if v < 0.5 else "") + name


def soccer(rng, style, radius):
    rotate = random_rotation(rng)
    if style == "classic":
        hexc, pentc = hsv(*jitter_hsv(rng, WHITE, 8, 0.04, 0.04)), hsv(0, 0, rng.uniform(0.05, 0.14))
    elif style == "colour":
        hexc, pentc = pick(rng, PALETTES["soccer_light"]), pick(rng, PALETTES["soccer_dark_panel"])
    else:
        hexc, pentc = pick(rng, PALETTES["soccer_dark_hex"]), pick(rng, PALETTES["soccer_bright_pent"])
    accent = pick(rng, PALETTES["soccer_dark_panel"] if style != "classic" else [(0, 0, 0.1)])
    accented = {i for i in range(12, 32) if style == "colour" and rng.random() < 0.3}
    depth = 2 * radius * rng.uniform(0.015, 0.022)      # seam groove below the panel tops
    rise = rng.uniform(0.07, 0.11)                       # rad over which a panel rises from its seam
    seam_dark, seam_w = rng.uniform(0.35, 0.6), rng.uniform(0.006, 0.012)
    smudge = make_smudges(rng, 6, 0.08)

    def radial(d):
        _, _, dist = soccer_panel(rotate(d))
        return -depth * math.exp(-dist / rise)

    def colour(d, noise):
        r = rotate(d)
        i, pent, dist = soccer_panel(r)
        c = pentc if pent else (accent if i in accented else hexc)
        c = scale(c, 1 - seam_dark * line(dist, seam_w) - 0.12 * math.exp(-dist / 0.03))
        return scale(c, smudge(d) * (1 + 0.02 * noise))

    desc = f"{colour_name(hexc)} hexagons, {colour_name(pentc)} pentagons"
    if accented:
        desc += f", {len(accented)} {colour_name(accent)}"
    return radial, colour, (0.35, 0.4), desc


def tennis(rng, style, radius):
    rotate, curve = random_rotation(rng), SeamCurve(rng.uniform(0.2, 0.28))
    felt = hsv(*jitter_hsv(rng, (66, 0.78, 0.92), 5, 0.06, 0.05)) if style == "classic" else pick(rng, PALETTES["felt"])
    h, s, _ = colorsys.rgb_to_hsv(*felt)
    seamc = hsv(h * 360, s * 0.15, rng.uniform(0.85, 0.95))
    band, depth = rng.uniform(0.032, 0.045), rng.uniform(0.0002, 0.0004)
    fuzz, smudge = make_bumps(rng, 16, 2 * math.pi * radius / 0.003), make_smudges(rng, 8, 0.1)

    def radial(d):
        dist, _ = curve.nearest(rotate(d))
        return 0.00008 * fuzz(d) - depth * line(dist, band)

    def colour(d, noise):
        dist, _ = curve.nearest(rotate(d))
        c = mix(felt, seamc, line(dist, band))
        return scale(c, smudge(d) * (1 + 0.09 * noise))

    return radial, colour, (0.04, 0.05), f"{colour_name(felt)} felt, {colour_name(seamc)} seam"


def baseball(rng, style, radius):
    rotate, curve = random_rotation(rng), SeamCurve(rng.uniform(0.22, 0.3))
    leather = hsv(*jitter_hsv(rng, (44, 0.09, 0.91), 8, 0.05, 0.04)) if style == "white" \
        else hsv(*jitter_hsv(rng, (60, 0.85, 0.94), 4, 0.05, 0.04))
    thread = hsv(*jitter_hsv(rng, (358, 0.85, 0.75), 5, 0.08, 0.1))
    stitches = rng.randint(70, 100)              # V-stitches along the whole seam
    spacing = curve.length / stitches
    inner, outer, slant = rng.uniform(0.012, 0.02), rng.uniform(0.055, 0.075), rng.uniform(0.4, 0.8)
    smudge = make_smudges(rng, 8, 0.08)

    def radial(d):
        dist, _ = curve.nearest(rotate(d))
        return -0.0003 * line(dist, 0.01)

    def colour(d, noise):
        dist, s = curve.nearest(rotate(d))
        c = scale(leather, 1 - 0.25 * line(dist, 0.006))
        x = abs(dist)
        if inner < x < outer:
            # Each stitch a short slanted dash either side of the seam: together a V along it.
            phase = (s / spacing - slant * (x - inner) / (outer - inner)) % 1.0
            w = smoothstep(0.0, 0.08, phase) * (1 - smoothstep(0.28, 0.36, phase))
            w *= smoothstep(inner, inner + 0.006, x) * (1 - smoothstep(outer - 0.006, outer, x))
            c = mix(c, thread, w)
        return scale(c, smudge(d) * (1 + 0.03 * noise))

    return radial, colour, (0.2, 0.25), f"{colour_name(leather)} leather, {colour_name(thread)} stitches"


def plain(rng, style, radius, kind):
    base = pick(rng, PALETTES[style], dh=8, ds=0.08, dv=0.08)
    rotate = random_rotation(rng)
    mould = kind == "plain_plastic" or rng.random() < 0.4
    smudge = make_smudges(rng, 6, 0.06)
    gloss = {"plain_rubber": (0.7, 0.8), "plain_plastic": (0.12, 0.15), "plain_solid": (0.5, 0.6)}[kind]

    def radial(d):
        return 0.0

    def colour(d, noise):
        c = scale(base, 1 - (0.15 * line(rotate(d)[2], 0.005) if mould else 0.0))
        return scale(c, smudge(d) * (1 + 0.02 * noise))

    finish = "glossy" if gloss[0] > 0.4 else "matte"
    return radial, colour, gloss, f"{colour_name(base)}, {finish}" + (", mould line" if mould else "")


def beach(rng, style, radius):
    rotate = random_rotation(rng)
    gores = rng.choice((4, 6, 6, 8))
    if rng.random() < 0.5:   # every other gore white
        colours = [pick(rng, PALETTES["beach"]) if k % 2 == 0 else hsv(*WHITE) for k in range(gores)]
    else:
        palette = PALETTES["beach"][:]
        rng.shuffle(palette)
        colours = [hsv(*jitter_hsv(rng, palette[k % len(palette)])) for k in range(gores)]
    cap, capc = rng.uniform(0.2, 0.35), hsv(*WHITE) if rng.random() < 0.6 else pick(rng, PALETTES["beach"])
    depth = 2 * radius * rng.uniform(0.006, 0.01)
    smudge = make_smudges(rng, 5, 0.06)

    def gore(r):
        a = math.atan2(r[1], r[0]) % (2 * math.pi)
        k = int(a / (2 * math.pi / gores)) % gores
        off = a - (k + 0.5) * 2 * math.pi / gores    # from the gore's middle
        edge = (math.pi / gores - abs(off)) * math.sqrt(max(0.0, 1 - r[2] * r[2]))  # to its seam
        return k, edge

    def radial(d):
        r = rotate(d)
        _, edge = gore(r)
        return -depth * math.exp(-edge / 0.1) * (1 - smoothstep(math.cos(cap + 0.1), math.cos(cap), abs(r[2])))

    def colour(d, noise):
        r = rotate(d)
        k, edge = gore(r)
        c = scale(colours[k], 1 - 0.15 * line(edge, 0.004))
        c = mix(c, capc, smoothstep(math.cos(cap) - 0.006, math.cos(cap) + 0.006, abs(r[2])))
        return scale(c, smudge(d) * (1 + 0.02 * noise))

    names = sorted({colour_name(c) for c in colours})
    return radial, colour, (0.6, 0.6), f"{gores} gores ({', '.join(names)}), {colour_name(capc)} caps"


def basketball(rng, style, radius):
    rotate = random_rotation(rng)
    base = hsv(*jitter_hsv(rng, (rng.uniform(14, 26), 0.82, rng.uniform(0.45, 0.85)), 2, 0.08, 0.04))
    linec = hsv(rng.uniform(0, 30), 0.4, rng.uniform(0.05, 0.15))
    w, ring, wave = rng.uniform(0.018, 0.026), rng.uniform(0.65, 0.75), rng.uniform(0.15, 0.22)
    pebbles = make_bumps(rng, 24, 2 * math.pi * radius / 0.0025)
    smudge = make_smudges(rng, 6, 0.08)

    def lines(r):
        theta = math.atan2(r[2], r[0])
        return min(abs(math.asin(max(-1.0, min(1.0, r[0])))), abs(math.asin(max(-1.0, min(1.0, r[2])))),
                   abs(abs(r[1]) - (ring + wave * math.cos(2 * theta))))

    def radial(d):
        bump = max(-0.00025, min(0.00025, 0.00012 * pebbles(d)))   # pebbles: 0.5 mm at most
        return bump - 0.0004 * line(lines(rotate(d)), w)

    def colour(d, noise):
        c = mix(base, linec, line(lines(rotate(d)), w))
        return scale(c, smudge(d) * (1 + 0.07 * noise + 0.05 * pebbles(d)))

    return radial, colour, (0.15, 0.2), f"{colour_name(base)}, {colour_name(linec)} lines, pebbled"


def volleyball(rng, style, radius):
    rotate = random_rotation(rng)
    if style == "white":
        strip_colours = [hsv(*jitter_hsv(rng, WHITE, 8, 0.04, 0.03))] * 3
    else:
        strip_colours = [hsv(*jitter_hsv(rng, c, 4, 0.05, 0.05)) for c in rng.choice(PALETTES["volley"])]
    depth = 2 * radius * rng.uniform(0.008, 0.014)
    seam_w = rng.uniform(0.005, 0.01)
    smudge = make_smudges(rng, 6, 0.08)

    def panel(r):
        a = [abs(x) for x in r]
        k = max(range(3), key=a.__getitem__)              # the section: a cube face
        j = max((i for i in range(3) if i != k), key=a.__getitem__)
        cube_edge = math.asin(min(1.0, (a[k] - a[j]) / math.sqrt(2)))
        b = (k + 1) % 3                                   # strips across axis b
        x = r[b] / a[k]
        strip = 0 if x < -1 / 3 else (1 if x < 1 / 3 else 2)
        n = math.sqrt(1 + 1 / 9)
        strip_edge = min(abs(r[b] - a[k] / 3), abs(r[b] + a[k] / 3)) / n
        return k, strip, min(cube_edge, math.asin(min(1.0, strip_edge)))

    def radial(d):
        _, _, dist = panel(rotate(d))
        return -depth * math.exp(-dist / 0.09)

    def colour(d, noise):
        k, strip, dist = panel(rotate(d))
        c = strip_colours[(strip + k) % 3]
        c = scale(c, 1 - 0.4 * line(dist, seam_w) - 0.1 * math.exp(-dist / 0.03))
        return scale(c, smudge(d) * (1 + 0.02 * noise))

    names = ", ".join(dict.fromkeys(colour_name(c) for c in strip_colours))
    return radial, colour, (0.3, 0.35), f"{names} panels"


# ---------------------------------------------------------------------------------------------------

def mesh(radial, radius, n_lat, n_lon):
    """Vertices (centred at the origin), texture coordinates and faces of a lat-long grid (a seam column
    and pole rows, as produce), and the area-weighted mean radius. MuJoCo maps v = 0 to the texture's
    first row, so v = 1 - t keeps the PNG's top row at the top of the ball."""
    verts, uvs, faces = [], [], []
    total, weight = 0.0, 0.0
    for i in range(n_lat + 1):
        t = i / n_lat
        for j in range(n_lon + 1):
            d = direction(t, 2 * math.pi * (j % n_lon) / n_lon)
            r = radius + radial(d)
            verts.append((r * d[0], r * d[1], r * d[2]))
            uvs.append((j / n_lon, 1 - t))
            if j < n_lon:
                w = math.sin(math.pi * t) if 0 < i < n_lat else math.sin(math.pi / (4 * n_lat)) / 4
                total, weight = total + w * r, weight + w
    row = n_lon + 1
    for i in range(n_lat):
        for j in range(n_lon):
            a, b, c, d = i * row + j, i * row + j + 1, (i + 1) * row + j + 1, (i + 1) * row + j
            if i > 0:
                faces.append((a, b, c))
            if i < n_lat - 1:
                faces.append((a, c, d))
    return verts, uvs, faces, total / weight


def texture_rows(rng, colour):
    rows = []
    for row in range(TEX_H):
        t = 1 - (row + 0.5) / TEX_H
        rows.append([colour(direction(t, 2 * math.pi * (col + 0.5) / TEX_W), rng.gauss(0, 1)) for col in range(TEX_W)])
    return rows


def default_pose(index):
    """Two rows of seven on the table between the bins, 10 cm apart (for viewing the set together)."""
    return 0.35 + 0.1 * (index // 7), -0.3 + 0.1 * (index % 7), 0.0


def make_instance(name, kind, style, index):
    rng = random.Random(f"{SEED}-{name}")
    spec = KINDS[kind]
    radius = rng.uniform(*spec["diameter"]) / 2
    if kind == "soccer":
        radial, colour, gloss, desc = soccer(rng, style, radius)
    elif kind == "tennis":
        radial, colour, gloss, desc = tennis(rng, style, radius)
    elif kind in ("baseball", "softball"):
        radial, colour, gloss, desc = baseball(rng, style, radius)
    elif kind.startswith("plain"):
        radial, colour, gloss, desc = plain(rng, style, radius, kind)
    elif kind == "beach":
        radial, colour, gloss, desc = beach(rng, style, radius)
    elif kind == "basketball":
        radial, colour, gloss, desc = basketball(rng, style, radius)
    else:
        radial, colour, gloss, desc = volleyball(rng, style, radius)
    n_lat, n_lon = spec["mesh"]
    verts, uvs, faces, r_mean = mesh(radial, radius, n_lat, n_lon)
    # The mean surface touches z = 0: the collision sphere's bottom (pillowed panel tops may dip a
    # fraction of a millimetre below it, seams stand above it).
    verts = [(x, y, z + r_mean) for x, y, z in verts]
    write_png(os.path.join(TEXTURES, f"ball_{name}.png"), TEX_W, TEX_H, texture_rows(rng, colour))

    build, density_range = spec["build"]
    density = rng.uniform(*density_range)
    if build == "hollow":
        mass, unit = density * 4 * math.pi * r_mean ** 2, 2 / 3 * r_mean ** 2
    else:
        mass, unit = density * 4 / 3 * math.pi * r_mean ** 3, 2 / 5 * r_mean ** 2
    mass = round(mass, 4)
    specular, shininess = gloss
    vertex = " ".join(f"{c:.5f}" for v in verts for c in v)
    texcoord = " ".join(f"{c:.4f}" for uv in uvs for c in uv)
    face = " ".join(str(i) for tri in faces for i in tri)
    x, y, z = default_pose(index)
    collision = (f'<geom name="{name}_hull" class="object_collision" type="sphere" condim="6" '
                 f'friction="1 0.01 0.0005" size="{r_mean:.4f}" pos="0 0 {r_mean:.4f}"/>')
    label = kind.replace("_", " ") + (f" ({style})" if style else "")
    text = f"""<!-- {name}: ball variety, {label}: {desc}; diameter {2 * r_mean:.3f} m, {mass} kg ({build}).
     Written by models/tools/make_balls.py. -->
<mujoco>
  <asset>
    <!-- The path is relative to scenes/; sortcell finds the texture by its name from anywhere. -->
    <texture name="{name}" type="2d" file="../models/objects/textures/ball_{name}.png"/>
    <material name="{name}" texture="{name}" specular="{specular}" shininess="{shininess}"/>
    <mesh name="{name}"
          vertex="{vertex}"
          texcoord="{texcoord}"
          face="{face}"/>
  </asset>
  <worldbody>
    <body name="{name}" pos="{x:.3f} {y:.3f} {z:.3f}" childclass="object">
      <freejoint name="{name}_free"/>
      <inertial pos="0 0 {r_mean:.4f}" mass="{mass}" diaginertia="{' '.join([f'{mass * unit:.3g}'] * 3)}"/>
      <geom name="{name}" class="object_visual" type="mesh" mesh="{name}" material="{name}"/>
      {collision}
    </body>
  </worldbody>
</mujoco>
"""
    with open(os.path.join(OBJECTS, f"{name}.inc.xml"), "w") as out:
        out.write(text)
    return label, 2 * r_mean, mass, desc


def main():
    os.makedirs(TEXTURES, exist_ok=True)
    yaml_lines = ["# Balls of many kinds for training the ball category (never placed in episodes by themselves). "
                  "Written by models/tools/make_balls.py.", "name: ball_variety", "objects:"]
    for index, (kind, style) in enumerate(INSTANCES):
        name = f"ballv{index + 1}"
        label, diameter, mass, desc = make_instance(name, kind, style, index)
        print(f"{name:8s} {label:24s} {diameter * 1000:5.1f} mm {mass * 1000:6.1f} g  {desc}")
        yaml_lines += [f"  - name: {name}", "    category: ball", f"    instance: {name}",
                       f"    model: ../../models/objects/{name}.inc.xml"]
    with open(os.path.join(ROOT, "scenes", "objects", "ball_variety.yaml"), "w") as out:
        out.write("\n".join(yaml_lines) + "\n")


if __name__ == "__main__":
    main()
