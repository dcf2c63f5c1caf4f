"""The state queries from Python (proximity, minimum_distance, intersections, is_intersection_free and the
closest-feature contacts) against a brute-force NumPy check on a small crumpled cloth, their refusals, and the
repulsion example."""

import pathlib
import subprocess
import sys

import numpy as np
import pytest

import clothcd


def crumpled_cloth(amplitude=0.08, seed=5):
    """A 7 x 7 cloth folded into waves and shaken: close pairs everywhere, some faces through others."""
    x, faces = clothcd.make_grid(7, 7, 0.6, 0.6)
    rng = np.random.default_rng(seed)
    x[:, 1] = amplitude * np.sin(11.0 * x[:, 0]) * np.cos(9.0 * x[:, 2])
    x += rng.normal(scale=0.02, size=x.shape)
    return x, faces


def unique_edges(faces):
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    return np.unique(edges, axis=0)


def point_triangle_distance(p, a, b, c):
    """Ericson's closest point on a triangle (Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return np.linalg.norm(p - a)
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return np.linalg.norm(p - b)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return np.linalg.norm(p - (a + d1 / (d1 - d3) * ab))
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return np.linalg.norm(p - c)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return np.linalg.norm(p - (a + d2 / (d2 - d6) * ac))
    va = d3 * d6 - d5 * d4
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0:
        return np.linalg.norm(p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)))
    denom = 1.0 / (va + vb + vc)
    return np.linalg.norm(p - (a + ab * vb * denom + ac * vc * denom))


def segment_segment_distance(p1, q1, p2, q2):
    """Ericson's closest points of two segments (5.1.9), with the ends tried as well for near-parallel segments."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = d1 @ d1, d2 @ d2, d2 @ r
    c, b = d1 @ r, d1 @ d2
    denom = a * e - b * b
    s = np.clip((b * f - c * e) / denom, 0.0, 1.0) if denom > 1e-14 * a * e else 0.0
    t = (b * s + f) / e
    if t < 0.0:
        t, s = 0.0, np.clip(-c / a, 0.0, 1.0)
    elif t > 1.0:
        t, s = 1.0, np.clip((b - c) / a, 0.0, 1.0)
    best = np.linalg.norm(p1 + s * d1 - (p2 + t * d2))
    for point, start, direction in ((p1, p2, d2), (q1, p2, d2), (p2, p1, d1), (q2, p1, d1)):
        u = np.clip((point - start) @ direction / (direction @ direction), 0.0, 1.0)
        best = min(best, np.linalg.norm(point - (start + u * direction)))
    return best


def brute_force_distances(x, faces):
    """{pair key: distance} over every vertex-face and edge-edge pair that shares no vertex."""
    distances = {}
    for v in range(len(x)):
        for f in faces:
            if v not in f:
                distances[("vf", v, *sorted(f.tolist()))] = point_triangle_distance(x[v], *x[f])
    edges = unique_edges(faces)
    for i, (a0, a1) in enumerate(edges):
        for b0, b1 in edges[i + 1:]:
            if len({a0, a1, b0, b1}) == 4:
                distances[("ee", a0, a1, b0, b1)] = segment_segment_distance(x[a0], x[a1], x[b0], x[b1])
    return distances


def key(kind, v):
    if kind == clothcd.VERTEX_FACE:
        return ("vf", int(v[0]), *sorted(int(i) for i in v[1:]))
    a, b = sorted([tuple(sorted((int(v[0]), int(v[1])))), tuple(sorted((int(v[2]), int(v[3]))))])
    return ("ee", *a, *b)


@pytest.fixture(scope="module")
def cloth():
    x, faces = crumpled_cloth()
    return x, faces, brute_force_distances(x, faces)


