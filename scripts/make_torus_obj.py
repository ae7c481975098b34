#!/usr/bin/env python3
"""Writes the torus mesh of the mesh golden scene (data/scenes/torus.obj).

A torus about the y axis: ring radius 1, tube radius 0.4, 64 x 32 quads, exact unit normals.
Generated here so that no third-party mesh enters the repository. Deterministic output:
  scripts/make_torus_obj.py > data/scenes/torus.obj
"""
import math

RING, TUBE, N_RING, N_TUBE = 1.0, 0.4, 64, 32


def main():
    print("# brdfit torus: ring radius %g, tube radius %g, %d x %d quads (scripts/make_torus_obj.py)"
          % (RING, TUBE, N_RING, N_TUBE))
    for i in range(N_RING):
        u = 2 * math.pi * i / N_RING
        for j in range(N_TUBE):
            v = 2 * math.pi * j / N_TUBE
            n = (math.cos(v) * math.cos(u), math.sin(v), math.cos(v) * math.sin(u))
            c = (RING * math.cos(u), 0.0, RING * math.sin(u))
            p = tuple(c[k] + TUBE * n[k] for k in range(3))
            print("v %.6f %.6f %.6f" % p)
            print("vn %.6f %.6f %.6f" % n)

    def idx(i, j):
        return (i % N_RING) * N_TUBE + (j % N_TUBE) + 1

    for i in range(N_RING):
        for j in range(N_TUBE):
            # Counter-clockwise seen from outside the tube.
            a, b, c, d = idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)
            print("f %d//%d %d//%d %d//%d %d//%d" % (a, a, b, b, c, c, d, d))


if __name__ == "__main__":
    main()
