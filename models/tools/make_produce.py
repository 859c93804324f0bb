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

The training variety (VARIETY): six more members of each category, <category>v<k>, for training only,
covering each category's real colour range (scenes/objects/produce_variety.yaml, for a set's
training_variety; produce.yaml does not name it yet, see docs/cell.md, Your own objects; not in scenes/produce.xml). They have their own seed; the set's own instances are
drawn exactly as before.

Reproducible: everything is drawn from one seeded generator per instance. The outputs are committed;
rerun this after editing the tables below:
    python3 models/tools/make_produce.py
Pure Python (no numpy or imaging library): PNGs are written with zlib (texture_tools.py).
"""
import math
import os
import random

from texture_tools import hsv, jitter_hsv, mix, smoothstep, write_png

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
# The two red apple palettes are as saturated as a real red apple looks to a Kinect: rendered through the
# simulated Kinect, red apples of saturation 0.80 and 0.75 came out at 144/255 and 140/255 against 195 for the
# real apple_2 of the RGB-D Object Dataset (docs/recognition.md, real views), and the set's only saturated reds
# were its tomatoes and peppers.
CATEGORIES = {
    "apple": dict(width=(0.066, 0.082), aspect=(0.80, 0.95),
                  palettes=[((358, 0.95, 0.55), (45, 0.70, 0.85)), ((350, 0.97, 0.40), (10, 0.95, 0.50)),
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

# The training variety: VARIETY_INSTANCES more members of each category (<category>v<k>), for training
# only (scenes/objects/produce_variety.yaml, for a set's training_variety; produce.yaml does not name it
# yet: the produce model trained with it did worse on real apples and in its own cross-validation), covering each
# category's real colour range: instance k wears palette k - 1 (one of each family), jittered. Sizes
# and proportions are a little wider than the set's own. Drawn from their own seed, so the set's own
# instances above stay as they were.
#   palettes: (label, pattern, base HSV, second HSV, amount range); patterns:
#     uniform  the base colour, mottled (second unused)
#     blush    a patch of the second colour on one side (amount: its strength)
#     streak   Gala/Fuji: a wash of the second colour over one side (amount: its cover) with
#              meridional streaks of it, darker
#     ends     towards the stem (lemons, limes: both ends) the colour turns to the second one
#     patches  irregular blotches of the second colour (amount: the share of the surface)
#     band     plates: a band of the second colour on the rim (amount: its width), sometimes a line at
#              the rim's edge
#   spots: (count range, (dh, s factor, v factor)) relative to the base colour (lenticels, pores, eyes)
VARIETY_INSTANCES = 6
VARIETY_SEED = 71
VARIETY = {
    "apple": dict(width=(0.060, 0.090), aspect=(0.76, 1.00), spots=((20, 70), (8, 0.45, 1.5)), palettes=[
        ("bright red", "uniform", (357, 0.88, 0.62), (355, 0.90, 0.50), (0, 0)),
        ("dark red (Red Delicious)", "streak", (352, 0.90, 0.30), (345, 0.92, 0.22), (0.7, 1.0)),
        ("red streaked over yellow (Gala, Fuji)", "streak", (45, 0.68, 0.86), (2, 0.85, 0.62), (0.55, 0.9)),
        ("green (Granny Smith)", "uniform", (92, 0.72, 0.62), (85, 0.65, 0.70), (0, 0)),
        ("yellow (Golden Delicious)", "blush", (52, 0.75, 0.86), (38, 0.70, 0.82), (0.2, 0.5)),
        ("green with a red blush", "blush", (80, 0.65, 0.70), (358, 0.80, 0.52), (0.5, 0.9))]),
    "orange": dict(width=(0.058, 0.092), aspect=(0.86, 1.02), spots=((250, 400), (0, 1.0, 0.84)), palettes=[
        ("deep orange", "uniform", (26, 0.94, 0.92), (24, 0.95, 0.85), (0, 0)),
        ("light orange", "uniform", (34, 0.85, 0.96), (36, 0.80, 0.92), (0, 0)),
        ("red-orange with a red blush (blood orange)", "blush", (18, 0.90, 0.82), (4, 0.88, 0.58), (0.4, 0.8)),
        ("orange, regreening (Valencia)", "patches", (30, 0.90, 0.90), (62, 0.70, 0.72), (0.15, 0.35)),
        ("dark orange, shaded", "uniform", (22, 0.95, 0.70), (20, 0.95, 0.60), (0, 0)),
        ("reddish orange (mandarin)", "ends", (20, 0.95, 0.92), (28, 0.90, 0.85), (0.3, 0.6))]),
    "lemon": dict(width=(0.046, 0.064), aspect=(1.25, 1.70), spots=((200, 320), (-2, 1.0, 0.86)), palettes=[
        ("bright yellow", "uniform", (54, 0.86, 0.95), (56, 0.85, 0.90), (0, 0)),
        ("pale yellow", "uniform", (56, 0.58, 0.96), (58, 0.55, 0.90), (0, 0)),
        ("deep yellow", "uniform", (47, 0.92, 0.88), (45, 0.92, 0.80), (0, 0)),
        ("yellow, green ends", "ends", (55, 0.85, 0.90), (75, 0.75, 0.68), (0.6, 1.0)),
        ("greenish, unripe", "uniform", (68, 0.78, 0.78), (75, 0.75, 0.70), (0, 0)),
        ("yellow with brownish blotches", "patches", (52, 0.82, 0.86), (40, 0.70, 0.58), (0.08, 0.2))]),
    "lime": dict(width=(0.040, 0.058), aspect=(1.00, 1.25), spots=((200, 320), (4, 1.0, 0.82)), palettes=[
        ("dark green", "uniform", (105, 0.82, 0.42), (100, 0.80, 0.36), (0, 0)),
        ("mid green", "uniform", (95, 0.76, 0.60), (90, 0.72, 0.55), (0, 0)),
        ("light green", "uniform", (85, 0.62, 0.76), (80, 0.60, 0.72), (0, 0)),
        ("yellow-green", "ends", (72, 0.72, 0.78), (88, 0.72, 0.60), (0.5, 0.9)),
        ("green with yellow patches", "patches", (98, 0.76, 0.55), (62, 0.70, 0.80), (0.15, 0.35)),
        ("very dark green", "uniform", (115, 0.78, 0.30), (110, 0.75, 0.25), (0, 0))]),
    "peach": dict(width=(0.054, 0.080), aspect=(0.86, 1.05), spots=((20, 60), (-20, 1.1, 0.75)), palettes=[
        ("yellow-orange with a red blush", "blush", (35, 0.66, 0.92), (2, 0.80, 0.68), (0.6, 0.95)),
        ("mostly red (nectarine)", "blush", (40, 0.65, 0.85), (352, 0.82, 0.45), (1.0, 1.0)),
        ("white peach: cream with a pink blush", "blush", (38, 0.25, 0.93), (350, 0.48, 0.80), (0.5, 0.9)),
        ("dark red blush over orange", "blush", (30, 0.72, 0.86), (350, 0.85, 0.40), (0.8, 1.0)),
        ("pale yellow, small blush", "blush", (46, 0.50, 0.90), (10, 0.62, 0.80), (0.2, 0.5)),
        ("orange with a red blush", "blush", (28, 0.76, 0.90), (5, 0.85, 0.62), (0.4, 0.8))]),
    "pear": dict(width=(0.056, 0.080), aspect=(1.20, 1.75), spots=((120, 260), (-5, 0.9, 0.7)), palettes=[
        ("green (Anjou)", "uniform", (85, 0.66, 0.62), (80, 0.60, 0.66), (0, 0)),
        ("yellow (ripe Bartlett)", "ends", (55, 0.72, 0.86), (70, 0.65, 0.72), (0.3, 0.7)),
        ("red (Red Anjou)", "ends", (356, 0.72, 0.40), (20, 0.65, 0.35), (0.3, 0.6)),
        ("russet brown (Bosc)", "patches", (30, 0.66, 0.48), (38, 0.55, 0.62), (0.2, 0.45)),
        ("yellow with a red blush", "blush", (52, 0.66, 0.84), (5, 0.72, 0.58), (0.5, 0.9)),
        ("pale green-yellow (Asian, Comice)", "uniform", (62, 0.50, 0.80), (55, 0.55, 0.75), (0, 0))]),
    "pepper": dict(width=(0.062, 0.088), aspect=(0.80, 1.35), spots=((0, 0), (0, 1, 1)), palettes=[
        ("red", "uniform", (358, 0.92, 0.68), (355, 0.90, 0.55), (0, 0)),
        ("dark red", "uniform", (352, 0.92, 0.42), (350, 0.92, 0.34), (0, 0)),
        ("yellow", "uniform", (50, 0.95, 0.92), (46, 0.95, 0.85), (0, 0)),
        ("orange", "uniform", (30, 0.96, 0.92), (25, 0.95, 0.82), (0, 0)),
        ("green", "uniform", (110, 0.85, 0.40), (105, 0.82, 0.32), (0, 0)),
        ("green turning red", "patches", (105, 0.80, 0.40), (0, 0.86, 0.50), (0.25, 0.6))]),
    "plate": dict(width=(0.17, 0.26), aspect=(0.065, 0.11), spots=((0, 0), (0, 1, 1)), palettes=[
        ("white", "uniform", (0, 0.0, 0.96), (0, 0.0, 0.96), (0, 0)),
        ("cream with a gold rim band", "band", (42, 0.15, 0.92), (38, 0.62, 0.66), (0.012, 0.03)),
        ("white with a blue rim band", "band", (210, 0.03, 0.95), (218, 0.65, 0.50), (0.01, 0.035)),
        ("blue", "uniform", (212, 0.55, 0.62), (212, 0.55, 0.62), (0, 0)),
        ("terracotta with a cream rim band", "band", (16, 0.62, 0.66), (40, 0.20, 0.90), (0.008, 0.02)),
        ("green", "uniform", (140, 0.45, 0.55), (140, 0.45, 0.55), (0, 0))]),
    "potato": dict(width=(0.044, 0.072), aspect=(0.50, 0.85), elongation=(1.15, 2.0),
                   spots=((25, 70), (-4, 1.0, 0.68)), palettes=[
        ("russet brown, netted", "patches", (28, 0.56, 0.45), (24, 0.48, 0.34), (0.35, 0.6)),
        ("yellow (Yukon Gold)", "uniform", (42, 0.45, 0.80), (38, 0.48, 0.70), (0, 0)),
        ("red", "patches", (356, 0.60, 0.46), (10, 0.45, 0.62), (0.1, 0.3)),
        ("pale tan, white", "uniform", (38, 0.28, 0.80), (35, 0.32, 0.70), (0, 0)),
        ("dark red", "uniform", (348, 0.58, 0.34), (352, 0.50, 0.42), (0, 0)),
        ("light brown, earthy", "patches", (34, 0.55, 0.62), (28, 0.55, 0.45), (0.2, 0.45))]),
    "tomato": dict(width=(0.050, 0.082), aspect=(0.66, 0.95), spots=((0, 0), (0, 1, 1)), palettes=[
        ("red", "uniform", (2, 0.88, 0.78), (6, 0.88, 0.72), (0, 0)),
        ("dark red", "uniform", (356, 0.90, 0.48), (354, 0.90, 0.40), (0, 0)),
        ("orange", "uniform", (20, 0.90, 0.90), (24, 0.88, 0.85), (0, 0)),
        ("yellow", "uniform", (46, 0.86, 0.90), (42, 0.86, 0.85), (0, 0)),
        ("green, unripe", "ends", (88, 0.62, 0.62), (80, 0.55, 0.72), (0.3, 0.6)),
        ("red with green shoulders", "ends", (4, 0.86, 0.70), (70, 0.62, 0.52), (0.6, 1.0))]),
}


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


def smooth_noise(rng, terms=6):
    """A smooth random field over the surface, periodic in u, about unit spread: (u, t) -> float. It
    fades out at the poles (t = 0, 1), where all longitudes meet, so that it does not swirl there."""
    waves = [(rng.randint(1, 4), rng.uniform(0.5, 4.0), rng.uniform(0, 2 * math.pi), rng.uniform(0, 2 * math.pi))
             for _ in range(terms)]
    norm = math.sqrt(terms / 4.0)
    return lambda u, t: math.sin(math.pi * t) * sum(math.sin(2 * math.pi * k * u + p) * math.cos(math.pi * m * t + q)
                                                    for k, m, p, q in waves) / norm


def make_variety_colour(palette):
    """A colour maker (like make_colour) for one palette of VARIETY."""
    label, pattern, base_hsv, second_hsv, amounts = palette

    def maker(rng, category, spec):
        b, s2 = jitter_hsv(rng, base_hsv, 5, 0.05, 0.07), jitter_hsv(rng, second_hsv, 5, 0.05, 0.07)
        base, second = hsv(*b), hsv(*s2)
        amount = rng.uniform(*amounts)
        n_lo, n_hi = spec["spots"][0]
        dh, fs, fv = spec["spots"][1]
        spots = [(rng.random(), rng.uniform(0.05, 0.95), rng.uniform(0.008, 0.018)) for _ in range(rng.randint(n_lo, n_hi))]
        spot_colour = hsv(b[0] + dh, b[1] * fs, b[2] * fv)
        blotch, mottle = smooth_noise(rng), smooth_noise(rng)
        wobble = smooth_noise(rng)
        mottling = rng.uniform(0.03, 0.08)
        speckle = {"orange": 0.05, "lemon": 0.05, "lime": 0.05, "potato": 0.08, "pear": 0.05}.get(category, 0.03)
        side_u, side_t = rng.random(), rng.uniform(0.35, 0.7)
        # How far round the blush (the streaked wash) reaches; a strong blush covers more.
        spread = rng.uniform(0.15, 0.30) * (0.6 + amount) if pattern == "blush" else rng.uniform(0.35, 0.6)
        n_streaks, wash = rng.randint(24, 48), rng.uniform(0.35, 0.7)
        threshold = 0.9 - 1.8 * amount          # patches: about `amount` of the surface above it
        ends_from = rng.uniform(0.45, 0.7)
        band_at, edge_line = rng.uniform(0.585, 0.625), rng.random() < 0.5

        def colour(u, t, noise):
            # MuJoCo puts texcoord v = 0 at the image's top row, so the row texture_rows computes for t
            # shows at 1 - t on the mesh: the variety turns it back (t here is the mesh's, top = 1).
            # The set's own instances (make_colour) keep it as it was.
            t = 1 - t
            c = base
            if pattern in ("blush", "streak"):
                d = min(abs(u - side_u), 1 - abs(u - side_u))
                w = amount * math.exp(-(d / spread) ** 2 - ((t - side_t) / 0.5) ** 2) * (1 + 0.25 * blotch(u, t))
                if pattern == "streak":
                    # Meridional streaks, wavy, over a lighter wash of the same colour.
                    st = 0.5 + 0.5 * math.sin(2 * math.pi * n_streaks * u + 2.5 * wobble(u, t))
                    w = min(1.0, 2.2 * w) * (wash + (1 - wash) * st ** 1.5)
                c = mix(c, second, max(0.0, min(1.0, w)))
            elif pattern == "ends":
                ends = max(t, 1 - t) if category in ("lemon", "lime") else t
                c = mix(c, second, amount * smoothstep(ends_from, 1.0, ends + 0.06 * blotch(u, t)))
            elif pattern == "patches":
                c = mix(c, second, smoothstep(threshold - 0.5, threshold + 0.5, blotch(u, t)))
            elif pattern == "band":
                # The rim's top lies at t 0.53 .. 0.66 (shape_plate's profile; the well beyond it).
                if abs(t - band_at) < amount or (edge_line and 0.535 < t < 0.55):
                    c = second
            for su, st_, sr in spots:
                du = min(abs(u - su), 1 - abs(u - su)) * math.sin(math.pi * max(0.05, min(0.95, t))) * 2
                if du * du + (t - st_) ** 2 < sr * sr:
                    c = spot_colour
                    break
            k = 1 + mottling * mottle(u, t) + speckle * noise
            return tuple(max(0.0, min(1.0, x * k)) for x in c)

        return colour, base

    return maker


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


def make_instance(name, category, index, spec=None, seed=SEED, colour_maker=None, pose=None, kind=""):
    """Writes one instance. The defaults are the set's own instances; the training variety passes its
    own spec (sizes), seed, colour maker and pose (make_variety_instance). The draws from `rng` come in
    the same order either way."""
    rng = random.Random(f"{seed}-{name}")
    spec = CATEGORIES[category] if spec is None else spec
    colour_maker = make_colour if colour_maker is None else colour_maker
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
        f = shape_potato(rng, w, h, w * rng.uniform(*spec.get("elongation", (1.3, 1.8))))
    elif category == "tomato":
        f = shape_tomato(rng, w, h)
    else:
        f = shape_plate(rng, w, h)
    verts, uvs, faces = mesh(f)
    verts, size = place_on_table(verts)
    colour, base = colour_maker(rng, category, spec)
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
    x, y, z = default_pose(category, index) if pose is None else pose
    text = f"""<!-- {name}: {category} instance{kind} ({dims}, {mass} kg). Written by models/tools/make_produce.py. -->
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


