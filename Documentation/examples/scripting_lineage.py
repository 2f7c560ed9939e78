"""The case study with the Python layer: the floater of the last snapshot and its ancestors.

  build/bin/vis4gs-python Documentation/examples/scripting_lineage.py [LOG.h5]

The same steps as case_study.py (the plain VTK pipeline) in a few lines: View Coverage of the
last snapshot, the visible Gaussian that the fewest training views see, and its trace to the
root with each ancestor's coverage at the snapshot nearest its birth.
"""
import os
import sys

import numpy as np

import vis4gs

log = sys.argv[1] if len(sys.argv) > 1 else os.path.normpath(os.path.join(
    os.path.dirname(__file__), "..", "..", "Data", "Demo", "vis4gs-demo.h5"))
scene = vis4gs.open(log)
coverage = scene.scores(["coverage"])["coverage"]
candidates = np.flatnonzero((scene["Opacity"] >= 0.1) & (coverage > 0))
floater = scene.ids[candidates[np.argmin(coverage[candidates])]]
print(f"floater at iteration {scene.iteration}: Gaussian {floater}, "
      f"View Coverage {coverage[scene.ids == floater][0]:g}")
for step in scene.lineage(floater, score="coverage"):
    at = "in no snapshot" if step.snapshot is None else f"{step.value:.3f} at {step.snapshot}"
    died = "alive" if step.died is None else f"died {step.died}"
    print(f"  {step.gaussian_id:>6}  born {step.born:>4} ({step.kind}), {died}; coverage {at}")
