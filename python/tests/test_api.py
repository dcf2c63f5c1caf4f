"""The Python API: version, meshes, simplification, boxes, CCD, simulation, and clear errors on bad input."""

import pathlib
import re
import threading

import numpy as np
import pytest

import clothcd


def test_version_is_the_project_version(root):
    declared = re.search(r"project\(clothcd VERSION ([0-9.]+)", (root / "CMakeLists.txt").read_text()).group(1)
    assert clothcd.__version__ == declared


def test_mesh_round_trip_simplify_and_obb(tmp_path):
    vertices, faces = clothcd.make_uv_sphere(1.0, 32, 16)
    assert vertices.dtype == np.float64 and vertices.shape[1] == 3 and faces.dtype == np.int32
    path = tmp_path / "sphere.ply"
    clothcd.save_mesh(str(path), vertices, faces)
    loaded_vertices, loaded_faces = clothcd.load_mesh(str(path))
    assert loaded_faces.shape == faces.shape
    small_vertices, small_faces = clothcd.simplify(loaded_vertices, loaded_faces, ratio=0.25)
    assert 0 < len(small_faces) <= 0.25 * len(faces) + 2
    center, axes, half = clothcd.obb(vertices, faces, "adaptive")
    local = (vertices - center) @ axes
    assert np.all(np.abs(local) <= half + 1e-9)
    assert np.allclose(axes.T @ axes, np.eye(3), atol=1e-9)


def test_detect_fields_and_obstacles():
    cloth_vertices, cloth_faces = clothcd.make_grid(10, 10, 1.0, 1.0)
    x0 = cloth_vertices + [0.0, 0.05, 0.0]
    x1 = cloth_vertices + [0.0, -0.05, 0.0]  # falls through the plate below
    plate_vertices = np.array([[-1.0, 0.0, -1.0], [2.0, 0.0, -1.0], [2.0, 0.0, 2.0], [-1.0, 0.0, 2.0]])
    plate_faces = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.int32)
    detector = clothcd.CollisionDetector(cloth_faces, len(cloth_vertices), thickness=0.0)
    assert detector.add_obstacle(plate_vertices, plate_faces) == 1
    found = detector.detect(x0, x1)
    assert len(found.kind) > 0
    vertex_face = found.kind == clothcd.VERTEX_FACE
    # Every cloth vertex crosses the plate at half the step.
    cloth_vertex_hits = vertex_face & (found.bodies[:, 0] == 0) & (found.bodies[:, 1] == 1)
    assert set(found.vertices[cloth_vertex_hits, 0]) == set(range(len(cloth_vertices)))
    assert np.allclose(found.toi[cloth_vertex_hits], 0.5, atol=1e-6)
    assert np.allclose(np.abs(found.normal[cloth_vertex_hits, 1]), 1.0, atol=1e-9)
    assert found.conservative.dtype == bool and found.parameters.shape == (len(found.kind), 2)
    # The plate moved away over the step: nothing left to hit.
    away = np.eye(4)
    away[1, 3] = 5.0
    detector.set_obstacle_transforms(1, away, away)
    assert len(detector.detect(x0, x1).kind) == 0


def test_column_major_and_other_dtypes_are_accepted():
    cloth_vertices, cloth_faces = clothcd.make_paper_cloth("A")
    detector = clothcd.CollisionDetector(cloth_faces.astype(np.int64), len(cloth_vertices))
    x1 = cloth_vertices + 0.001
    c_order = detector.detect(cloth_vertices, x1)
    fortran = detector.detect(np.asfortranarray(cloth_vertices), np.asfortranarray(x1).astype(np.float32).astype(np.float64))
    assert len(c_order.kind) == len(fortran.kind)


def same_collisions(a: clothcd.Collisions, b: clothcd.Collisions) -> bool:
    columns_a, columns_b = a.to_dict(), b.to_dict()
    return all(np.array_equal(columns_a[name], columns_b[name]) for name in columns_a)


