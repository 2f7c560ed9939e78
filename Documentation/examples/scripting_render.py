"""Render a view off-screen to a PNG with the Python layer (no display needed).

  build/bin/vis4gs-python Documentation/examples/scripting_render.py [LOG_OR_PLY]
      [--cameras=DIR] [--camera=NAME_OR_INDEX] [--size=W,H] [--output=view.png]

Renders a training camera with the exact CPU rasteriser (what `vis4gs render` uses), once
for the whole scene and once for the Gaussians that most training views see, and writes both.
"""
import os
import sys

import vis4gs

args = [a for a in sys.argv[1:] if not a.startswith("--")]
options = dict(a[2:].split("=", 1) for a in sys.argv[1:] if a.startswith("--") and "=" in a)
path = args[0] if args else os.path.normpath(os.path.join(
    os.path.dirname(__file__), "..", "..", "Data", "Demo", "vis4gs-demo.h5"))
camera = options.get("camera", "0")
camera = int(camera) if camera.isdigit() else camera
size = tuple(int(v) for v in options["size"].split(",")) if "size" in options else None
output = options.get("output", "view.png")



def mean_rgb(image):
    return " ".join(f"{v:.4f}" for v in image.mean(axis=(0, 1), dtype=float))


scene = vis4gs.open(path, cameras=options.get("cameras"))
image = scene.render(output, camera=camera, size=size)
print(f"{output}: {image.shape[1]}x{image.shape[0]}, camera {camera} of "
      f"{len(scene.camera_names)}, mean RGB {mean_rgb(image)}")

coverage = scene.scores(["coverage"])["coverage"]
well_seen = scene.select(mask=coverage >= 0.5)
second = os.path.splitext(output)[0] + "-well-seen.png"
image = well_seen.render(second, camera=camera, size=size)
print(f"{second}: {len(well_seen)} of {len(scene)} Gaussians (View Coverage >= 0.5), "
      f"mean RGB {mean_rgb(image)}")
