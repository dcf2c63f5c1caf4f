"""The state queries from Python give the answers of `clothcd proximity` and `clothcd intersections` on the same mesh:
the same pairs, distances to the bit, the same minimum and the same intersecting faces."""

import json
import subprocess

import numpy as np

import clothcd


def crossing_sheets(tmp_path):
    """Two 6 x 6 sheets in one mesh, the second tilted through the first, written as PLY (full precision)."""
    x, faces = clothcd.make_grid(6, 6, 0.5, 0.5)
    rng = np.random.default_rng(7)
    flat = x + rng.normal(scale=0.004, size=x.shape)
    tilted = x.copy()
    tilted[:, 1] = 0.4 * x[:, 0] + 0.013
    vertices = np.vstack([flat, tilted])
    all_faces = np.vstack([faces, faces + len(x)]).astype(np.int32)
    path = tmp_path / "sheets.ply"
    clothcd.save_mesh(str(path), vertices, all_faces)
    vertices, _, all_faces = clothcd.load_mesh_frames(str(path), str(path))  # as the program reads it
    return path, vertices, all_faces


def cli_json(cli, *arguments):
    return json.loads(subprocess.run([cli, *map(str, arguments), "--json"], check=True, capture_output=True,
                                     text=True).stdout)


def test_proximity_matches_the_cli(cli, tmp_path):
    path, x, faces = crossing_sheets(tmp_path)
    ours = clothcd.CollisionDetector(faces, len(x)).proximity(x, 0.04)
    theirs = cli_json(cli, "proximity", path, "--distance", 0.04)
    vf = ours.kind == clothcd.VERTEX_FACE
    assert len(ours) > 10
    assert [[c["pair"][0], *c["face_vertices"]] for c in theirs["vertex_face"]] == ours.vertices[vf].tolist()
    assert [c["pair"][0] + c["pair"][1] for c in theirs["edge_edge"]] == ours.vertices[~vf].tolist()
    assert [c["distance"] for c in theirs["vertex_face"] + theirs["edge_edge"]] == \
        ours.distance[vf].tolist() + ours.distance[~vf].tolist()
    assert [c["type"] for c in theirs["vertex_face"] + theirs["edge_edge"]] == \
        [clothcd.DISTANCE_TYPES[t] for t in ours.type[vf].tolist() + ours.type[~vf].tolist()]


def test_minimum_distance_matches_the_cli(cli, tmp_path):
    path, x, faces = crossing_sheets(tmp_path)
    ours = clothcd.CollisionDetector(faces, len(x)).minimum_distance(x)
    theirs = cli_json(cli, "proximity", path, "--minimum")["minimum"]
    assert theirs["found"] and ours.found
    assert theirs["distance"] == ours.distance


def test_contacts_match_the_cli(cli, tmp_path):
    path, x, faces = crossing_sheets(tmp_path)
    ours = clothcd.closest_feature_contacts(clothcd.CollisionDetector(faces, len(x)).proximity(x, 0.04))
    theirs = cli_json(cli, "proximity", path, "--distance", 0.04, "--contacts")["contacts"]
    assert [c["kind"] for c in theirs] == [clothcd.CONTACT_KINDS[k] for k in ours.kind.tolist()]
    assert [c["vertices"] for c in theirs] == [[v for v in row if v >= 0] for row in ours.vertices.tolist()]


def test_intersections_match_the_cli(cli, tmp_path):
    path, x, faces = crossing_sheets(tmp_path)
    detector = clothcd.CollisionDetector(faces, len(x))
    ours = detector.intersections(x)
    theirs = cli_json(cli, "intersections", path)
    assert len(ours) > 0
    assert theirs["intersection_free"] is False and not detector.is_intersection_free(x)
    assert [c["faces"] for c in theirs["intersections"]] == ours.faces.tolist()
    assert [c["edge"] for c in theirs["intersections"]] == ours.edge_vertices.tolist()
    assert [c["coplanar"] for c in theirs["intersections"]] == ours.coplanar.tolist()
