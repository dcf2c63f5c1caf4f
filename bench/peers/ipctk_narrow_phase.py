#!/usr/bin/env python3
"""The benchmarks' narrow-phase peer: the IPC Toolkit's Tight-Inclusion CCD (`ipctk.TightInclusionCCD()`, its
defaults: tolerance 1e-6, 1e7 iterations, conservative rescaling 0.8; minimum distance 0) on one step's own LBVH
candidates, or on a list of single queries.

Usage: ipctk_narrow_phase.py step SCENE.bin --hits HITS.txt [--per-pair] [--repeats R]
       ipctk_narrow_phase.py queries QUERIES.bin --hits HITS.txt [--repeats R]
       ipctk_narrow_phase.py --version

One thread (`ipctk.set_num_threads(1)`). Prints one line of `name=value` words.

step: SCENE.bin as bench/peers/ipctk_candidates.py reads it. The candidates are built with `Candidates.build(mesh,
V0, V1, 0.0, LBVH())`. Timed inside C++, best of R:
  stepsize_ms   `Candidates.compute_collision_free_stepsize` on every candidate: each candidate's search is limited
                to the earliest time of impact found so far, so candidates after a hit cost less (early termination).
  clean_ms      with --per-pair: `Candidates.is_step_collision_free` on the candidates without the peer's own hits
                (`clean_candidates` of them): it stops at the first hit, so with none every candidate is decided to the
                end; the hits' own cost is not in it.
With --per-pair, every candidate is also decided one at a time from Python (`point_triangle_ccd` / `edge_edge_ccd`,
`loop_ms` with the call overhead) and the hits are written to HITS.txt, one a line: `vf VERTEX FACE TOI` or
`ee A0 A1 B0 B1 TOI` (vertex ids).

queries: QUERIES.bin (little-endian): query count (int64), then per query its kind (int64: 0 vertex-face, 1 edge-edge)
and its 8 points (the four start points, then the four end points, 24 float64; the public benchmark's point order).
Every query is decided R times, one call at a time; HITS.txt gets one line per query, `1 TOI` or `0 1`. Printed: the
median and mean time of a call, and of a call of `point_triangle_aabb_ccd` / `edge_edge_aabb_ccd` on the same eight
points (same argument conversion, a bounding-box test as the only work): the Python call overhead.
"""
import argparse
import statistics
import sys
import time

import numpy as np

import ipctk

from ipctk_candidates import read_scene


def time_best(repeats, work):
    best = float("inf")
    for _ in range(repeats):
        clock = time.perf_counter()
        result = work()
        best = min(best, 1000 * (time.perf_counter() - clock))
    return best, result


