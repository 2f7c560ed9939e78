# SPDX-License-Identifier: BSD-3-Clause
"""Independent numpy evaluation of the rules TestSelectionRule.MatchesNumpy writes.

Reads the arrays the test wrote to FOLDER, evaluates each rule with hand-written numpy
expressions (no parser: the rule texts are only checked to be the ones expected), and writes
one mask per rule (mask<k>.u8). Definitions as in Core/Selection/SelectionRule.h, computed in
float64 from the raw float32 parameters.
"""
import sys

import numpy as np

folder = sys.argv[1]
pos = np.fromfile(f"{folder}/positions.f32", dtype=np.float32).reshape(-1, 3).astype(np.float64)
log_scales = np.fromfile(f"{folder}/log_scales.f32", dtype=np.float32).reshape(-1, 3).astype(np.float64)
logits = np.fromfile(f"{folder}/opacity_logits.f32", dtype=np.float32).astype(np.float64)
coverage = np.fromfile(f"{folder}/coverage.f64", dtype=np.float64)
blur = np.fromfile(f"{folder}/blur.f64", dtype=np.float64)
needle_score = np.fromfile(f"{folder}/needle_score.f64", dtype=np.float64)
lines = open(f"{folder}/rules.txt").read().splitlines()
views_used = int(lines[-1].split()[1])
rules = lines[:-1]
n = len(logits)

with np.errstate(all="ignore"):
    opacity = 1.0 / (1.0 + np.exp(-logits))
    scale = np.exp(log_scales.max(axis=1))
    volume = 4.0 / 3.0 * np.pi * np.exp(log_scales[:, 0] + log_scales[:, 1] + log_scales[:, 2])
    views = np.round(coverage * views_used)
    # Needle shape s = (3 - exp(H)) / 2 with q = softmax(2 log-scales), 0 log 0 = 0.
    z = 2.0 * log_scales
    z = z - z.max(axis=1, keepdims=True)
    q = np.exp(z) / np.exp(z).sum(axis=1, keepdims=True)
    h = -np.where(q > 0, q * np.log(np.where(q > 0, q, 1.0)), 0.0).sum(axis=1)
    needle = (3.0 - np.exp(h)) / 2.0


def top(v, p, largest=True):
    finite = ~np.isnan(v)  # +-inf rank, NaN does not
    values = np.sort(v[finite])
    k = int(np.ceil(p * finite.sum() / 100.0))
    if k < 1:
        return np.zeros(n, dtype=bool)
    if largest:
        return finite & (v >= values[::-1][k - 1])
    return finite & (v <= values[k - 1])


def isolated(r):
    finite = np.isfinite(pos).all(axis=1)
    out = np.zeros(n, dtype=bool)
    p = pos[finite]
    idx = np.nonzero(finite)[0]
    for row, i in enumerate(idx):
        d = p - p[row]
        d2 = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] + d[:, 2] * d[:, 2]
        d2[row] = np.inf
        out[i] = not (d2 <= r * r).any()
    return out


expected = {
    "coverage<=0.1 and opacity>=0.5": lambda: (coverage <= 0.1) & (opacity >= 0.5),
    "blur top 5%": lambda: top(blur, 5),
    "needle>=0.8": lambda: needle >= 0.8,
    "isolated r=0.3": lambda: isolated(0.3),
    "views<=2 or not (scale<0.1 and volume>1e-05)": lambda: (views <= 2)
    | ~((scale < 0.1) & (volume > 1e-05)),
    "needle_score top 12.5% and blur bottom 30%": lambda: top(needle_score, 12.5)
    & top(blur, 30, largest=False),
    "not isolated r=0.5 and opacity<0.2 or needle<0.1": lambda: (~isolated(0.5) & (opacity < 0.2))
    | (needle < 0.1),
}
for k, rule in enumerate(rules):
    if rule not in expected:
        sys.exit(f"selection_rule_numpy.py: no numpy evaluation for rule '{rule}'")
    with np.errstate(all="ignore"):
        mask = expected[rule]()
    mask.astype(np.uint8).tofile(f"{folder}/mask{k}.u8")
