#!/usr/bin/env python3
"""The state benchmark's peer: the IPC Toolkit's questions of one state (the start positions of a scene written by
`clothcd bench state`, the format ipctk_candidates.py reads), with its LBVH broad phase.

Usage: ipctk_state.py SCENE.bin --dhat D --threads N --repeats R [--contacts FILE]
       ipctk_state.py --version

Prints `name=value` lines: the active set's counts by type (vv, ev, ee, fv), the best over the repeats of the time of
`NormalCollisions.build(mesh, V, dhat, dmin=0, broad_phase=LBVH())` alone (build_ms), of that build followed by
`compute_minimum_distance(mesh, V)` (build_min_ms), the minimum distance (min_distance: the square root of what
compute_minimum_distance returns, which is the squared distance; inf without a contact), and
of `has_intersections(mesh, V, LBVH())` (has_intersections_ms) with its answer. The collision mesh and its edges are
built before the clock. With --contacts, writes the active set, one contact a line: `vv A B`, `ev V E0 E1`,
`ee A0 A1 B0 B1`, `fv V F0 F1 F2` (mesh vertex indices).
"""
import argparse
import math
import sys
import time

import numpy as np

import ipctk
from ipctk_candidates import read_scene


def best_ms(repeats, work):
    best = float("inf")
    for _ in range(repeats):
        clock = time.perf_counter()
        work()
        best = min(best, 1000 * (time.perf_counter() - clock))
    return best


def write_contacts(path, mesh, collisions):
    edges, faces = mesh.edges, mesh.faces
    with open(path, "w") as out:
        for c in collisions.vv_collisions:
            out.write(f"vv {c.vertex0_id} {c.vertex1_id}\n")
        for c in collisions.ev_collisions:
            e = edges[c.edge_id]
            out.write(f"ev {c.vertex_id} {e[0]} {e[1]}\n")
        for c in collisions.ee_collisions:
            a, b = edges[c.edge0_id], edges[c.edge1_id]
            out.write(f"ee {a[0]} {a[1]} {b[0]} {b[1]}\n")
        for c in collisions.fv_collisions:
            f = faces[c.face_id]
            out.write(f"fv {c.vertex_id} {f[0]} {f[1]} {f[2]}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?")
    parser.add_argument("--dhat", type=float)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--contacts")
    parser.add_argument("--version", action="store_true")
    args = parser.parse_args()
    if args.version:
        print(f"ipctk {ipctk.__version__}")
        return 0
    if args.scene is None or args.dhat is None or args.dhat <= 0 or args.threads < 1 or args.repeats < 1:
        parser.error("need SCENE.bin, --dhat > 0, --threads >= 1 and --repeats >= 1")
    ipctk.set_num_threads(args.threads)
    positions, _, faces = read_scene(args.scene)
    mesh = ipctk.CollisionMesh(positions, np.asfortranarray(ipctk.edges(faces)), faces)
    collisions = ipctk.NormalCollisions()

    def build():
        collisions.build(mesh, positions, args.dhat, dmin=0, broad_phase=ipctk.LBVH())

    def build_and_minimum():
        build()
        return collisions.compute_minimum_distance(mesh, positions)

    build_ms = best_ms(args.repeats, build)
    build_min_ms = best_ms(args.repeats, build_and_minimum)
    minimum = math.sqrt(build_and_minimum()) if len(collisions) > 0 else math.inf
    intersecting = [False]

    def has_intersections():
        intersecting[0] = ipctk.has_intersections(mesh, positions, ipctk.LBVH())

    has_intersections_ms = best_ms(args.repeats, has_intersections)
    print(f"vv={len(collisions.vv_collisions)} ev={len(collisions.ev_collisions)} ee={len(collisions.ee_collisions)} "
          f"fv={len(collisions.fv_collisions)}")
    print(f"build_ms={build_ms:.4f} build_min_ms={build_min_ms:.4f} min_distance={minimum!r}")
    print(f"has_intersections_ms={has_intersections_ms:.4f} has_intersections={int(intersecting[0])}")
    if args.contacts:
        write_contacts(args.contacts, mesh, collisions)
    return 0


if __name__ == "__main__":
    sys.exit(main())
