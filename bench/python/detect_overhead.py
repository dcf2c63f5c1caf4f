"""Python detect() against the same calls made from C++: cloth C draping over the human (the frames of consecutive
simulation steps), one detector each, alternating runs. Prints one row: frames, C++ and Python ms per call (best of
the repeats), the overhead of the bests and the median overhead over the pairs of runs, and the fixed cost of a
Python call (wrapper, arrays in and out) measured the same way on a four-vertex cloth whose detection costs almost
nothing, in microseconds and as a percentage of the best C++ call. The target is <= 5%. On a busy machine the two
ratios of whole calls scatter by several percent either way; the fixed cost does not depend on the load as much.

    python bench/python/detect_overhead.py [--frames 30] [--repeats 7]      (after `pip install .`)
"""

import argparse
import time

import numpy as np

import clothcd
from clothcd import _clothcd


def fixed_cost_seconds(calls: int = 20000, repeats: int = 7) -> float:
    """Median over `repeats` runs of (Python loop - C++ loop) / calls on a four-vertex cloth: seconds per call."""
    vertices, faces = clothcd.make_grid(2, 2, 1.0, 1.0)
    starts, ends = [vertices] * calls, [vertices + np.array([0.0, -0.01, 0.0])] * calls
    d = clothcd.CollisionDetector(faces, len(vertices), parallel=False, reuse_unchanged=False)
    differences = []
    for _ in range(repeats):
        cpp = _clothcd._detect_loop_seconds(d._detector, starts, ends)
        begin = time.perf_counter()
        for x0, x1 in zip(starts, ends):
            d.detect(x0, x1)
        differences.append((time.perf_counter() - begin - cpp) / calls)
    return sorted(differences)[repeats // 2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="human")
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    settle = 150
    faces, frames, obstacles = clothcd.simulate_scene(args.scene, "C", steps=settle + args.frames, frames_every=1)
    draped = frames[settle:]
    starts, ends = draped[:-1], draped[1:]

    def detector() -> clothcd.CollisionDetector:
        d = clothcd.CollisionDetector(faces, len(starts[0]), thickness=0.004)
        for vertices, obstacle_faces in obstacles:
            d.add_obstacle(vertices, obstacle_faces)
        return d

    cpp_times, python_times = [], []
    for _ in range(args.repeats):
        d = detector()
        cpp_times.append(_clothcd._detect_loop_seconds(d._detector, starts, ends))
        d = detector()
        begin = time.perf_counter()
        for x0, x1 in zip(starts, ends):
            d.detect(x0, x1)
        python_times.append(time.perf_counter() - begin)
    n = len(starts)
    cpp_best, python_best = min(cpp_times), min(python_times)
    ratios = sorted(p / c for p, c in zip(python_times, cpp_times))
    fixed = fixed_cost_seconds()
    print("frames,cpp_ms_per_call,python_ms_per_call,overhead_percent_best,overhead_percent_median_pair,"
          "fixed_us_per_call,fixed_percent_of_cpp_call")
    print(f"{n},{1e3 * cpp_best / n:.4f},{1e3 * python_best / n:.4f},{100.0 * (python_best / cpp_best - 1.0):.2f},"
          f"{100.0 * (ratios[len(ratios) // 2] - 1.0):.2f},{1e6 * fixed:.2f},{100.0 * fixed / (cpp_best / n):.2f}")


if __name__ == "__main__":
    main()
