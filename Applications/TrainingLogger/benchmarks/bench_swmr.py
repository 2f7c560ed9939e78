# SPDX-License-Identifier: BSD-3-Clause
"""What SWMR mode (format version 2, issue 32) costs the writer: per-step overhead and
snapshot write speed, against the format version 1 writer, in one run.

    /usr/bin/python3 bench_swmr.py [--steps=2000] [--gaussians=500000] [--snapshots=4] [--dir=/tmp]

Steps: each step appends one metrics row and 8 clone events, as a training step does; the
writers compared: version 1 as before issue 32 (rows buffered, flushed at snapshots only:
the straightforward implementation), version 1 flushed every step, and version 2 in SWMR
mode flushed every step (what `step()` with live_flush_s=0 does; the default 0.5 s flushes
far less often) and not flushed per step. Microseconds per step, wall and CPU.

Snapshots: ``snapshots`` snapshots of ``gaussians`` Gaussians at SH degree 3 with
grad_accum/denom (260 bytes each) per layout, each write_snapshot (arrays, index, two
flushes for version 2) timed to the page cache: MB/s, wall and CPU, median over snapshots.
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


def steps_cost(path, steps, swmr, flush_each):
    w = TrainingLogWriter(path, sh_degree=0, swmr=swmr, flush_every_s=None)
    parents = np.arange(8, dtype=np.int64)
    wall0, cpu0 = time.perf_counter(), time.process_time()
    for s in range(steps):
        w.append_metrics(s, num_gaussians=1000 + s, loss=1.0 / (s + 1), l1=0.5)
        w.append_events(s, 1, parents, 10000 + 8 * s + parents)
        if flush_each:
            w.flush()
    w.close()
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    size = os.path.getsize(path)
    os.remove(path)
    return 1e6 * wall / steps, 1e6 * cpu / steps, size


def snapshot_speed(path, n, count, swmr):
    rng = np.random.default_rng(1)
    arrays = dict(position=rng.normal(size=(n, 3)).astype(np.float32),
                  log_scale=rng.normal(-4, 1, size=(n, 3)).astype(np.float32),
                  rotation=rng.normal(size=(n, 4)).astype(np.float32),
                  opacity_logit=rng.normal(size=n).astype(np.float32),
                  sh=rng.normal(0, 0.05, size=(n, 16, 3)).astype(np.float32),
                  grad_accum=rng.random(n).astype(np.float32),
                  denom=rng.integers(0, 50, n).astype(np.float32))
    ids = np.arange(n, dtype=np.int64)
    nbytes = ids.nbytes + sum(a.nbytes for a in arrays.values())
    w = TrainingLogWriter(path, sh_degree=3, swmr=swmr)
    walls, cpus = [], []
    for s in range(count):
        wall0, cpu0 = time.perf_counter(), time.process_time()
        w.write_snapshot(500 * s, ids, **arrays)
        walls.append(time.perf_counter() - wall0)
        cpus.append(time.process_time() - cpu0)
    w.close()
    size = os.path.getsize(path)
    os.remove(path)
    return nbytes / 1e6 / statistics.median(walls), nbytes / 1e6 / statistics.median(cpus), \
        size / (count * n)


def main():
    steps = arg("steps", 2000)
    n = arg("gaussians", 500000)
    count = arg("snapshots", 4)
    folder = tempfile.mkdtemp(dir=arg("dir", "/tmp"))
    print(f"load {open('/proc/loadavg').read().split()[:3]}")
    print(f"per step ({steps} steps: 1 metrics row + 8 events each), microseconds:")
    for label, swmr, flush in (("version 1, flushed at snapshots only (before)", False, False),
                               ("version 1, flushed every step", False, True),
                               ("version 2 SWMR, not flushed per step", True, False),
                               ("version 2 SWMR, flushed every step", True, True)):
        wall, cpu, size = steps_cost(os.path.join(folder, "steps.h5"), steps, swmr, flush)
        print(f"  {label:48s} wall {wall:8.1f}  cpu {cpu:8.1f}  file {size / 1e6:.2f} MB")
    print(f"snapshot write ({count} x {n} Gaussians, SH 3 + statistics), median:")
    for label, swmr in (("version 1 (a group per snapshot)", False),
                        ("version 2 SWMR (packed rows)", True)):
        wall, cpu, per = snapshot_speed(os.path.join(folder, "snap.h5"), n, count, swmr)
        print(f"  {label:36s} {wall:7.0f} MB/s wall  {cpu:7.0f} MB/s cpu  "
              f"{per:.1f} file bytes per Gaussian")
    os.rmdir(folder)


if __name__ == "__main__":
    main()
