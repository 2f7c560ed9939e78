"""Issue 15: a generated INRIA PLY holding the special values the reference computation has an
answer for (opacity logits +inf and -inf, log-scales of -inf on one or all axes, zero
quaternions, SH degree 2) rendered by vtkGaussianRasterizer from several arbitrary cameras must
match the independent numpy float64 reference (Testing/Python/reference_render.py, which reads
the file itself) at >= 50 dB PSNR per image, in float and in double arithmetic. Needs no shared
data. Exits non-zero and prints FAILED on any miss."""
import os
import sys
import tempfile

import numpy as np

import reference_check as rc
import reference_render as rr

rng = np.random.default_rng(15)
n = 400
means = rng.normal(0, 0.6, (n, 3))
log_scales = np.log(rng.uniform(0.03, 0.25, (n, 3)))
rotations = rng.normal(0, 1, (n, 4))
logits = rng.uniform(-2, 3, n)
sh = np.concatenate([rng.uniform(-1.2, 1.2, (n, 1, 3)), rng.normal(0, 0.3, (n, 8, 3))], 1)
specials = rng.permutation(n)
plus_inf, minus_inf, flat, point, zero_q = np.split(specials[:200], [60, 90, 130, 160])
logits[plus_inf] = np.inf
logits[minus_inf] = -np.inf
log_scales[flat, rng.integers(0, 3, len(flat))] = -np.inf
log_scales[point] = -np.inf
rotations[zero_q] = 0.0
# A few of the +inf ones are also points and unrotated: the combinations must hold too.
log_scales[plus_inf[:8]] = -np.inf
rotations[plus_inf[8:16]] = 0.0

failures = []
with tempfile.TemporaryDirectory() as tmp:
    path = os.path.join(tmp, "specials.ply")
    rr.write_inria_ply(path, means, log_scales, rotations, logits, sh)
    scene = rr.read_inria_ply(path)
    if not (np.sum(scene.opacities == 1.0) >= 60 and np.sum(scene.opacities == 0.0) == 30 and
            np.sum(np.isinf(scene.scales) | (scene.scales == 0)) > 0):
        print("FAILED: the generated file does not hold the special values")
        sys.exit(1)
    cameras = rr.orbit_cameras(scene.means, count=4, distance=2.2)
    for width, height in ((160, 120), (200, 150)):
        for row in rc.compare_file(path, scene, cameras, width, height,
                                   label=f"specials {width}x{height}", report=rc.print_row):
            if row[2] < rc.MIN_PSNR or row[3] < rc.MIN_PSNR or row[5] < 0.05:
                failures.append(row)
for row in failures:
    print(f"FAILED: {row[0]} camera {row[1]}: PSNR float {row[2]:.1f} dB, double {row[3]:.1f} dB"
          f" (>= {rc.MIN_PSNR} dB needed), {100 * row[5]:.0f}% covered")
sys.exit(1 if failures else 0)