def test_proximity_reports_the_pairs_within_the_distance(cloth):
    x, faces, truth = cloth
    d = 0.08
    detector = clothcd.CollisionDetector(faces, len(x))
    pairs = detector.proximity(x, d)
    assert isinstance(pairs, clothcd.Proximities)
    ours = {key(k, v): dist for k, v, dist in zip(pairs.kind, pairs.vertices, pairs.distance)}
    within = {k: dist for k, dist in truth.items() if dist < d}
    assert len(within) > 20
    for k, dist in truth.items():  # away from the threshold, where the brute force's rounding cannot decide
        if abs(dist - d) > 1e-9:
            assert (k in ours) == (dist < d), k
    for k, dist in ours.items():
        assert dist == pytest.approx(truth[k], rel=1e-9, abs=1e-12)
    assert len(pairs) == len(ours)  # each pair once
    assert np.all(pairs.bodies == 0)
    assert pairs.parameters.shape == (len(pairs), 2) and pairs.direction.shape == (len(pairs), 3)
    touching = pairs.distance == 0
    assert np.allclose(np.linalg.norm(pairs.direction[~touching], axis=1), 1.0)
    assert set(pairs.type[pairs.kind == clothcd.VERTEX_FACE].tolist()) <= set(range(7))
    assert set(pairs.type[pairs.kind == clothcd.EDGE_EDGE].tolist()) <= set(range(7, 16))
    assert clothcd.DISTANCE_TYPES[pairs.type[0]] in clothcd.DISTANCE_TYPES
    assert detector.stats()["collisions"] == len(pairs)
    assert set(pairs.to_dict()) >= {"kind", "vertex_0", "distance", "direction_z", "type"}


def test_the_vertex_face_parameters_give_the_closest_point(cloth):
    x, faces, _ = cloth
    pairs = clothcd.CollisionDetector(faces, len(x)).proximity(x, 0.08)
    vf = pairs.kind == clothcd.VERTEX_FACE
    v = pairs.vertices[vf]
    w1, w2 = pairs.parameters[vf, 0], pairs.parameters[vf, 1]
    closest = (1 - w1 - w2)[:, None] * x[v[:, 1]] + w1[:, None] * x[v[:, 2]] + w2[:, None] * x[v[:, 3]]
    assert np.allclose(np.linalg.norm(x[v[:, 0]] - closest, axis=1), pairs.distance[vf], atol=1e-12)
    far = pairs.distance[vf] > 0
    assert np.allclose((x[v[far, 0]] - closest[far]) / pairs.distance[vf][far, None], pairs.direction[vf][far])


def test_the_minimum_distance_is_the_smallest_pair_distance(cloth):
    x, faces, truth = cloth
    detector = clothcd.CollisionDetector(faces, len(x))
    smallest = min(truth.values())
    minimum = detector.minimum_distance(x)
    assert minimum.found
    assert minimum.distance == pytest.approx(smallest, rel=1e-9, abs=1e-12)
    assert len(minimum.pair) == 1
    assert truth[key(minimum.pair.kind[0], minimum.pair.vertices[0])] == pytest.approx(smallest, rel=1e-9, abs=1e-12)
    assert minimum.pair.distance[0] == minimum.distance
    below = detector.minimum_distance(x, upper_bound=smallest / 2) if smallest > 0 else None
    if below is not None:
        assert below == clothcd.MinimumDistance(False, smallest / 2, None)


def test_a_flat_cloth_is_intersection_free():
    x, faces = clothcd.make_grid(7, 7, 0.6, 0.6)
    detector = clothcd.CollisionDetector(faces, len(x))
    assert detector.is_intersection_free(x)
    assert len(detector.intersections(x)) == 0


