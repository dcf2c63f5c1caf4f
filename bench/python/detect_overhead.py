"""Python detect() against the same calls made from C++: cloth C draping over the human (the frames of consecutive
simulation steps), one detector each, alternating runs, best of several. Prints one row: frames, C++ ms per call,
Python ms per call and the overhead. The target is <= 5%.

    python bench/python/detect_overhead.py [--frames 30] [--repeats 7]      (after `pip install .`)
"""

import argparse
import time

import clothcd
from clothcd import _clothcd


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

    cpp_best = python_best = float("inf")
    for _ in range(args.repeats):
        d = detector()
        cpp_best = min(cpp_best, _clothcd._detect_loop_seconds(d._detector, starts, ends))
        d = detector()
        begin = time.perf_counter()
        for x0, x1 in zip(starts, ends):
            d.detect(x0, x1)
        python_best = min(python_best, time.perf_counter() - begin)
    n = len(starts)
    print("frames,cpp_ms_per_call,python_ms_per_call,overhead_percent")
    print(f"{n},{1e3 * cpp_best / n:.4f},{1e3 * python_best / n:.4f},{100.0 * (python_best / cpp_best - 1.0):.2f}")


if __name__ == "__main__":
    main()
