"""A cloth dropped on a sphere by a repulsion loop: the active set of CollisionDetector.proximity pushes close pairs
apart, and CollisionDetector.earliest_impact limits each step so that nothing passes through anything.

Each step proposes a motion (gravity, then a few passes that restore the edges' rest lengths, as position-based
dynamics does) and adds a repulsion: every pair within the distance D (a vertex and a triangle, or two edges, of the
cloth with itself or with the sphere) pushes its two sides apart along the pair's direction, by a share of what it
lacks to D, spread over the vertices by the closest point's weights. The detector then says how far along the
proposal nothing touches (a line search), and the cloth moves 90% of that way. Prints the per-step counts (pairs
within D, their closest-feature contacts, the collision-free fraction) and writes a picture of the last frame.

    python examples/python/repulsion.py [OUT.png] [STEPS]     (after `pip install .`)
"""

import argparse

import numpy as np

import clothcd

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("out", nargs="?", default="repulsion.png", metavar="OUT.png",
                    help="the picture of the last frame (default: %(default)s)")
parser.add_argument("steps", nargs="?", type=int, default=300, metavar="STEPS",
                    help="the number of steps (default: %(default)s)")
args = parser.parse_args()
dt, gravity, fraction, distance, strength = 0.01, np.array([0.0, -9.81, 0.0]), 0.9, 0.02, 0.5

sphere = clothcd.make_uv_sphere(0.5, 32, 16)
x, faces = clothcd.make_grid(20, 20, 1.4, 1.4)
x = x + [0.05, 0.55, 0.0]  # just above the sphere, off its top
velocity = np.zeros_like(x)

edges = np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
rest = np.linalg.norm(x[edges[:, 0]] - x[edges[:, 1]], axis=1)


def keep_edge_lengths(p, passes=8):
    """Moves `p`'s vertices so that the edges get back towards their rest lengths (Jacobi passes)."""
    for _ in range(passes):
        d = p[edges[:, 1]] - p[edges[:, 0]]
        length = np.linalg.norm(d, axis=1)
        half = (0.5 * (length - rest) / np.maximum(length, 1e-12))[:, None] * d
        move, count = np.zeros_like(p), np.zeros(len(p))
        np.add.at(move, edges[:, 0], half)
        np.add.at(move, edges[:, 1], -half)
        np.add.at(count, edges.ravel(), 1.0)
        p = p + move / np.maximum(count, 1)[:, None]
    return p


def repulsion(pairs):
    """The displacement of each cloth vertex that pushes the pairs within `distance` apart along their directions
    (the first primitive along it, the second against it), each by `strength` of its gap to `distance`."""
    w = np.empty((len(pairs), 4))
    s, u = pairs.parameters[:, 0], pairs.parameters[:, 1]
    vertex_face = pairs.kind == clothcd.VERTEX_FACE
    # The closest point's weight on each vertex: the vertex, then the triangle's barycentric weights; or the two edges'.
    w[vertex_face] = np.column_stack([np.ones_like(s), -(1 - s - u), -s, -u])[vertex_face]
    w[~vertex_face] = np.column_stack([1 - s, s, -(1 - u), -u])[~vertex_face]
    push = (strength * (distance - pairs.distance))[:, None] * pairs.direction
    move, count = np.zeros_like(x), np.zeros(len(x))
    cloth = pairs.bodies == 0  # the sphere does not move
    for k in range(4):
        on = cloth[:, k]
        np.add.at(move, pairs.vertices[on, k], w[on, k, None] * push[on])
        np.add.at(count, pairs.vertices[on, k], 1.0)
    return move / np.maximum(count, 1)[:, None]


detector = clothcd.CollisionDetector(faces, len(x))
detector.add_obstacle(*sphere)
for step in range(args.steps):
    velocity += dt * gravity
    pairs = detector.proximity(x, distance)
    proposal = keep_edge_lengths(x + dt * velocity) + repulsion(pairs)
    impact = detector.earliest_impact(x, proposal)
    moved = x + fraction * impact.toi * (proposal - x) if impact.hit else proposal
    velocity = 0.98 * (moved - x) / dt  # a little damping
    x = moved
    if step % 25 == 0 or step == args.steps - 1:
        contacts = clothcd.closest_feature_contacts(pairs)
        print(f"step {step:4d}: {len(pairs):5d} pairs within {distance}, {len(contacts):5d} contacts, "
              f"collision-free fraction {impact.toi:.3f}")

minimum = detector.minimum_distance(x)
print(f"clothcd {clothcd.__version__}: {args.steps} steps; closest cloth vertex to the sphere's centre "
      f"{np.linalg.norm(x, axis=1).min():.3f} (radius 0.5), smallest pair distance {minimum.distance:.2e}, "
      f"intersection-free: {detector.is_intersection_free(x)}")
clothcd.render_png(args.out, [(sphere[0], sphere[1], (0.55, 0.6, 0.7)), (x, faces, (0.35, 0.55, 0.85))])
print(f"wrote {args.out}")
