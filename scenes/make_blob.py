"""Writes scenes/blob.obj: a deformed icosphere (2 subdivisions: 162 vertices, 320
faces) for scenes/local-mesh.toml.  Run once; the .obj text is committed.

    python scenes/make_blob.py
"""

import os

import numpy as np


def icosphere(subdivisions):
    t = (1 + 5 ** 0.5) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    vertices = [np.array(v, float) / np.linalg.norm(v) for v in vertices]
    for _ in range(subdivisions):
        middle, out = {}, []

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                m = vertices[i] + vertices[j]
                vertices.append(m / np.linalg.norm(m))
                middle[key] = len(vertices) - 1
            return middle[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = out
    return np.array(vertices), np.array(faces)


def blob(seed=7):
    vertices, faces = icosphere(2)
    rng = np.random.default_rng(seed)
    # a few smooth bumps: radius 1 + sum of Gaussian lobes about random directions
    centres = rng.normal(size=(5, 3))
    centres /= np.linalg.norm(centres, axis=1, keepdims=True)
    heights = rng.uniform(-0.15, 0.3, size=5)
    radius = 1 + (heights * np.exp(-4 * (1 - vertices @ centres.T))).sum(1)
    return vertices * radius[:, None], faces


def main():
    vertices, faces = blob()
    lines = ["# blob.obj: deformed icosphere written by scenes/make_blob.py (seed 7)",
             f"# {len(vertices)} vertices, {len(faces)} faces, no vn: normals are computed"]
    lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blob.obj")
    with open(path, "w") as file:
        file.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
