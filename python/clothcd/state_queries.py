"""The answers of the state queries, the questions of one set of positions: the pairs within a distance
(Proximities, what CollisionDetector.proximity returns), the smallest distance (MinimumDistance), the intersecting
face pairs (Intersections) and the closest-feature contacts of the pairs within a distance (FeatureContacts, what
closest_feature_contacts returns)."""

from __future__ import annotations

from typing import Dict, NamedTuple, Optional, Tuple

import numpy as np

from . import _clothcd

DISTANCE_TYPES = (
    "point_face", "point_edge0", "point_edge1", "point_edge2", "point_vertex0", "point_vertex1", "point_vertex2",
    "edge_edge", "edge_vertex_b0", "edge_vertex_b1", "vertex_a0_edge", "vertex_a1_edge",
    "vertex_a0_vertex_b0", "vertex_a0_vertex_b1", "vertex_a1_vertex_b0", "vertex_a1_vertex_b1",
)
"""The name of each Proximities.type value (DISTANCE_TYPES[type]), the C++ clothcd::DistanceType in order: where the
closest points lie. Vertex-face pairs (0-6): inside the triangle, on its edge k (vertices[1 + k], vertices[1 + (k + 1)
% 3]) between the ends, or at its vertex k (vertices[1 + k]). Edge-edge pairs (7-15): between the ends of both edges
(edge a = vertices[0:2], edge b = vertices[2:4]), at an end of one edge (b0 = vertices[2], b1 = vertices[3],
a0 = vertices[0], a1 = vertices[1]) and between the ends of the other, or at ends of both."""

CONTACT_KINDS = ("vertex_vertex", "vertex_edge", "edge_edge", "vertex_face")
"""The name of each FeatureContacts.kind value (CONTACT_KINDS[kind]), the C++ clothcd::ContactKind in order."""


class Proximities:
    """The pairs within a distance at one state (CollisionDetector.proximity), one row per pair, as NumPy arrays, in
    the detector's order (vertex-face pairs first, each kind sorted by its primitives).

    len() is the number of pairs, repr() is one line of counts and to_dict() gives one-dimensional columns."""

    __slots__ = ("kind", "bodies", "vertices", "distance", "parameters", "direction", "type")

    kind: np.ndarray
    """(n,) uint8: VERTEX_FACE (0) or EDGE_EDGE (1)."""
    bodies: np.ndarray
    """(n, 4) int32: body of each vertex (0 = cloth, k = the k-th obstacle added)."""
    vertices: np.ndarray
    """(n, 4) int32: vertex index of each vertex in its body, ordered as `kind` says."""
    distance: np.ndarray
    """(n,) float64: distance between the two closed primitives (relative error at most 2^-40; 0 when they touch)."""
    parameters: np.ndarray
    """(n, 2) float64: vertex-face: barycentric w1, w2 of the closest point on the triangle (w0 = 1 - w1 - w2);
    edge-edge: s on edge a, u on edge b of the closest points."""
    direction: np.ndarray
    """(n, 3) float64: unit direction from the closest point of the second primitive to that of the first (zero when
    they touch)."""
    type: np.ndarray
    """(n,) uint8: where the closest points lie, DISTANCE_TYPES[type] names it."""

    def __init__(self, kind: np.ndarray, bodies: np.ndarray, vertices: np.ndarray, distance: np.ndarray,
                 parameters: np.ndarray, direction: np.ndarray, type: np.ndarray) -> None:
        self.kind = kind
        self.bodies = bodies
        self.vertices = vertices
        self.distance = distance
        self.parameters = parameters
        self.direction = direction
        self.type = type

    def __len__(self) -> int:
        """The number of pairs."""
        return len(self.kind)

    def __repr__(self) -> str:
        """One line: the counts by kind and the smallest distance."""
        vertex_face = int(np.count_nonzero(self.kind == 0))
        smallest = f"{self.distance.min():.6g}" if len(self) > 0 else "none"
        return (f"Proximities({len(self)}: {vertex_face} vertex-face, {len(self) - vertex_face} edge-edge, "
                f"smallest distance {smallest})")

    def row(self, i: int) -> "Proximities":
        """The one-row Proximities of row i."""
        return Proximities(*(getattr(self, name)[i:i + 1] for name in self.__slots__))

    def to_dict(self) -> Dict[str, np.ndarray]:
        """One-dimensional (n,) columns, views of the arrays: kind, body_0..body_3, vertex_0..vertex_3, distance,
        parameter_0, parameter_1, direction_x, direction_y, direction_z, type."""
        columns = {"kind": self.kind}
        columns.update((f"body_{k}", self.bodies[:, k]) for k in range(4))
        columns.update((f"vertex_{k}", self.vertices[:, k]) for k in range(4))
        columns["distance"] = self.distance
        columns.update((f"parameter_{k}", self.parameters[:, k]) for k in range(2))
        columns.update((f"direction_{axis}", self.direction[:, k]) for k, axis in enumerate("xyz"))
        columns["type"] = self.type
        return columns


