"""The Collisions result: len(), one record per collision when iterated (its repr() naming the kind), a one-line repr()
and flat columns."""

import numpy as np

import clothcd


def two_collisions() -> clothcd.Collisions:
    """A vertex-face collision at toi 0.75 and a conservative edge-edge one at 0.25, written by hand."""
    return clothcd.Collisions(
        kind=np.array([clothcd.VERTEX_FACE, clothcd.EDGE_EDGE], dtype=np.uint8),
        bodies=np.array([[0, 1, 1, 1], [0, 0, 0, 0]], dtype=np.int32),
        vertices=np.array([[5, 0, 1, 2], [3, 4, 7, 8]], dtype=np.int32),
        toi=np.array([0.75, 0.25]),
        parameters=np.array([[0.1, 0.2], [0.3, 0.4]]),
        normal=np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]),
        conservative=np.array([False, True]))


def plate_collisions() -> clothcd.Collisions:
    """A 6 x 6 grid falling through a plate below it: every grid vertex hits the plate at half the step."""
    cloth_vertices, cloth_faces = clothcd.make_grid(6, 6, 1.0, 1.0)
    plate_vertices = np.array([[-1.0, 0.0, -1.0], [2.0, 0.0, -1.0], [2.0, 0.0, 2.0], [-1.0, 0.0, 2.0]])
    plate_faces = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.int32)
    detector = clothcd.CollisionDetector(cloth_faces, len(cloth_vertices))
    detector.add_obstacle(plate_vertices, plate_faces)
    return detector.detect(cloth_vertices + [0.0, 0.05, 0.0], cloth_vertices + [0.0, -0.05, 0.0])


def test_len_is_the_number_of_collisions():
    assert len(two_collisions()) == 2
    found = plate_collisions()
    assert len(found) == len(found.kind) > 36


def test_iteration_yields_one_record_per_row():
    records = list(two_collisions())
    assert records == [
        clothcd.Collision(clothcd.VERTEX_FACE, (0, 1, 1, 1), (5, 0, 1, 2), 0.75, (0.1, 0.2), (0.0, 1.0, 0.0), False),
        clothcd.Collision(clothcd.EDGE_EDGE, (0, 0, 0, 0), (3, 4, 7, 8), 0.25, (0.3, 0.4), (1.0, 0.0, 0.0), True),
    ]
    assert all(type(value) in (int, float, bool, tuple) for record in records for value in record)


def test_a_record_s_repr_names_its_kind():
    vertex_face, edge_edge = two_collisions()
    assert repr(vertex_face) == ("Collision(kind=vertex_face, bodies=(0, 1, 1, 1), vertices=(5, 0, 1, 2), toi=0.75, "
                                 "parameters=(0.1, 0.2), normal=(0.0, 1.0, 0.0), conservative=False)")
    assert repr(edge_edge) == ("Collision(kind=edge_edge, bodies=(0, 0, 0, 0), vertices=(3, 4, 7, 8), toi=0.25, "
                               "parameters=(0.3, 0.4), normal=(1.0, 0.0, 0.0), conservative=True)")


def test_iteration_matches_the_arrays_of_a_detected_step():
    found = plate_collisions()
    records = list(found)
    assert len(records) == len(found)
    for i, record in enumerate(records):
        assert record.kind == found.kind[i] and record.toi == found.toi[i]
        assert record.conservative == found.conservative[i]
        assert record.bodies == tuple(found.bodies[i]) and record.vertices == tuple(found.vertices[i])
        assert record.parameters == tuple(found.parameters[i]) and record.normal == tuple(found.normal[i])


def test_repr_is_one_line_of_counts():
    assert repr(two_collisions()) == (
        "Collisions(2: 1 vertex-face, 1 edge-edge, earliest toi 0.25, 1 conservative)")
    found = plate_collisions()
    vertex_face = int(np.count_nonzero(found.kind == clothcd.VERTEX_FACE))
    conservative = int(np.count_nonzero(found.conservative))
    assert repr(found) == (f"Collisions({len(found)}: {vertex_face} vertex-face, {len(found) - vertex_face} edge-edge, "
                           f"earliest toi {found.toi.min():.6g}, {conservative} conservative)")
    assert "\n" not in repr(found)


def test_repr_of_no_collision():
    empty = clothcd.Collisions(*(np.zeros((0,) + shape, dtype) for shape, dtype in [
        ((), np.uint8), ((4,), np.int32), ((4,), np.int32), ((), np.float64), ((2,), np.float64), ((3,), np.float64),
        ((), bool)]))
    assert len(empty) == 0 and list(empty) == [] and len(empty.to_dict()["toi"]) == 0
    assert repr(empty) == "Collisions(0: 0 vertex-face, 0 edge-edge, earliest toi none, 0 conservative)"


def test_to_dict_gives_flat_columns_of_every_field():
    found = two_collisions()
    columns = found.to_dict()
    assert list(columns) == ["kind", "body_0", "body_1", "body_2", "body_3", "vertex_0", "vertex_1", "vertex_2",
                             "vertex_3", "toi", "parameter_0", "parameter_1", "normal_x", "normal_y", "normal_z",
                             "conservative"]
    assert all(column.shape == (2,) for column in columns.values())
    assert columns["vertex_2"].tolist() == [1, 7] and columns["body_1"].tolist() == [1, 0]
    assert columns["parameter_1"].tolist() == [0.2, 0.4] and columns["normal_x"].tolist() == [0.0, 1.0]
    assert columns["conservative"].tolist() == [False, True] and columns["toi"].tolist() == [0.75, 0.25]
    assert np.shares_memory(columns["vertex_0"], found.vertices)  # views, not copies