def default_pose(category, index, per_category=INSTANCES):
    """scenes/produce.xml: an 8 x 8 grid of the produce on the table between the bins, apart (the
    widest, 85 mm, 9 cm apart; lemons lie along x, 97 mm apart), plates stacked in two piles beyond
    the bins."""
    categories = [c for c in CATEGORIES if c != "plate"]
    if category == "plate":
        return 0.76, -0.6 if index % 2 == 0 else 0.6, 0.025 * (index // 2)
    k = categories.index(category) * per_category + index
    return 0.2 + 0.097 * (k // 8), -0.315 + 0.09 * (k % 8), 0.0


def make_variety_instance(name, category, index):
    """One training-variety instance: VARIETY's sizes and palette `index`, its own seed."""
    v = VARIETY[category]
    spec = dict(CATEGORIES[category], width=v["width"], aspect=v["aspect"], spots=v["spots"])
    if "elongation" in v:
        spec["elongation"] = v["elongation"]
    palette = v["palettes"][index % len(v["palettes"])]
    return make_instance(name, category, index, spec=spec, seed=VARIETY_SEED,
                         colour_maker=make_variety_colour(palette),
                         pose=default_pose(category, index, VARIETY_INSTANCES),
                         kind=f", training variety: {palette[0]}")


def write_variety():
    lines = ["# Training variety of the produce set: more members of each category, for training only. "
             "Written by models/tools/make_produce.py.", "name: produce_variety", "objects:"]
    for category in CATEGORIES:
        for i in range(VARIETY_INSTANCES):
            name = f"{category}v{i + 1}"
            make_variety_instance(name, category, i)
            lines += [f"  - name: {name}", f"    category: {category}", f"    instance: {name}",
                      f"    model: ../../models/objects/{name}.inc.xml"]
    with open(os.path.join(ROOT, "scenes", "objects", "produce_variety.yaml"), "w") as out:
        out.write("\n".join(lines) + "\n")


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
    write_variety()


if __name__ == "__main__":
    main()