def data_address(array: np.ndarray) -> int:
    return array.__array_interface__["data"][0]


def test_detect_reads_float64_arrays_in_place():
    cloth_vertices, cloth_faces = clothcd.make_paper_cloth("B")
    rng = np.random.default_rng(3)
    x0 = cloth_vertices.copy()
    x1 = cloth_vertices + rng.normal(scale=0.02, size=cloth_vertices.shape)
    detector = clothcd.CollisionDetector(cloth_faces, len(x0))
    expected = detector.detect(x0, x1)
    assert len(expected.kind) > 0
    assert detector._detector._last_detect_inputs() == (data_address(x0), data_address(x1))
    # Fortran order and the first three columns of wider rows: read in place too, with the same answer.
    fortran = np.asfortranarray(x0)
    padded = np.full((len(x1), 4), np.nan)
    padded[:, :3] = x1
    found = clothcd.CollisionDetector(cloth_faces, len(x0)).detect(fortran, padded[:, :3])
    assert same_collisions(found, expected)
    fresh = clothcd.CollisionDetector(cloth_faces, len(x0))
    fresh.detect(fortran, padded[:, :3])
    assert fresh._detector._last_detect_inputs() == (data_address(fortran), data_address(padded))
    # Another dtype is converted: the detector reads a copy, which the addresses show.
    x1_single = x1.astype(np.float32)
    fresh.detect(x0, x1_single)
    assert fresh._detector._last_detect_inputs()[0] == data_address(x0)
    assert fresh._detector._last_detect_inputs()[1] != data_address(x1_single)
    # Rows in reverse (a negative stride), numbered in reverse by the faces: the same collisions as a C-order copy.
    last = len(x0) - 1
    reverse_faces = last - cloth_faces
    reversed_rows = clothcd.CollisionDetector(reverse_faces, len(x0)).detect(x0[::-1], x1[::-1])
    copied = clothcd.CollisionDetector(reverse_faces, len(x0)).detect(x0[::-1].copy(), x1[::-1].copy())
    assert len(reversed_rows.kind) > 0 and same_collisions(reversed_rows, copied)


def test_obstacle_positions_in_any_order():
    cloth_vertices, cloth_faces = clothcd.make_grid(8, 8, 1.0, 1.0)
    plate_vertices = np.array([[-1.0, 0.0, -1.0], [2.0, 0.0, -1.0], [2.0, 0.0, 2.0], [-1.0, 0.0, 2.0]])
    plate_faces = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.int32)
    x0 = cloth_vertices + [0.0, 0.05, 0.0]
    results = []
    for order in ("C", "F"):
        detector = clothcd.CollisionDetector(cloth_faces, len(x0))
        detector.add_obstacle(plate_vertices, plate_faces)
        raised = np.array(plate_vertices + [0.0, 0.1, 0.0], order=order)
        detector.set_obstacle_positions(1, np.array(plate_vertices, order=order), raised)
        results.append(detector.detect(x0, x0))
    assert len(results[0].kind) > 0 and same_collisions(results[0], results[1])


def test_ccd_on_query_arrays():
    # A vertex falling through a triangle, and the same vertex beside it.
    triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    hit = np.array([[0.2, 1.0, 0.2]] + triangle + [[0.2, -1.0, 0.2]] + triangle)
    miss = np.array([[3.0, 1.0, 3.0]] + triangle + [[3.0, -1.0, 3.0]] + triangle)
    hits, toi, culled = clothcd.ccd(np.stack([hit, miss]), "vf")
    assert hits.tolist() == [True, False]
    assert 0.5 - 1e-6 <= toi[0] <= 0.5  # a lower bound of the time of impact
    assert not culled[0]
    # Seeded random queries: the filters never cull a pair the unfiltered CCD finds colliding.
    rng = np.random.default_rng(5)
    queries = rng.uniform(-1.0, 1.0, size=(2000, 8, 3))
    for kind in ("vf", "ee"):
        plain, _, _ = clothcd.ccd(queries, kind, filter="none")
        filtered, _, culled = clothcd.ccd(queries, kind, filter="combined")
        assert not np.any(plain & culled)
        assert np.array_equal(plain, filtered | (plain & culled))


