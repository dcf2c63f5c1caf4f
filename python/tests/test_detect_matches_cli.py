"""CollisionDetector.detect from Python reports exactly the pairs, times of impact and conservative flags of
`clothcd detect --out` on the same frames: generated crumpled cloths and, when present, the Scalable CCD sample."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import clothcd


def crumpled_frames(tmp_path: pathlib.Path, seed: int, letter: str = "A"):
    """Cloth `letter` lifted into waves at t0 and pushed through itself at t1, written as PLY (full precision)."""
    vertices, faces = clothcd.make_paper_cloth(letter)
    rng = np.random.default_rng(seed)
    x0 = vertices.copy()
    x0[:, 1] = 0.05 * np.sin(9.0 * vertices[:, 0]) * np.cos(7.0 * vertices[:, 2])
    x1 = x0 + rng.normal(scale=0.03, size=x0.shape)
    t0, t1 = tmp_path / f"t0-{seed}.ply", tmp_path / f"t1-{seed}.ply"
    clothcd.save_mesh(str(t0), x0, faces)
    clothcd.save_mesh(str(t1), x1, faces)
    return t0, t1


def cli_pairs(cli: str, t0, t1, out: pathlib.Path, extra=()):
    subprocess.run([cli, "detect", str(t0), str(t1), "--out", str(out), *extra], check=True, capture_output=True)
    return json.loads(out.read_text())


def canonical_cli(result, faces):
    """{(kind, vertices...): (toi, conservative)} from the program's JSON (faces by index -> their vertices)."""
    pairs = {}
    for c in result["vertex_face"]:
        v, f = c["pair"]
        pairs[("vf", v, *sorted(faces[f]))] = (c["toi"], c.get("conservative", False))
    for c in result["edge_edge"]:
        a, b = sorted(tuple(sorted(e)) for e in c["pair"])
        pairs[("ee", *a, *b)] = (c["toi"], c.get("conservative", False))
    return pairs


def canonical_python(collisions: clothcd.Collisions):
    pairs = {}
    for kind, v, toi, conservative in zip(collisions.kind, collisions.vertices, collisions.toi,
                                          collisions.conservative):
        if kind == clothcd.VERTEX_FACE:
            key = ("vf", int(v[0]), *sorted(int(x) for x in v[1:]))
        else:
            a, b = sorted([tuple(sorted((int(v[0]), int(v[1])))), tuple(sorted((int(v[2]), int(v[3]))))])
            key = ("ee", *a, *b)
        pairs[key] = (float(toi), bool(conservative))
    return pairs


def python_pairs(t0, t1, **settings):
    x0, x1, faces = clothcd.load_mesh_frames(str(t0), str(t1))
    detector = clothcd.CollisionDetector(faces, len(x0), **settings)
    return canonical_python(detector.detect(x0, x1)), faces


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("culling,cli_filter", [("filters", "combined"), ("none", "none"), ("network", "network")])
def test_generated_frames(cli, tmp_path, seed, culling, cli_filter):
    t0, t1 = crumpled_frames(tmp_path, seed)
    ours, faces = python_pairs(t0, t1, culling=culling)
    theirs = canonical_cli(cli_pairs(cli, t0, t1, tmp_path / "out.json", ["--filter", cli_filter]), faces)
    assert len(ours) > 0, "the frames were made to collide"
    assert ours == theirs


def test_generated_frames_with_thickness(cli, tmp_path):
    t0, t1 = crumpled_frames(tmp_path, 4)
    ours, faces = python_pairs(t0, t1, thickness=1e-3)
    theirs = canonical_cli(cli_pairs(cli, t0, t1, tmp_path / "out.json", ["--thickness", "0.001"]), faces)
    assert ours == theirs


SAMPLE = pathlib.Path(os.environ.get("CLOTHCD_SCALABLE_CCD_SAMPLE") or
                      pathlib.Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "scalable-ccd-sample")


@pytest.mark.skipif(not SAMPLE.is_dir(), reason="no ../shared/data/scalable-ccd-sample beside the repository")
def test_scalable_ccd_sample(cli, tmp_path):
    scene = SAMPLE / "cloth-funnel"
    ours, faces = python_pairs(scene / "t0.ply", scene / "t1.ply")
    theirs = canonical_cli(cli_pairs(cli, scene / "t0.ply", scene / "t1.ply", tmp_path / "out.json"), faces)
    assert ours == theirs
    truth = json.loads((scene / "truth.json").read_text())
    for v, f in truth["vf"]:
        assert ("vf", v, *sorted(int(x) for x in faces[f])) in ours
    for a, b in truth["ee"]:
        first, second = sorted([tuple(sorted(a)), tuple(sorted(b))])
        assert ("ee", *first, *second) in ours
