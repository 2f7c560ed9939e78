"""Scores of a training log (or a scene with cameras) with the Python layer, in a few lines.

  build/bin/vis4gs-python Documentation/examples/scripting_scores.py [LOG_OR_PLY]
      [--cameras=DIR] [--output=DIR]

Computes View Coverage, Blur and Needle (only those: the needle shape is not asked for),
prints the most suspicious Gaussians as `vis4gs analyze` lists them, and writes the scores
as CSV and the weakly covered Gaussians as a PLY.
"""
import os
import sys

import numpy as np

import vis4gs

args = [a for a in sys.argv[1:] if not a.startswith("--")]
options = dict(a[2:].split("=", 1) for a in sys.argv[1:] if a.startswith("--") and "=" in a)
path = args[0] if args else os.path.normpath(os.path.join(
    os.path.dirname(__file__), "..", "..", "Data", "Demo", "vis4gs-demo.h5"))
output = options.get("output", "scripting-scores")
os.makedirs(output, exist_ok=True)

scene = vis4gs.open(path, cameras=options.get("cameras"))
scores = scene.scores(["coverage", "blur", "needle"])
print(scene)
for name, values in scores.items():
    # Lowest coverage first (floaters), highest blur and needle first; ties by row.
    order = np.argsort(values if name == "coverage" else -values, kind="stable")[:3]
    print(f"top 3 by {vis4gs.SCORES[name]}:",
          ", ".join(f"{scene.ids[i]} ({values[i]:.6g})" for i in order))

weak = scene.select(mask=(scores["coverage"] < 0.1) & (scene["Opacity"] >= 0.1))
print(f"{len(weak)} visible Gaussians seen by fewer than 10% of the training views")
scene.to_csv(os.path.join(output, "scores.csv"))
weak.save(os.path.join(output, "weakly-covered.ply"))
print(f"wrote {output}/scores.csv and {output}/weakly-covered.ply")