class MinimumDistance(NamedTuple):
    """The smallest distance at one state (CollisionDetector.minimum_distance)."""

    found: bool
    """True when some pair is closer than the upper bound (always, without one, when there is a pair at all)."""
    distance: float
    """The smallest distance over the pairs (relative error at most 2^-40); the upper bound when none was found."""
    pair: Optional[Proximities]
    """With `found`: a one-row Proximities of a pair at that distance; None otherwise."""


class Intersections:
    """The intersecting face pairs at one state (CollisionDetector.intersections), one row per pair, sorted by the
    first face's body and index, then the second's.

    len() is the number of pairs and repr() one line of counts."""

    __slots__ = ("bodies", "faces", "edge_face", "edge_vertices", "edge_parameter", "face_weights", "coplanar")

    bodies: np.ndarray
    """(n, 2) int32: body of each face (0 = cloth), bodies[:, 0] <= bodies[:, 1]."""
    faces: np.ndarray
    """(n, 2) int32: face index of each in its body (within one body faces[:, 0] < faces[:, 1])."""
    edge_face: np.ndarray
    """(n,) uint8: which face (0 or 1) has the edge that crosses the other at a common point."""
    edge_vertices: np.ndarray
    """(n, 2) int32: that edge's two vertices (in its face's order, of body bodies[i, edge_face[i]])."""
    edge_parameter: np.ndarray
    """(n,) float64: the common point's parameter s on the edge (from edge_vertices[:, 0] to [:, 1])."""
    face_weights: np.ndarray
    """(n, 2) float64: its barycentric weights w1, w2 on the other face's corners 1 and 2 (corner 0: 1 - w1 - w2)."""
    coplanar: np.ndarray
    """(n,) bool: the two faces lie in one plane (exactly)."""

    def __init__(self, bodies: np.ndarray, faces: np.ndarray, edge_face: np.ndarray, edge_vertices: np.ndarray,
                 edge_parameter: np.ndarray, face_weights: np.ndarray, coplanar: np.ndarray) -> None:
        self.bodies = bodies
        self.faces = faces
        self.edge_face = edge_face
        self.edge_vertices = edge_vertices
        self.edge_parameter = edge_parameter
        self.face_weights = face_weights
        self.coplanar = coplanar

    def __len__(self) -> int:
        """The number of intersecting face pairs."""
        return len(self.faces)

    def __repr__(self) -> str:
        """One line: the count and how many pairs are coplanar."""
        return f"Intersections({len(self)}: {int(np.count_nonzero(self.coplanar))} coplanar)"


class FeatureContacts:
    """The closest-feature contacts of a set of pairs (closest_feature_contacts), each once: a barrier's active set,
    sorted by kind, then vertices."""

    __slots__ = ("kind", "bodies", "vertices", "distance")

    kind: np.ndarray
    """(n,) uint8: CONTACT_KINDS[kind]: vertex_vertex (vertices[:, 0:2]), vertex_edge (the vertex vertices[:, 0],
    the edge vertices[:, 1:3]), edge_edge (vertices[:, 0:2] and vertices[:, 2:4]), vertex_face (the vertex, then the
    triangle)."""
    bodies: np.ndarray
    """(n, 4) int32: body of each vertex (-1 where unused)."""
    vertices: np.ndarray
    """(n, 4) int32: the features' vertices (-1 where unused)."""
    distance: np.ndarray
    """(n,) float64: the features' distance."""

    def __init__(self, kind: np.ndarray, bodies: np.ndarray, vertices: np.ndarray, distance: np.ndarray) -> None:
        self.kind = kind
        self.bodies = bodies
        self.vertices = vertices
        self.distance = distance

    def __len__(self) -> int:
        """The number of contacts."""
        return len(self.kind)

    def __repr__(self) -> str:
        """One line: the counts by kind."""
        counts = ", ".join(f"{int(np.count_nonzero(self.kind == k))} {name.replace('_', '-')}"
                           for k, name in enumerate(CONTACT_KINDS))
        return f"FeatureContacts({len(self)}: {counts})"


def closest_feature_contacts(pairs: Proximities) -> FeatureContacts:
    """The pairs of closest features of `pairs` (what CollisionDetector.proximity returns), each once, as IPC
    Toolkit's normal collisions build a barrier's active set: a vertex-face pair whose closest point is inside the
    triangle is a vertex-face contact, on an edge of it a vertex-edge contact, at a vertex of it a vertex-vertex
    contact; edge-edge pairs likewise. Several pairs giving the same contact (a vertex near an edge is near both of its
    faces) give it once, with the distance of the first."""
    columns = _clothcd._closest_feature_contacts(
        np.ascontiguousarray(pairs.kind, dtype=np.uint8), np.ascontiguousarray(pairs.bodies, dtype=np.int32),
        np.ascontiguousarray(pairs.vertices, dtype=np.int32), np.ascontiguousarray(pairs.distance, dtype=np.float64),
        np.ascontiguousarray(pairs.type, dtype=np.uint8))
    return FeatureContacts(*columns)


def intersections(columns: Tuple[np.ndarray, ...]) -> Intersections:
    """Intersections of the extension's columns (coplanar as bool)."""
    bodies, faces, edge_face, edge_vertices, edge_parameter, face_weights, coplanar = columns
    return Intersections(bodies, faces, edge_face, edge_vertices, edge_parameter, face_weights, coplanar.view(bool))
