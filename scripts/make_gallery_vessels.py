#!/usr/bin/env python3
"""Writes the file vessels of data/vessels/ (run from the repository root):

  wavy_tube.stl  a tube of diameter 3.5 whose axis waves sideways, x = 3.5 + 0.5 sin(2 pi z / 10),
                 in a 7 x 5 x 10 box (one wave per period, so the two ends match), as 2 x 36 x 34
                 triangles (edges about 0.3) of a binary STL; its seam rings at z = 0 and z = 10
                 are both written.
  stenosis.step  a tube of diameter 3.5 narrowed to 2.1 by a cosine bump of length 4 in the middle of
                 a 5 x 5 x 10 box, revolved by gmsh's OpenCASCADE kernel from stenosis.geo
                 (gmsh stenosis.geo -0 -o stenosis.step).
"""
import math
import struct
import subprocess
from pathlib import Path

HERE = Path("data/vessels")


def wavy_tube(path, radius=1.75, length=10.0, centre=(3.5, 2.5), amplitude=0.5, rings=34, around=36):
    def point(i, j):
        z = length * i / rings
        phi = 2 * math.pi * j / around
        cx = centre[0] + amplitude * math.sin(2 * math.pi * z / length)
        return (cx + radius * math.cos(phi), centre[1] + radius * math.sin(phi), z)

    facets = []
    for i in range(rings):
        for j in range(around):
            a, b = point(i, j), point(i, j + 1)
            c, d = point(i + 1, j + 1), point(i + 1, j)
            facets += [(a, b, c), (a, c, d)]  # rbcflow orients every wall into its lumen
    with open(path, "wb") as f:
        f.write(b"wavy tube for rbcflow's vessel gallery".ljust(80, b" "))
        f.write(struct.pack("<I", len(facets)))
        for a, b, c in facets:
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            norm = math.sqrt(sum(x * x for x in n))
            f.write(struct.pack("<12fH", *(x / norm for x in n), *a, *b, *c, 0))


if __name__ == "__main__":
    wavy_tube(HERE / "wavy_tube.stl")
    subprocess.run(["gmsh", str(HERE / "stenosis.geo"), "-0", "-o", str(HERE / "stenosis.step")], check=True,
                   stdout=subprocess.DEVNULL)
