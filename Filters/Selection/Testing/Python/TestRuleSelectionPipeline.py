"""Guided selection from Python (issue 20): the training-log reader's last snapshot through the
score filter (View Coverage) into vtkGaussianRuleSelectionFilter. The selected ids equal an
independent numpy evaluation of the same rules over the same arrays, Remove gives the cleaned
scene (the others, every array kept), the rule combines with a current selection, and a bad
rule is an error naming its token."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
scores = vis4gs.vtkGaussianArtifactScoreFilter()
scores.SetInputConnection(reader.GetOutputPort(0))
scores.SetCamerasConnection(reader.GetOutputPort(1))
scores.SetComputeBlurScore(False)
scores.SetComputeNeedleScore(False)
scores.Update()
views = scores.GetNumberOfViewsUsed()
pd = scores.GetOutput().GetPointData()
ids = vtk_to_numpy(pd.GetArray("GaussianId")).astype(np.int64)
coverage = vtk_to_numpy(pd.GetArray("ViewCoverage")).astype(np.float64)
opacity = 1.0 / (1.0 + np.exp(-vtk_to_numpy(pd.GetArray("OpacityLogit")).astype(np.float64)))
log_scale = vtk_to_numpy(pd.GetArray("LogScale")).astype(np.float64)
q = np.exp(2 * log_scale - (2 * log_scale).max(axis=1, keepdims=True))
q /= q.sum(axis=1, keepdims=True)
entropy = -np.where(q > 0, q * np.log(np.where(q > 0, q, 1.0)), 0.0).sum(axis=1)
needle = (3.0 - np.exp(entropy)) / 2.0

rule = vis4gs.vtkGaussianRuleSelectionFilter()
rule.SetInputConnection(scores.GetOutputPort())
rule.SetNumberOfViews(views)
cases = {
    "views<=3": np.round(coverage * views) <= 3,
    "coverage<0.2 and opacity>=0.5": (coverage < 0.2) & (opacity >= 0.5),
    "needle>=0.8 or not opacity>0.05": (needle >= 0.8) | ~(opacity > 0.05),
}
for text, expected in cases.items():
    rule.SetRule(text)
    rule.Update()
    selected = vtk_to_numpy(rule.GetSelectedIds()).astype(np.int64)
    check(np.array_equal(selected, np.sort(ids[expected])),
          f"'{text}': {selected.size} ids, numpy {expected.sum()}")
    check(0 < selected.size < ids.size, f"'{text}' selects some but not all")

# Remove: the cleaned scene, with the scores of the others.
rule.SetRule("views<=3")
rule.SetOutputMode(rule.Remove)
rule.Update()
cleaned = rule.GetOutput()
kept = ~(np.round(coverage * views) <= 3)
check(cleaned.GetNumberOfPoints() == kept.sum(), f"cleaned scene: {kept.sum()} Gaussians")
check(np.array_equal(vtk_to_numpy(cleaned.GetPointData().GetArray("GaussianId")), ids[kept]),
      "cleaned scene holds the others, in order")
check(np.array_equal(vtk_to_numpy(cleaned.GetPointData().GetArray("ViewCoverage")),
                     coverage[kept]), "with their scores")
check(cleaned.GetFieldData().GetAbstractArray("SelectionRule").GetValue(0) == "views<=3",
      "the rule travels in the field data")

# Intersect with a current selection (the first 1000 ids).
rule.SetOutputMode(rule.Mark)
rule.SetCurrentIds(numpy_to_vtkIdTypeArray(ids[:1000].copy(), deep=1))
rule.SetCombineMode(rule.Intersect)
rule.Update()
selected = vtk_to_numpy(rule.GetSelectedIds()).astype(np.int64)
check(np.array_equal(selected, np.sort(ids[:1000][(np.round(coverage * views) <= 3)[:1000]])),
      "intersect with a current selection")

# A bad rule: an error naming the token, no output.
rule.GlobalWarningDisplayOff()
rule.SetRule("opacity>=0.5 and covrage<0.1")
rule.Update()
message = rule.GetLastRuleError()
check("found 'covrage' (column 18)" in message, "bad rule: " + message)
check(rule.GetOutput().GetNumberOfPoints() == 0, "no output for a bad rule")

sys.exit(1 if failures else 0)
