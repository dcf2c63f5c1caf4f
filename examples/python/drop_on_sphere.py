"""Drops the paper's cloth A on a sphere with clothcd's simulation and writes a picture of the last frame.

    python examples/python/drop_on_sphere.py [OUT.png]     (after `pip install .`)
"""

import argparse

import numpy as np

import clothcd

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("out", nargs="?", default="drop_on_sphere.png", metavar="OUT.png",
                    help="the picture of the last frame (default: %(default)s)")
out = parser.parse_args().out
sphere = clothcd.make_uv_sphere(0.5, 32, 16)
cloth_vertices, cloth_faces = clothcd.make_paper_cloth("A", 1.6)
cloth_vertices = cloth_vertices + [0.0, 0.7, 0.0]  # above the sphere

frames = clothcd.simulate((cloth_vertices, cloth_faces), [sphere], steps=200, frames_every=50)
last = frames[-1]
print(f"clothcd {clothcd.__version__}: {len(frames)} frames; lowest cloth point y = {last[:, 1].min():+.3f}; "
      f"closest to the sphere's centre {np.linalg.norm(last, axis=1).min():.3f} (radius 0.5)")
clothcd.render_png(out, [(sphere[0], sphere[1], (0.55, 0.6, 0.7)), (last, cloth_faces, (0.85, 0.35, 0.3))])
print(f"wrote {out}")