def test_intersections_find_a_face_pushed_through_the_cloth():
    x, faces = clothcd.make_grid(5, 5, 0.4, 0.4)
    # A second copy of the grid lifted and tilted so that it crosses the first: one cloth of two sheets.
    y = x.copy()
    y[:, 1] = 0.5 * x[:, 0] + 0.01
    both = np.vstack([x, y])
    both_faces = np.vstack([faces, faces + len(x)]).astype(np.int32)
    detector = clothcd.CollisionDetector(both_faces, len(both))
    found = detector.intersections(both)
    assert isinstance(found, clothcd.Intersections)
    assert len(found) > 0
    assert not detector.is_intersection_free(both)
    assert np.all(found.bodies == 0)
    assert np.all(found.faces[:, 0] < found.faces[:, 1])
    assert np.all(found.faces[:, 0] < len(faces)) and np.all(found.faces[:, 1] >= len(faces))  # sheet against sheet
    # The reported point: on the crossing edge at s, and on the other face at its weights.
    for i in range(len(found)):
        edge_point = (1 - found.edge_parameter[i]) * both[found.edge_vertices[i, 0]] + \
            found.edge_parameter[i] * both[found.edge_vertices[i, 1]]
        other = both_faces[found.faces[i, 1 - found.edge_face[i]]]
        w1, w2 = found.face_weights[i]
        face_point = (1 - w1 - w2) * both[other[0]] + w1 * both[other[1]] + w2 * both[other[2]]
        assert np.allclose(edge_point, face_point, atol=1e-12)
    assert found.coplanar.dtype == bool and not found.coplanar.any()


def test_closest_feature_contacts_list_each_contact_once(cloth):
    x, faces, _ = cloth
    pairs = clothcd.CollisionDetector(faces, len(x)).proximity(x, 0.08)
    contacts = clothcd.closest_feature_contacts(pairs)
    assert isinstance(contacts, clothcd.FeatureContacts)
    assert 0 < len(contacts) <= len(pairs)
    rows = {(int(k), *v.tolist()) for k, v in zip(contacts.kind, contacts.vertices)}
    assert len(rows) == len(contacts)
    assert set(contacts.kind.tolist()) <= set(range(len(clothcd.CONTACT_KINDS)))
    vertex_vertex = contacts.kind == clothcd.CONTACT_KINDS.index("vertex_vertex")
    assert np.all(contacts.vertices[vertex_vertex, 2:] == -1)
    assert contacts.distance.min() >= pairs.distance.min()
    # Inside-the-triangle vertex-face pairs are vertex-face contacts as they are.
    inside = (pairs.kind == clothcd.VERTEX_FACE) & (pairs.type == clothcd.DISTANCE_TYPES.index("point_face"))
    face_kind = clothcd.CONTACT_KINDS.index("vertex_face")
    for v in pairs.vertices[inside]:
        assert (face_kind, *v.tolist()) in rows


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_positions_are_refused(cloth, bad):
    x, faces, _ = cloth
    detector = clothcd.CollisionDetector(faces, len(x))
    y = x.copy()
    y[3, 1] = bad
    for call in (lambda: detector.proximity(y, 0.01), lambda: detector.minimum_distance(y),
                 lambda: detector.intersections(y), lambda: detector.is_intersection_free(y)):
        with pytest.raises(ValueError):
            call()


@pytest.mark.parametrize("distance", [0.0, -1.0, np.nan, np.inf])
def test_bad_distances_are_refused(cloth, distance):
    x, faces, _ = cloth
    with pytest.raises(ValueError):
        clothcd.CollisionDetector(faces, len(x)).proximity(x, distance)


def test_wrong_shapes_are_refused(cloth):
    x, faces, _ = cloth
    detector = clothcd.CollisionDetector(faces, len(x))
    with pytest.raises(ValueError):
        detector.proximity(x[:, :2], 0.01)
    with pytest.raises(ValueError):
        detector.intersections(x[:-1])
    with pytest.raises(ValueError):
        detector.minimum_distance(x, upper_bound=0.0)


def test_the_repulsion_example_keeps_the_cloth_outside_the_sphere(tmp_path):
    example = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "repulsion.py"
    picture = tmp_path / "repulsion.png"
    run = subprocess.run([sys.executable, str(example), str(picture), "60"], capture_output=True, text=True,
                         check=True)
    assert picture.stat().st_size > 1000
    assert "pairs within" in run.stdout and "intersection-free: True" in run.stdout
    assert float(run.stdout.split("centre ")[1].split()[0]) >= 0.49
