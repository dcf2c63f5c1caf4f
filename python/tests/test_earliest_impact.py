"""CollisionDetector.earliest_impact from Python: the step's earliest time of impact, the pair that sets it, a step
without contact, and the line-search example."""

import os
import subprocess
import sys

import numpy as np

import clothcd

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def falling_cloth(drop):
    """A 6 x 6 cloth 0.1 above a plate obstacle, falling by `drop`."""
    cloth, faces = clothcd.make_grid(6, 6, 0.5, 0.5)
    plate, plate_faces = clothcd.make_grid(3, 3, 2.0, 2.0)
    x0 = cloth + [0.0, 0.1, 0.0]
    x1 = x0 - [0.0, drop, 0.0]
    detector = clothcd.CollisionDetector(faces, len(x0))
    detector.add_obstacle(plate, plate_faces)
    return detector, x0, x1


def test_the_earliest_impact_is_detect_s_earliest_collision():
    detector, x0, x1 = falling_cloth(0.4)  # through the plate at t = 0.25
    collisions = detector.detect(x0, x1)
    impact = detector.earliest_impact(np.asfortranarray(x0), x1)
    assert impact.hit
    assert impact.toi == collisions.toi.min()
    assert 0.25 - 1e-6 <= impact.toi <= 0.25
    assert impact.windows >= 2  # the first window, at most 1/16 of the step, holds no contact
    assert isinstance(impact.pair, clothcd.Collision)
    assert impact.pair.toi == impact.toi
    assert impact.pair.bodies[1:] == (1, 1, 1)  # a cloth vertex against a plate face
    assert detector.stats()["collisions"] == 1


def test_a_step_without_contact_is_free_to_the_end():
    detector, x0, x1 = falling_cloth(0.05)
    impact = detector.earliest_impact(x0, x1)
    assert impact == clothcd.EarliestImpact(1.0, False, None, 3)


def test_the_line_search_example_never_passes_through_the_sphere(tmp_path):
    picture = tmp_path / "line_search.png"
    run = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "python", "line_search.py"), str(picture),
                          "60"], capture_output=True, text=True, check=True)
    assert picture.stat().st_size > 1000
    assert "shortened by the collision-free fraction" in run.stdout
    closest = float(run.stdout.split("centre ")[1].split()[0])
    assert closest >= 0.49  # the sphere's faces are within 0.5 * cos(pi / 32) of its centre
