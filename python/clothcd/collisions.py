"""The collisions of one step (Collisions, what CollisionDetector.detect returns), one collision of it (Collision) and
the step's earliest time of impact (EarliestImpact, what CollisionDetector.earliest_impact returns)."""

from __future__ import annotations

from typing import Dict, Iterator, NamedTuple, Optional, Tuple

import numpy as np

VERTEX_FACE = 0
"""Collisions.kind of a vertex-face pair: vertices[0] is the vertex, vertices[1:4] the triangle."""
EDGE_EDGE = 1
"""Collisions.kind of an edge-edge pair: vertices[0:2] is edge a, vertices[2:4] edge b."""
_KIND_NAMES = {VERTEX_FACE: "vertex_face", EDGE_EDGE: "edge_edge"}
"""The name of each kind, as the clothcd program's JSON names its collision lists."""


class Collision(NamedTuple):
    """One collision, as iterating over Collisions yields it (Python numbers; the fields of Collisions, one row).

    repr() names the kind: Collision(kind=vertex_face, ...) or Collision(kind=edge_edge, ...)."""

    kind: int
    """VERTEX_FACE (0) or EDGE_EDGE (1)."""
    bodies: Tuple[int, int, int, int]
    """Body of each vertex (0 = cloth, k = the k-th obstacle added)."""
    vertices: Tuple[int, int, int, int]
    """Vertex index of each vertex in its body, ordered as `kind` says."""
    toi: float
    """Earliest time of impact as a fraction of the step (a lower bound when conservative)."""
    parameters: Tuple[float, float]
    """Vertex-face: barycentric w1, w2 on the triangle; edge-edge: s on edge a, u on edge b."""
    normal: Tuple[float, float, float]
    """Unit contact normal at toi, from the second primitive to the first."""
    conservative: bool
    """Reported because the CCD could not decide the pair."""

    def __repr__(self) -> str:
        """The fields as a NamedTuple shows them, the kind by its name (a kind without one as its number)."""
        fields = [f"kind={_KIND_NAMES.get(self.kind, self.kind)}"]
        fields += [f"{name}={value!r}" for name, value in zip(self._fields[1:], self[1:])]
        return f"Collision({', '.join(fields)})"


class EarliestImpact(NamedTuple):
    """The earliest time of impact of a step (CollisionDetector.earliest_impact)."""

    toi: float
    """The step's earliest time of impact in [0, 1], 1 without contact: never later than the exact earliest contact of
    any pair (with a thickness h: the earliest time some pair comes within h), at thickness 0 in the default settings
    at most 1e-6 of the step before it. No safety factor is applied."""
    hit: bool
    """True when some pair comes into contact during the step."""
    pair: Optional[Collision]
    """The pair that sets toi (as detect() reports it), None without contact."""
    windows: int
    """Consecutive time windows of the step searched, in time order, up to the first that holds a contact."""


class Collisions:
    """Every collision of one step, one row per colliding primitive pair, as NumPy arrays (one per field).

    len() is the number of collisions, iterating yields one Collision per row, repr() is one line of counts and
    to_dict() gives one-dimensional columns (pandas.DataFrame(collisions.to_dict()))."""

    __slots__ = ("kind", "bodies", "vertices", "toi", "parameters", "normal", "conservative")

    kind: np.ndarray
    """(n,) uint8: VERTEX_FACE (0) or EDGE_EDGE (1)."""
    bodies: np.ndarray
    """(n, 4) int32: body of each vertex (0 = cloth, k = the k-th obstacle added)."""
    vertices: np.ndarray
    """(n, 4) int32: vertex index of each vertex in its body, ordered as `kind` says."""
    toi: np.ndarray
    """(n,) float64: earliest time of impact as a fraction of the step (a lower bound when conservative)."""
    parameters: np.ndarray
    """(n, 2) float64: vertex-face: barycentric w1, w2 on the triangle; edge-edge: s on edge a, u on edge b."""
    normal: np.ndarray
    """(n, 3) float64: unit contact normal at toi, from the second primitive to the first."""
    conservative: np.ndarray
    """(n,) bool: reported because the CCD could not decide the pair."""

    def __init__(self, kind: np.ndarray, bodies: np.ndarray, vertices: np.ndarray, toi: np.ndarray,
                 parameters: np.ndarray, normal: np.ndarray, conservative: np.ndarray) -> None:
        self.kind = kind
        self.bodies = bodies
        self.vertices = vertices
        self.toi = toi
        self.parameters = parameters
        self.normal = normal
        self.conservative = conservative

    def __len__(self) -> int:
        """The number of collisions."""
        return len(self.kind)

    def __iter__(self) -> Iterator[Collision]:
        """One Collision per row, in row order."""
        rows = zip(self.kind.tolist(), self.bodies.tolist(), self.vertices.tolist(), self.toi.tolist(),
                   self.parameters.tolist(), self.normal.tolist(), self.conservative.tolist())
        for kind, bodies, vertices, toi, parameters, normal, conservative in rows:
            yield Collision(kind, tuple(bodies), tuple(vertices), toi, tuple(parameters), tuple(normal), conservative)

    def __repr__(self) -> str:
        """One line: the counts by kind, the earliest toi and how many collisions are conservative."""
        vertex_face = int(np.count_nonzero(self.kind == VERTEX_FACE))
        earliest = f"{self.toi.min():.6g}" if len(self) > 0 else "none"
        return (f"Collisions({len(self)}: {vertex_face} vertex-face, {len(self) - vertex_face} edge-edge, "
                f"earliest toi {earliest}, {int(np.count_nonzero(self.conservative))} conservative)")

    def to_dict(self) -> Dict[str, np.ndarray]:
        """One-dimensional (n,) columns, views of the arrays (no copy): kind, body_0..body_3, vertex_0..vertex_3,
        toi, parameter_0, parameter_1, normal_x, normal_y, normal_z, conservative."""
        columns = {"kind": self.kind}
        columns.update((f"body_{k}", self.bodies[:, k]) for k in range(4))
        columns.update((f"vertex_{k}", self.vertices[:, k]) for k in range(4))
        columns["toi"] = self.toi
        columns.update((f"parameter_{k}", self.parameters[:, k]) for k in range(2))
        columns.update((f"normal_{axis}", self.normal[:, k]) for k, axis in enumerate("xyz"))
        columns["conservative"] = self.conservative
        return columns

    @property
    def vertex_face(self) -> np.ndarray:
        """(m, 4) vertices of the vertex-face pairs: vertex, then the triangle's three vertices."""
        return self.vertices[self.kind == VERTEX_FACE]

    @property
    def edge_edge(self) -> np.ndarray:
        """(m, 4) vertices of the edge-edge pairs: edge a's two vertices, then edge b's."""
        return self.vertices[self.kind == EDGE_EDGE]
