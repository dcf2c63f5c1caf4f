"""A cloth advanced by the collision-free fraction of each step: a line-search loop on CollisionDetector.earliest_impact.

Each step proposes a motion (gravity, then a few passes that restore the edges' rest lengths, as position-based
dynamics does), asks the detector how far along it nothing touches, and moves 80% of that way. The vertices of the pair that
stopped the step stick where they are, so the cloth settles on the sphere without ever passing through it or itself.
Writes a picture of the last frame.

    python examples/python/line_search.py [OUT.png] [STEPS]     (after `pip install .`)
"""

import argparse

import numpy as np

import clothcd

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("out", nargs="?", default="line_search.png", metavar="OUT.png",
                    help="the picture of the last frame (default: %(default)s)")
parser.add_argument("steps", nargs="?", type=int, default=500, metavar="STEPS",
                    help="the number of steps (default: %(default)s)")
args = parser.parse_args()
out, steps = args.out, args.steps
dt, gravity, fraction = 0.01, np.array([0.0, -9.81, 0.0]), 0.8

sphere = clothcd.make_uv_sphere(0.5, 32, 16)
x, faces = clothcd.make_grid(24, 24, 1.6, 1.6)
x = x + [0.05, 0.6, 0.0]  # just above the sphere, off its top
velocity = np.zeros_like(x)
stuck = np.zeros(len(x), dtype=bool)

edges = np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
rest = np.linalg.norm(x[edges[:, 0]] - x[edges[:, 1]], axis=1)


def keep_edge_lengths(p, passes=8):
    """Moves the free vertices of `p` so that the edges get back towards their rest lengths (Jacobi passes)."""
    free = (~stuck).astype(float)
    for _ in range(passes):
        d = p[edges[:, 1]] - p[edges[:, 0]]
        length = np.linalg.norm(d, axis=1)
        weights = free[edges[:, 0]] + free[edges[:, 1]]
        scale = np.where(weights > 0, (length - rest) / np.maximum(length, 1e-12) / np.maximum(weights, 1), 0.0)
        move, count = np.zeros_like(p), np.zeros(len(p))
        np.add.at(move, edges[:, 0], (scale * free[edges[:, 0]])[:, None] * d)
        np.add.at(move, edges[:, 1], -(scale * free[edges[:, 1]])[:, None] * d)
        np.add.at(count, edges.ravel(), 1.0)
        p = p + move / np.maximum(count, 1)[:, None]
    return p


detector = clothcd.CollisionDetector(faces, len(x))
detector.add_obstacle(*sphere)
shortened = 0
for step in range(steps):
    velocity[~stuck] += dt * gravity
    proposal = keep_edge_lengths(x + dt * velocity)
    proposal[stuck] = x[stuck]
    impact = detector.earliest_impact(x, proposal)
    moved = proposal
    if impact.hit:
        shortened += 1
        moved = x + fraction * impact.toi * (proposal - x)
        for body, vertex in zip(impact.pair.bodies, impact.pair.vertices):
            if body == 0:
                stuck[vertex] = True
    velocity = (moved - x) / dt
    velocity[stuck] = 0.0
    x = moved

print(f"clothcd {clothcd.__version__}: {steps} steps, {shortened} shortened by the collision-free fraction, "
      f"{int(stuck.sum())} vertices resting on the sphere; closest cloth vertex to the sphere's centre "
      f"{np.linalg.norm(x, axis=1).min():.3f} (radius 0.5)")
clothcd.render_png(out, [(sphere[0], sphere[1], (0.55, 0.6, 0.7)), (x, faces, (0.85, 0.35, 0.3))])
print(f"wrote {out}")
