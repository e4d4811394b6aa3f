#!/usr/bin/env python3
"""Writes boulder.obj: the mesh obstacle of scenes/dam_break_mesh_3d.json.

An icosphere (an icosahedron whose triangles are split in four, three times:
1,280 triangles) of radius 1, made lumpy by a smooth deterministic bump on the
radius and cut flat at y = -0.6 so that it stands on the floor. Units are
the scene's "scale" (the scene makes it 5 cm); the flat base is at y = -0.6.
Faces are counter-clockwise seen from outside. Run it from anywhere:

    python3 scenes/meshes/make_boulder.py
"""
import math
import os

SUBDIVISIONS = 3
BASE = -0.6  # the flat bottom, in units of the radius


def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
                (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [normalised(v) for v in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
             (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
             (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
             (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p, q = vertices[a], vertices[b]
                vertices.append(normalised(tuple((p[k] + q[k]) / 2 for k in range(3))))
                middle[key] = len(vertices) - 1
            return middle[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return vertices, faces


def normalised(v):
    length = math.sqrt(sum(x * x for x in v))
    return tuple(x / length for x in v)


def lumpy(v):
    # A few smooth bumps, at most +-12% of the radius; then the flat base.
    x, y, z = v
    r = 1 + 0.08 * math.sin(3 * x + 1) * math.cos(2 * z) + 0.04 * math.sin(5 * y + 2 * x)
    return (r * x, max(r * y, BASE), r * z)


def main():
    vertices, faces = icosphere(SUBDIVISIONS)
    vertices = [lumpy(v) for v in vertices]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "boulder.obj")
    with open(path, "w") as out:
        out.write("# A lumpy boulder with a flat base, written by make_boulder.py.\n")
        out.write(f"# {len(vertices)} vertices, {len(faces)} triangles, radius about 1.\n")
        for v in vertices:
            out.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for a, b, c in faces:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")


if __name__ == "__main__":
    main()