def test_simulation_drops_a_cloth_on_a_sphere():
    cloth = clothcd.make_paper_cloth("A", 1.6)
    cloth_vertices = cloth[0] + [0.0, 0.8, 0.0]
    sphere = clothcd.make_uv_sphere(0.5, 24, 12)
    frames = clothcd.simulate((cloth_vertices, cloth[1]), [sphere], steps=40, frames_every=20)
    assert len(frames) == 3
    assert all(f.shape == cloth_vertices.shape and np.all(np.isfinite(f)) for f in frames)
    assert frames[-1][:, 1].mean() < frames[0][:, 1].mean()  # it fell
    # Nothing passed into the sphere: every cloth vertex stays outside it (up to the thickness).
    assert np.min(np.linalg.norm(frames[-1], axis=1)) > 0.5 - 0.01
    # The network culler (the shipped model) gives the same simulation: it culls only pairs that cannot collide.
    with_network = clothcd.simulate((cloth_vertices, cloth[1]), [sphere], steps=40, frames_every=20, culling="network")
    assert all(np.array_equal(a, b) for a, b in zip(frames, with_network))


def test_threads_get_the_same_answers():
    cloth_vertices, cloth_faces = clothcd.make_paper_cloth("B")
    rng = np.random.default_rng(9)
    x1 = cloth_vertices + rng.normal(scale=0.02, size=cloth_vertices.shape)
    expected = clothcd.CollisionDetector(cloth_faces, len(cloth_vertices)).detect(cloth_vertices, x1)
    results = [None] * 4

    def run(i):
        results[i] = clothcd.CollisionDetector(cloth_faces, len(cloth_vertices)).detect(cloth_vertices, x1)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r.vertices, expected.vertices) and np.array_equal(r.toi, expected.toi)


def test_bad_input_raises_with_the_library_message(tmp_path):
    with pytest.raises(OSError, match="nonexistent"):
        clothcd.load_mesh(str(tmp_path / "nonexistent.obj"))
    truncated = tmp_path / "truncated.off"
    truncated.write_text("OFF\n4 2 0\n0 0 0\n1 0 0\n")
    with pytest.raises(OSError, match="truncated.off"):
        clothcd.load_mesh(str(truncated))
    cloth_vertices, cloth_faces = clothcd.make_paper_cloth("A")
    with pytest.raises(ValueError, match="outside"):
        clothcd.CollisionDetector(cloth_faces + 1000, len(cloth_vertices))
    detector = clothcd.CollisionDetector(cloth_faces, len(cloth_vertices))
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        detector.detect(cloth_vertices[:, :2], cloth_vertices[:, :2])
    with pytest.raises(ValueError, match="rows"):
        detector.detect(cloth_vertices[:10], cloth_vertices[:10])
    bad = cloth_vertices.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        detector.detect(cloth_vertices, bad)
    with pytest.raises(ValueError, match="culling"):
        clothcd.CollisionDetector(cloth_faces, len(cloth_vertices), culling="magic")
    with pytest.raises(OSError, match="no-such-model"):
        clothcd.CollisionDetector(cloth_faces, len(cloth_vertices), culling="network", model_path=str(tmp_path / "no-such-model"))
    with pytest.raises(ValueError, match="body"):
        detector.set_obstacle_transforms(7, np.eye(4), np.eye(4))
    with pytest.raises(ValueError, match=r"\(N, 8, 3\)"):
        clothcd.ccd(np.zeros((3, 4, 3)))
    queries = np.zeros((3, 8, 3))
    queries[2, 5, 1] = np.inf
    with pytest.raises(ValueError, match="NaN or infinite"):
        clothcd.ccd(queries)
    with pytest.raises(ValueError):
        clothcd.simulate(clothcd.make_paper_cloth("A"), [], steps=-1)
