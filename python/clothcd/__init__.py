"""clothcd: cloth collision detection (Jin et al.'s method, with no missed collision).

Positions are (N, 3) float64 arrays and faces (F, 3) int32 arrays. CollisionDetector.detect and
set_obstacle_positions read float64 arrays where they are, in any order (C, Fortran, a slice): no copy; other dtypes
and array-likes are converted first (a copy). Elsewhere arrays in other dtypes or orders are converted.
Errors arrive with the library's message: invalid arguments as ValueError, unreadable or invalid files as OSError, a
step with more collisions than the detector's max_collisions as CollisionBudgetExceeded (a RuntimeError).
"""

from __future__ import annotations

import os

import numpy as np
import numpy.typing as npt

from ._clothcd import (
    CollisionBudgetExceeded,
    __version__,
    load_mesh,
    load_mesh_frames,
    make_grid,
    make_paper_cloth,
    make_uv_sphere,
    obb,
    render_png,
    save_mesh,
    simplify,
)
from . import _clothcd
from .collisions import EDGE_EDGE, VERTEX_FACE, Collision, Collisions, EarliestImpact
from .state_queries import (
    CONTACT_KINDS,
    DISTANCE_TYPES,
    FeatureContacts,
    Intersections,
    MinimumDistance,
    Proximities,
    closest_feature_contacts,
    intersections,
)

__all__ = [
    "__version__", "CONTACT_KINDS", "DISTANCE_TYPES", "Collision", "CollisionBudgetExceeded", "Collisions",
    "CollisionDetector", "EarliestImpact", "FeatureContacts", "Intersections", "MinimumDistance", "Proximities", "ccd",
    "closest_feature_contacts", "default_model_dir", "load_mesh",
    "load_mesh_frames", "make_grid", "make_paper_cloth", "make_uv_sphere", "obb", "render_png", "save_mesh", "simplify",
    "simulate", "simulate_scene",
]


def default_model_dir() -> str:
    """The pair network shipped with the package (the repository's models/default)."""
    return os.path.join(os.path.dirname(__file__), "models", "default")


class CollisionDetector:
    """Continuous collision detection between a cloth and obstacles, step after step.

    Settings (keywords): hierarchy ("sphere-root-aabb", "aabb", "aabb-obb"), culling ("filters", "none",
    "nonpenetration", "projection", "network"), thickness, self_collision, model_path (network culling; default: the
    shipped model), max_leaf_faces, parallel, reuse_unchanged, projection_normals, decide_exactly (True: every
    reported collision is proven; False: the approximate mode's conservative hits), max_collisions (the collision
    budget of one detect() call); see the C++ clothcd::DetectorSettings. One detector must not be used from two threads at once; separate detectors may.
    """

    def __init__(self, faces, vertex_count: int, *, hierarchy: str = "sphere-root-aabb", culling: str = "filters",
                 thickness: float = 0.0, self_collision: bool = True, model_path: str = "",
                 max_leaf_faces: int = 32, parallel: bool = True, reuse_unchanged: bool = True,
                 projection_normals: bool = True, decide_exactly: bool = True,
                 max_collisions: int = 4_000_000) -> None:
        if culling == "network" and not model_path:
            model_path = default_model_dir()
        self._detector = _clothcd._CollisionDetector(
            np.ascontiguousarray(faces, dtype=np.int32), vertex_count, hierarchy, culling, thickness, self_collision,
            model_path, max_leaf_faces, parallel, reuse_unchanged, projection_normals, decide_exactly, max_collisions)

    def add_obstacle(self, vertices, faces) -> int:
        """Adds a static obstacle; returns its body id (1, 2, ...)."""
        return self._detector.add_obstacle(np.ascontiguousarray(vertices, dtype=np.float64),
                                           np.ascontiguousarray(faces, dtype=np.int32))

    def set_obstacle_transforms(self, body: int, start, end) -> None:
        """Moves obstacle `body` rigidly over the next step: its mesh as added, transformed by the (4, 4) `start` and
        `end` rigid transforms."""
        self._detector.set_obstacle_transforms(body, np.ascontiguousarray(start, dtype=np.float64),
                                               np.ascontiguousarray(end, dtype=np.float64))

    def set_obstacle_positions(self, body: int, start: npt.ArrayLike, end: npt.ArrayLike) -> None:
        """Sets the (N, 3) positions of obstacle `body` at the start and end of the next step (float64 arrays are
        read in place; the detector keeps its own copy)."""
        self._detector.set_obstacle_positions(body, np.asarray(start, dtype=np.float64),
                                              np.asarray(end, dtype=np.float64))

    @property
    def obstacle_count(self) -> int:
        """Number of obstacles added."""
        return self._detector.obstacle_count()

    def detect(self, x0: npt.ArrayLike, x1: npt.ArrayLike) -> Collisions:
        """Every collision of the step from cloth positions `x0` to `x1` ((N, 3) each). float64 arrays in any order
        reach the C++ detector as views, without a copy (the detector then copies the positions once into its own
        buffers, as it does for a C++ caller); other dtypes are converted first. Runs without the GIL: do not modify
        `x0` or `x1` from another thread meanwhile. Ctrl-C stops it within a fraction of a second (KeyboardInterrupt).
        Raises CollisionBudgetExceeded when the step has more than max_collisions collisions (a degenerate step: the
        search stops early); the detector stays usable, and the next call searches its step in full."""
        kind, bodies, vertices, toi, parameters, normal, conservative = self._detector.detect(
            np.asarray(x0, dtype=np.float64), np.asarray(x1, dtype=np.float64))
        return Collisions(kind, bodies, vertices, toi, parameters, normal, conservative.view(bool))

    def earliest_impact(self, x0: npt.ArrayLike, x1: npt.ArrayLike) -> EarliestImpact:
        """The step's earliest time of impact, from cloth positions `x0` to `x1` (taken as detect() takes them): how far
        along the step everything can move before any pair comes into contact (or within the thickness), and the pair
        that sets it. Searches only as much of the step as it needs, so an early contact costs far less than detect().
        A line search takes a fraction of it, e.g. x0 + 0.8 * toi * (x1 - x0). Like detect(), it ends the step (an
        obstacle moved by set_obstacle_positions rests at its end afterwards)."""
        toi, hit, windows, arrays = self._detector.earliest_impact(
            np.asarray(x0, dtype=np.float64), np.asarray(x1, dtype=np.float64))
        kind, bodies, vertices, tois, parameters, normal, conservative = arrays
        pairs = list(Collisions(kind, bodies, vertices, tois, parameters, normal, conservative.view(bool)))
        return EarliestImpact(toi, hit, pairs[0] if pairs else None, windows)

    def proximity(self, x: npt.ArrayLike, distance: float) -> Proximities:
        """Every pair detect() covers whose distance at the state `x` ((N, 3) cloth positions, taken as detect() takes
        them; the obstacles where they rest) is below `distance` (exactly: a pair at `distance` is not reported), with
        its distance, closest points and direction. Runs without the GIL; Ctrl-C stops it. Raises ValueError on a NaN
        or infinite coordinate, a wrong shape or a distance that is <= 0, NaN or infinite, CollisionBudgetExceeded
        beyond max_collisions pairs."""
        return Proximities(*self._detector.proximity(np.asarray(x, dtype=np.float64), float(distance)))

    def minimum_distance(self, x: npt.ArrayLike, upper_bound: float = float("inf")) -> MinimumDistance:
        """The smallest distance at the state `x` over the pairs proximity() covers, and a pair that has it (a branch
        and bound: no distance to guess). With `upper_bound` only pairs closer than it count, which ends the search
        sooner (found is False when there is none). Raises as proximity() does."""
        found, distance, pair = self._detector.minimum_distance(np.asarray(x, dtype=np.float64), float(upper_bound))
        return MinimumDistance(found, distance, Proximities(*pair) if found else None)

    def intersections(self, x: npt.ArrayLike) -> Intersections:
        """Every pair of intersecting faces at the state `x` (closed triangles, touching counts; faces sharing a
        vertex or an edge only where they meet beyond it), decided exactly. Raises as proximity() does."""
        return intersections(self._detector.intersections(np.asarray(x, dtype=np.float64)))

    def is_intersection_free(self, x: npt.ArrayLike) -> bool:
        """True when no pair of faces intersects at the state `x` (intersections() would be empty); stops at the
        first intersecting pair. Raises as proximity() does."""
        return self._detector.is_intersection_free(np.asarray(x, dtype=np.float64))

    def stats(self) -> dict:
        """Counts and times of the last detect(), earliest_impact() or state query (proximity, minimum_distance,
        intersections, is_intersection_free: candidates are the pairs tested, collisions the records found)."""
        return self._detector.stats()


