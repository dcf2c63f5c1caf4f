#!/usr/bin/env python3
"""The scale benchmark's peer: the IPC Toolkit's LBVH candidate search (continuous, linear trajectories, no
inflation) on one step written by `clothcd bench scale`.

Usage: ipctk_candidates.py SCENE.bin --threads N --repeats R
       ipctk_candidates.py --version

SCENE.bin (little-endian): vertex count and face count (int64 each), the start positions and the end positions
(vertex count x 3 float64 each, row by row), the faces (face count x 3 int32). Prints one line:
`candidates=C vertex_face=VF edge_edge=EE best_ms=T` where T is the best over the repeats of the time of
`Candidates.build(mesh, V0, V1, 0.0, LBVH())` alone (the collision mesh and its edges are built before the clock).
"""
import argparse
import sys
import time

import numpy as np

import ipctk


def read_scene(path):
    with open(path, "rb") as file:
        vertex_count, face_count = (int(n) for n in np.fromfile(file, dtype="<i8", count=2))
        start = np.fromfile(file, dtype="<f8", count=3 * vertex_count).reshape(vertex_count, 3)
        end = np.fromfile(file, dtype="<f8", count=3 * vertex_count).reshape(vertex_count, 3)
        faces = np.fromfile(file, dtype="<i4", count=3 * face_count).reshape(face_count, 3)
    if faces.shape[0] != face_count or end.shape[0] != vertex_count:
        raise ValueError(f"{path}: truncated scene file")
    return np.asfortranarray(start), np.asfortranarray(end), np.asfortranarray(faces)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--version", action="store_true")
    args = parser.parse_args()
    if args.version:
        print(f"ipctk {ipctk.__version__}")
        return 0
    if args.scene is None or args.threads < 1 or args.repeats < 1:
        parser.error("need SCENE.bin, --threads >= 1 and --repeats >= 1")
    ipctk.set_num_threads(args.threads)
    start, end, faces = read_scene(args.scene)
    mesh = ipctk.CollisionMesh(start, np.asfortranarray(ipctk.edges(faces)), faces)
    best_ms = float("inf")
    candidates = ipctk.Candidates()
    for _ in range(args.repeats):
        candidates.clear()
        clock = time.perf_counter()
        candidates.build(mesh, start, end, 0.0, ipctk.LBVH())
        best_ms = min(best_ms, 1000 * (time.perf_counter() - clock))
    vertex_face = len(candidates.fv_candidates)
    edge_edge = len(candidates.ee_candidates)
    print(f"candidates={len(candidates)} vertex_face={vertex_face} edge_edge={edge_edge} best_ms={best_ms:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
