# SPDX-License-Identifier: BSD-3-Clause
"""Logging overhead of vis4gs_logger on a CPU torch training step of 100k Gaussians.

    /usr/bin/python3 bench_overhead.py [--gaussians=100000] [--iterations=300]

The mock step is the structure of a 3DGS iteration on the CPU, with autograd: activate
scales/rotations/opacities, build 3D covariances, project the means with a pinhole camera,
form the EWA 2D covariances and their inverses, evaluate SH (degree 1) colours, splat each
Gaussian's weighted colour into the pixel under its centre (index_add into 128x128), L1 loss
against a target, backward, add_densification_stats with the 2D-mean gradient, Adam step,
and densify_and_prune (the mock GaussianModel of the tests, i.e. the original trainer's
tensor operations) every 100 iterations. It has no tile rasteriser, so it is cheaper than a
real CPU iteration: the overhead measured against it is an upper bound.

Runs the same seeded loop without and with the logger (metrics every iteration, id hooks,
snapshot every DEFAULT_SNAPSHOT_INTERVAL iterations) and reports both the A/B difference and
the time spent inside the logger, plus the cost of one snapshot amortised over the interval.
"""

import math
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))

import torch  # noqa: E402

from mock_3dgs import GaussianModel, build_rotation  # noqa: E402
from vis4gs_logger import TrainingLogger, track_3dgs  # noqa: E402
from vis4gs_logger.logger import DEFAULT_SNAPSHOT_INTERVAL  # noqa: E402
from bench_common import arg  # noqa: E402


def train(n, iterations, logger_path=None):
    torch.manual_seed(0)
    g = GaussianModel(3)
    g.create_random(n, seed=1)
    with torch.no_grad():
        g._xyz[:, 2] += 6.0  # in front of the camera
        g._features_rest[:] = 0.01 * torch.randn_like(g._features_rest)
    H = W = 128
    target = torch.rand(H * W, 3)
    logger = None
    if logger_path:
        logger = TrainingLogger(logger_path, scene="bench", sh_degree=3, iterations=iterations)
        track_3dgs(g, logger)
    f = 100.0
    t0 = time.perf_counter()
    for it in range(1, iterations + 1):
        xyz = g._xyz
        scales = g.get_scaling
        R = build_rotation(g._rotation)
        M = R * scales[:, None, :]
        cov3d = M @ M.transpose(1, 2)
        z = xyz[:, 2].clamp_min(0.2)
        u = f * xyz[:, 0] / z + W / 2
        v = f * xyz[:, 1] / z + H / 2
        J = torch.zeros(xyz.shape[0], 2, 3)
        J[:, 0, 0] = f / z
        J[:, 1, 1] = f / z
        J[:, 0, 2] = -f * xyz[:, 0] / (z * z)
        J[:, 1, 2] = -f * xyz[:, 1] / (z * z)
        cov2d = J @ cov3d @ J.transpose(1, 2) + 0.3 * torch.eye(2)
        conic = torch.linalg.inv(cov2d)
        means2d = torch.stack([u, v], dim=-1)
        means2d.retain_grad()
        px = means2d.detach().round().clamp(0, W - 1)
        d = means2d - px
        power = -0.5 * (d[:, None, :] @ conic @ d[:, :, None]).reshape(-1)
        alpha = (g.get_opacity.reshape(-1) * torch.exp(power)).clamp(max=0.99)
        dirs = torch.nn.functional.normalize(xyz, dim=-1)
        sh = torch.cat([g._features_dc, g._features_rest], dim=1)
        color = 0.28209479 * sh[:, 0] - 0.48860251 * dirs[:, 1:2] * sh[:, 1] \
            + 0.48860251 * dirs[:, 2:3] * sh[:, 2] - 0.48860251 * dirs[:, 0:1] * sh[:, 3] + 0.5
        index = (px[:, 1] * W + px[:, 0]).long()
        image = torch.zeros(H * W, 3).index_add(0, index, alpha[:, None] * color)
        l1 = (image - target).abs().mean()
        loss = l1
        loss.backward()
        if logger is not None:
            logger.log_metrics(it, loss=loss.item(), l1=l1.item())
        else:
            loss.item()  # the trainer reads the loss anyway (progress bar)
        with torch.no_grad():
            visible = torch.ones(xyz.shape[0], dtype=torch.bool)
            g.add_densification_stats(means2d, visible)
            densified = it % 100 == 0
            if densified:
                g.densify_and_prune(0.0002, 0.005, 1.0, None)
        if not densified:  # as in the trainer, no optimizer step right after densification
            g.optimizer.step()
        g.optimizer.zero_grad(set_to_none=True)
        if logger is not None:
            logger.step(it)
    total = time.perf_counter() - t0
    spent = 0.0
    if logger is not None:
        spent = logger.time_spent_s
        logger.close()
    return total, spent, g.get_xyz.shape[0]


def main():
    n = arg("gaussians", 100000)
    iterations = arg("iterations", 300)
    torch.set_num_threads(2)
    tmp = tempfile.mkdtemp()
    path = os.path.join(tmp, "bench_log.h5")
    base, _, n_end = train(n, iterations)
    logged, spent, _ = train(n, iterations, path)
    # The iteration time of the logged run without the logger's own time: on a shared machine
    # the two runs see different loads, so the A/B difference alone is not reliable.
    per_it = (logged - spent) / iterations
    # One snapshot of the final model, timed on its own (amortised over the default interval).
    logger = TrainingLogger(os.path.join(tmp, "snap.h5"))
    g = GaussianModel(3)
    g.create_random(n_end, seed=2)
    tracker = track_3dgs(g, logger, snapshot_initial=False)
    t0 = time.perf_counter()
    tracker.write_snapshot(1)
    snap = time.perf_counter() - t0
    logger.close()
    size_mb = os.path.getsize(os.path.join(tmp, "snap.h5")) / 2 ** 20
    # Time inside the logger excluding the snapshots it wrote during the run.
    snaps_in_run = 1 + iterations // DEFAULT_SNAPSHOT_INTERVAL
    per_it_logging = max(0.0, spent - snaps_in_run * snap) / iterations
    overhead = (per_it_logging + snap / DEFAULT_SNAPSHOT_INTERVAL) / per_it
    print(f"gaussians {n} -> {n_end}, {iterations} iterations, torch threads 2")
    print(f"without logger: {base:.2f} s ({1000 * base / iterations:.1f} ms/iteration)")
    print(f"logged run without the logger's time: {1000 * per_it:.1f} ms/iteration")
    print(f"with logger:    {logged:.2f} s (A/B difference {100 * (logged - base) / base:+.2f}%, "
          f"includes {snaps_in_run} snapshot(s))")
    print(f"inside the logger: {spent:.3f} s; per iteration without snapshots "
          f"{1000 * per_it_logging:.3f} ms")
    print(f"one snapshot of {n_end} Gaussians (SH degree 3): {snap:.3f} s, {size_mb:.1f} MiB")
    print(f"overhead at the default interval ({DEFAULT_SNAPSHOT_INTERVAL}): "
          f"{100 * overhead:.2f}% of an iteration")


if __name__ == "__main__":
    main()