def ccd(queries, kind: str = "vf", *, filter: str = "combined", thickness: float = 0.0, exact: bool = True):
    """Continuous collision detection on (N, 8, 3) queries (the four points at t=0, then at t=1; vertex-face: the
    vertex then the triangle, edge-edge: edge a then edge b). Returns (hit (N,) bool, toi (N,), culled (N,) bool):
    `culled` pairs were removed by `filter` ("none", "nonpenetration", "projection", "combined"). exact=False is the
    approximate mode: queries the floating-point fast tier leaves undecided count as hits (toi a lower bound)."""
    hit, toi, culled = _clothcd._ccd(np.ascontiguousarray(queries, dtype=np.float64), kind, filter, thickness, exact)
    return hit.astype(bool), toi, culled.astype(bool)


def simulate(cloth, obstacles, *, steps: int = 200, frames_every: int = 10, dt: float = 0.005,
             thickness: float = 0.004, culling: str = "filters", model_path: str = ""):
    """Drops `cloth` = (vertices, faces) under gravity (-y) onto static `obstacles` [(vertices, faces), ...]; returns
    the cloth positions (N, 3) of step 0 and of every `frames_every`-th step. culling: "filters", "network" (with
    `model_path`, default the shipped model) or "none". Runs without the GIL."""
    if culling == "network" and not model_path:
        model_path = default_model_dir()
    return _clothcd.simulate(cloth, obstacles, steps=steps, frames_every=frames_every, dt=dt, thickness=thickness,
                             culling=culling, model_path=model_path)


def simulate_scene(name: str, cloth: str = "A", *, steps: int = -1, frames_every: int = 10, dt: float = 0.005,
                   thickness: float = 0.004, culling: str = "filters", model_path: str = ""):
    """One of the paper's scenes (box, sphere, human, ...; models from the Debian packages of
    scripts/install-deps.sh): returns (cloth faces, frames, obstacles at rest [(vertices, faces), ...]); steps < 0
    takes the scene's default."""
    if culling == "network" and not model_path:
        model_path = default_model_dir()
    return _clothcd.simulate_scene(name, cloth, steps=steps, frames_every=frames_every, dt=dt, thickness=thickness,
                                   culling=culling, model_path=model_path)