def run_step(args, ccd):
    start, end, faces = read_scene(args.input)
    edges = np.asfortranarray(ipctk.edges(faces))
    mesh = ipctk.CollisionMesh(start, edges, faces)
    candidates = ipctk.Candidates()
    candidates.build(mesh, start, end, 0.0, ipctk.LBVH())
    words = {"candidates": len(candidates), "vertex_face": len(candidates.fv_candidates),
             "edge_edge": len(candidates.ee_candidates), "edge_vertex": len(candidates.ev_candidates)}
    stepsize_ms, stepsize = time_best(
        args.repeats, lambda: candidates.compute_collision_free_stepsize(mesh, start, end, 0.0, ccd))
    words.update(stepsize_ms=f"{stepsize_ms:.3f}", stepsize=f"{stepsize:.9g}")
    if args.per_pair:
        v0, v1 = np.ascontiguousarray(start), np.ascontiguousarray(end)
        kept_fv, kept_ee, lines = [], [], []
        clock = time.perf_counter()
        for candidate in candidates.fv_candidates:
            vertex, face = candidate.vertex_id, candidate.face_id
            t = faces[face]
            hit, toi = ccd.point_triangle_ccd(v0[vertex], v0[t[0]], v0[t[1]], v0[t[2]],
                                              v1[vertex], v1[t[0]], v1[t[1]], v1[t[2]], 0.0)
            if hit:
                lines.append(f"vf {vertex} {face} {toi:.17g}")
            else:
                kept_fv.append(candidate)
        for candidate in candidates.ee_candidates:
            a, b = edges[candidate.edge0_id], edges[candidate.edge1_id]
            hit, toi = ccd.edge_edge_ccd(v0[a[0]], v0[a[1]], v0[b[0]], v0[b[1]],
                                         v1[a[0]], v1[a[1]], v1[b[0]], v1[b[1]], 0.0)
            if hit:
                lines.append(f"ee {a[0]} {a[1]} {b[0]} {b[1]} {toi:.17g}")
            else:
                kept_ee.append(candidate)
        loop_ms = 1000 * (time.perf_counter() - clock)
        with open(args.hits, "w", encoding="ascii") as out:
            out.write("".join(line + "\n" for line in lines))
        clean = ipctk.Candidates()
        clean.fv_candidates, clean.ee_candidates = kept_fv, kept_ee
        clean.ev_candidates = candidates.ev_candidates
        clean_ms, free = time_best(args.repeats, lambda: clean.is_step_collision_free(mesh, start, end, 0.0, ccd))
        words.update(hits=len(lines), loop_ms=f"{loop_ms:.3f}", clean_candidates=len(clean),
                     clean_ms=f"{clean_ms:.3f}", clean_free=int(free))
    print(" ".join(f"{name}={value}" for name, value in words.items()))


def read_queries(path):
    with open(path, "rb") as file:
        count = int(np.fromfile(file, dtype="<i8", count=1)[0])
        records = np.fromfile(file, dtype=[("kind", "<i8"), ("points", "<f8", (8, 3))], count=count)
    if records.shape[0] != count:
        raise ValueError(f"{path}: truncated query file")
    return records


def run_queries(args, ccd):
    records = read_queries(args.input)
    call_ns, overhead_ns, lines = [], [], []
    for record in records:
        points = [np.ascontiguousarray(p) for p in record["points"]]
        decide = ccd.point_triangle_ccd if record["kind"] == 0 else ccd.edge_edge_ccd
        box = ipctk.point_triangle_aabb_ccd if record["kind"] == 0 else ipctk.edge_edge_aabb_ccd
        best_call = best_box = float("inf")
        for _ in range(args.repeats):
            clock = time.perf_counter_ns()
            hit, toi = decide(*points, 0.0)
            best_call = min(best_call, time.perf_counter_ns() - clock)
            clock = time.perf_counter_ns()
            box(*points, 0.0)
            best_box = min(best_box, time.perf_counter_ns() - clock)
        call_ns.append(best_call)
        overhead_ns.append(best_box)
        lines.append(f"{int(hit)} {toi:.17g}" if hit else "0 1")
    with open(args.hits, "w", encoding="ascii") as out:
        out.write("".join(line + "\n" for line in lines))
    words = {"queries": len(records), "hits": sum(line[0] == "1" for line in lines),
             "median_call_ns": statistics.median(call_ns) if call_ns else 0,
             "mean_call_ns": statistics.fmean(call_ns) if call_ns else 0,
             "median_overhead_ns": statistics.median(overhead_ns) if overhead_ns else 0,
             "mean_overhead_ns": statistics.fmean(overhead_ns) if overhead_ns else 0}
    print(" ".join(f"{name}={value:.6g}" if isinstance(value, float) else f"{name}={value}"
                   for name, value in words.items()))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=["step", "queries"])
    parser.add_argument("input")
    parser.add_argument("--hits", required=True)
    parser.add_argument("--per-pair", action="store_true")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--version", action="version", version=f"ipctk {ipctk.__version__}")
    args = parser.parse_args()
    if args.repeats < 1:
        parser.error("need --repeats >= 1")
    ipctk.set_num_threads(1)
    ccd = ipctk.TightInclusionCCD()
    if args.what == "step":
        run_step(args, ccd)
    else:
        run_queries(args, ccd)
    return 0


if __name__ == "__main__":
    sys.exit(main())
