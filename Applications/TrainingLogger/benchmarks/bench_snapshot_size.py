# SPDX-License-Identifier: BSD-3-Clause
"""Bytes per Gaussian and write speed of one snapshot for each snapshot option.

    /usr/bin/python3 bench_snapshot_size.py [--gaussians=500000] [--repeats=3] [--dir=/tmp]

A trained-like model of SH degree 3 (positions spread over a scene, log-scales around
-4, unit quaternions, opacity logits, SH DC of image colours and rest coefficients of a
trained model's magnitude, ~N(0, 0.05): random bits compress worse than trained values,
so the deflate figures are an upper bound on size). Each option writes the same model
``repeats`` times into a new log (the first snapshot's time is the median's too) through
TrainingLogWriter.write_snapshot, which flushes: the time is the whole write to the page
cache, wall and CPU. The straightforward implementation it is compared with is the
default (every coefficient, float32, uncompressed).

Then the size of a typical 30k-iteration run per option: snapshots every 500 iterations
(61), Gaussians growing linearly from 0.3M at 0 to 3M at 15,000 (densification ends) and
staying 3M, grad_accum/denom stored (+8 bytes): sum over snapshots of N x bytes/Gaussian.
"""

import os
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

import numpy as np  # noqa: E402

from vis4gs_logger import TrainingLogWriter  # noqa: E402
from bench_common import arg  # noqa: E402


OPTIONS = [
    ("default (SH 3, float32, no deflate)", {}),
    ("SH degree 2", {"snapshot_sh_degree": 2}),
    ("SH degree 1", {"snapshot_sh_degree": 1}),
    ("SH degree 0 (DC only)", {"snapshot_sh_degree": 0}),
    ("float16 colours", {"snapshot_sh_float16": True}),
    ("deflate 1", {"snapshot_deflate": 1}),
    ("deflate 4", {"snapshot_deflate": 4}),
    ("float16 colours + deflate 1", {"snapshot_sh_float16": True, "snapshot_deflate": 1}),
    ("SH degree 1 + float16 colours", {"snapshot_sh_degree": 1, "snapshot_sh_float16": True}),
]


def model(n, seed=0):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4)).astype(np.float32)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    sh = np.empty((n, 16, 3), np.float32)
    sh[:, 0] = (rng.random((n, 3)) - 0.5) / 0.28209479177387814
    sh[:, 1:] = rng.normal(0.0, 0.05, (n, 15, 3))
    return dict(ids=np.arange(n, dtype=np.int64),
                position=rng.normal(0.0, 3.0, (n, 3)).astype(np.float32),
                log_scale=rng.normal(-4.0, 0.8, (n, 3)).astype(np.float32),
                rotation=q, opacity_logit=rng.normal(0.0, 2.0, n).astype(np.float32), sh=sh,
                grad_accum=np.abs(rng.normal(0.0, 1e-4, n)).astype(np.float32),
                denom=rng.integers(0, 100, n).astype(np.float32))


def typical_run_bytes(bytes_per_gaussian):
    total = 0.0
    for it in range(0, 30001, 500):
        n = 3e6 if it >= 15000 else 0.3e6 + (3e6 - 0.3e6) * it / 15000
        total += n * bytes_per_gaussian
    return total


def main():
    n = arg("gaussians", 500000)
    repeats = arg("repeats", 3)
    folder = arg("dir", tempfile.gettempdir())
    m = model(n)
    with open("/proc/loadavg") as f:
        load = f.read().split()[:3]
    print(f"snapshot of {n} Gaussians (SH degree 3, with grad_accum/denom), {repeats} writes "
          f"each, load average {' '.join(load)}")
    print(f"{'option':40s} {'B/Gaussian':>10s} {'wall MB/s':>9s} {'CPU MB/s':>9s} "
          f"{'wall s':>7s} {'CPU s':>6s} {'30k run GB':>10s}")
    for name, options in OPTIONS:
        path = os.path.join(folder, f"vis4gs-bench-snapshot-{os.getpid()}.h5")
        walls, cpus = [], []
        w = TrainingLogWriter(path, **options)
        for r in range(repeats):
            t0, c0 = time.perf_counter(), time.process_time()
            w.write_snapshot(r, **m)
            walls.append(time.perf_counter() - t0)
            cpus.append(time.process_time() - c0)
        per = w.snapshot_bytes / repeats / n
        w.close()
        os.remove(path)
        wall, cpu = statistics.median(walls), statistics.median(cpus)
        raw = n * 252.0  # MB/s of the model as the trainer holds it (the default's bytes)
        print(f"{name:40s} {per:10.1f} {raw / wall / 1e6:9.0f} {raw / max(cpu, 1e-9) / 1e6:9.0f} "
              f"{wall:7.3f} {cpu:6.3f} {typical_run_bytes(per) / 1e9:10.1f}")


if __name__ == "__main__":
    main()
