#!/usr/bin/env python3
"""Writes bowl.obj: a bowl as an open spherical cap, for a mesh collider with a thickness.

The cap is part of a sphere of radius 1.2 centred at (0, 1.2, 0): its lowest point (the
pole) at the origin, its rim at y = 0.9 (rim radius about 1.16). Vertices lie on rings
of equal polar angle around the pole; triangles wind counter-clockwise seen from outside
(the convex side), and the vertex normals point outward, away from the sphere's centre.
It is open (the rim's edges lie on one triangle each): give the collider a thickness,
which makes a shell of that thickness centred on this surface.

Usage: python3 make_bowl.py [OUTPUT]   (default: bowl.obj beside this script)
No dependencies; the output is the same on every run.
"""

import math
import os
import sys

RADIUS = 1.2  # of the sphere, world units
RIM_Y = 0.9  # height of the rim above the pole, world units
RINGS = 12  # rings of vertices from the pole to the rim
SEGMENTS = 48  # vertices per ring


def bowl():
    """Returns (positions, normals, triangles), triangles as 0-based index triples."""
    rim_angle = math.acos((RADIUS - RIM_Y) / RADIUS)  # polar angle from the pole
    positions = [(0.0, 0.0, 0.0)]
    normals = [(0.0, -1.0, 0.0)]
    for ring in range(1, RINGS + 1):
        theta = rim_angle * ring / RINGS
        for k in range(SEGMENTS):
            phi = 2 * math.pi * k / SEGMENTS
            n = (math.sin(theta) * math.cos(phi), -math.cos(theta), math.sin(theta) * math.sin(phi))
            normals.append(n)
            positions.append((RADIUS * n[0], RADIUS + RADIUS * n[1], RADIUS * n[2]))

    def vertex(ring, k):
        return 1 + (ring - 1) * SEGMENTS + k % SEGMENTS

    triangles = []
    for k in range(SEGMENTS):
        triangles.append((0, vertex(1, k), vertex(1, k + 1)))
    for ring in range(1, RINGS):
        for k in range(SEGMENTS):
            a, b = vertex(ring, k), vertex(ring, k + 1)
            c, d = vertex(ring + 1, k), vertex(ring + 1, k + 1)
            triangles.append((a, c, d))
            triangles.append((a, d, b))
    return positions, normals, triangles


def check_winding(positions, triangles):
    """Every face normal points away from the sphere's centre (outside the bowl)."""
    for t in triangles:
        a, b, c = (positions[i] for i in t)
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        centroid = [(a[i] + b[i] + c[i]) / 3 for i in range(3)]
        out = (centroid[0], centroid[1] - RADIUS, centroid[2])
        assert sum(n[i] * out[i] for i in range(3)) > 0, t


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "bowl.obj")
    positions, normals, triangles = bowl()
    check_winding(positions, triangles)
    lines = [
        "# bowl.obj: an open spherical cap, a bowl for a mesh collider with a thickness.",
        "# Made by scenes/effectors/make_bowl.py (python3 make_bowl.py); edit that, not this.",
        "# Sphere radius %g centred at (0, %g, 0): pole at the origin, rim at y = %g." % (
            RADIUS, RADIUS, RIM_Y),
        "# %d vertices, %d triangles, counter-clockwise seen from outside (the convex side)."
        % (len(positions), len(triangles)),
    ]
    lines += ["v %.5f %.5f %.5f" % p for p in positions]
    lines += ["vn %.5f %.5f %.5f" % n for n in normals]
    lines += ["f %d//%d %d//%d %d//%d" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1)
              for a, b, c in triangles]
    with open(path, "w", newline="\n") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
