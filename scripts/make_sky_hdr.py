#!/usr/bin/env python3
"""Writes the project's own environment map: a procedural clear sky with a sun disc, as an
equirectangular Radiance .hdr (flat RGBE scanlines, which every .hdr reader takes).

The sun stands where the default sun of `--lighting auto` does (elevation 50 deg, azimuth 30 deg
from +Z towards +X; renderer/scene/scene.h), its disc of angular radius SUN_RADIUS_DEG carries
the same irradiance at normal incidence (3), and the sky's mean radiance over the upper hemisphere
is close to the default sky's 0.4. Mapping: Blender's (renderer/environment.h): +Y up, the top row
the zenith, u = 0.5 + atan2(z, x) / 2pi (the centre column looks down +X).

    python3 scripts/make_sky_hdr.py assets/environments/sky_sun.hdr [WIDTH]
"""
import argparse
import math

SUN_ELEVATION_DEG = 50.0
SUN_AZIMUTH_DEG = 30.0
SUN_IRRADIANCE = 3.0
SUN_RADIUS_DEG = 3.0


def direction(u, v):
    phi, theta = (u - 0.5) * 2.0 * math.pi, v * math.pi
    s = math.sin(theta)
    return (s * math.cos(phi), math.cos(theta), s * math.sin(phi))


def sky(d, sun):
    """Zenith blue to a brighter horizon, a grey ground, and a glow around the sun."""
    x, y, z = d
    if y < 0.0:
        return (0.12, 0.11, 0.10)
    horizon = (1.0 - y) ** 3
    base = [0.18 + 0.42 * horizon, 0.32 + 0.38 * horizon, 0.62 + 0.18 * horizon]
    cos_sun = x * sun[0] + y * sun[1] + z * sun[2]
    glow = 0.35 * max(cos_sun, 0.0) ** 16
    return tuple(c + glow for c in base)


def rgbe(rgb):
    m = max(rgb)
    if m < 1e-32:
        return b"\0\0\0\0"
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([min(255, int(c * scale)) for c in rgb] + [exponent + 128])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("path", nargs="?", default="assets/environments/sky_sun.hdr", help="the .hdr to write")
    parser.add_argument("width", nargs="?", type=int, default=128, help="texels across (the height is half)")
    args = parser.parse_args()
    path, width = args.path, args.width
    if width < 2 or width % 2:
        parser.error("width must be an even number of at least 2")
    height = width // 2
    e, a = math.radians(SUN_ELEVATION_DEG), math.radians(SUN_AZIMUTH_DEG)
    sun = (math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a))
    cos_radius = math.cos(math.radians(SUN_RADIUS_DEG))
    sun_radiance = SUN_IRRADIANCE / (2.0 * math.pi * (1.0 - cos_radius))  # E = L * disc solid angle
    # Supersample 4x4 per texel so the small disc lands on the texels it covers in proportion.
    n = 4
    rows = []
    for j in range(height):
        row = bytearray()
        for i in range(width):
            acc = [0.0, 0.0, 0.0]
            for sj in range(n):
                for si in range(n):
                    d = direction((i + (si + 0.5) / n) / width, (j + (sj + 0.5) / n) / height)
                    c = sky(d, sun)
                    if d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] >= cos_radius:
                        c = (sun_radiance, sun_radiance * 0.96, sun_radiance * 0.88)
                    acc = [p + q for p, q in zip(acc, c)]
            row += rgbe([c / (n * n) for c in acc])
        rows.append(bytes(row))
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\n# gisandbox scripts/make_sky_hdr.py: procedural sky, sun disc\n")
        f.write(b"FORMAT=32-bit_rle_rgbe\n\n")
        f.write(("-Y %d +X %d\n" % (height, width)).encode())
        for r in rows:
            f.write(r)
    print("wrote %s (%dx%d, sun radiance %.1f)" % (path, width, height, sun_radiance))


if __name__ == "__main__":
    main()
