"""Colour and PNG helpers shared by the object generators (make_produce.py, make_balls.py): HSV
colours with jitter, mixing, smoothstep, and a pure-Python RGB PNG writer (zlib only, so the
generators need no imaging library)."""
import colorsys
import struct
import zlib


def hsv(h, s, v):
    """RGB in [0, 1] of hue h (degrees), saturation s and value v (clamped to [0, 1])."""
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
