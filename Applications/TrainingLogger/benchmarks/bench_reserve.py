# SPDX-License-Identifier: BSD-3-Clause
"""Cost of the writer's space reservations (a full disk must never reach HDF5; see
TrainingLogWriter): the same writes with them and without them, in one run.

    /usr/bin/python3 bench_reserve.py [--gaussians=200000] [--snapshots=6] [--steps=400]
                                      [--repeats=3] [--folder=DIR]

For each writer (swmr: format version 2; v1: swmr=False) it writes a log of ``snapshots``
snapshots of ``gaussians`` Gaussians (SH degree 3) with ``steps`` steps between two snapshots,
each step a metrics row, a few events and a flush (SWMR's live flushes are at most this
frequent), once with the reservations (as shipped) and once with ``_reserve`` replaced by
nothing (the straightforward writer), alternating, ``repeats`` times. Reports per variant the
best of the repeats: process CPU time and wall time of the whole log, and of its flushes and
snapshots alone, plus the file's size.
"""

import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

import numpy as np  # noqa: E402

from vis4gs_logger import writer as writer_module  # noqa: E402
from vis4gs_logger.writer import TrainingLogWriter  # noqa: E402
from bench_common import arg  # noqa: E402


def write_log(path, swmr, n, snapshots, steps, reserve):
    saved = TrainingLogWriter._reserve
    if not reserve:
        TrainingLogWriter._reserve = lambda self, nbytes: None
    rng = np.random.default_rng(0)
    arrays = dict(position=rng.normal(size=(n, 3)).astype(np.float32),
                  log_scale=rng.normal(size=(n, 3)).astype(np.float32),
                  rotation=rng.normal(size=(n, 4)).astype(np.float32),
                  opacity_logit=rng.normal(size=n).astype(np.float32),
                  sh=rng.normal(size=(n, 16, 3)).astype(np.float32))
    times = {"flush": [0.0, 0.0], "snapshot": [0.0, 0.0]}

    def timed(what, call, *args, **kwargs):
        c0, w0 = time.process_time(), time.perf_counter()
        call(*args, **kwargs)
        times[what][0] += time.process_time() - c0
        times[what][1] += time.perf_counter() - w0

    c0, w0 = time.process_time(), time.perf_counter()
    try:
        w = TrainingLogWriter(path, iterations=snapshots * steps, swmr=swmr)
        ids = np.arange(n, dtype=np.int64)
        for s in range(snapshots):
            timed("snapshot", w.write_snapshot, s * steps, ids, **arrays)
            for step in range(s * steps + 1, (s + 1) * steps):
                w.append_metrics(step, num_gaussians=n, loss=1.0 / step)
                w.append_events(step, writer_module.CLONE, ids[step % n: step % n + 4],
                                ids[step % n: step % n + 4] + n)
                timed("flush", w.flush)
        w.close()
    finally:
        TrainingLogWriter._reserve = saved
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    size = os.path.getsize(path)
    os.remove(path)
    return dict(cpu=cpu, wall=wall, flush=times["flush"], snapshot=times["snapshot"], size=size)


def main():
    n = arg("gaussians", 200000)
    snapshots = arg("snapshots", 6)
    steps = arg("steps", 400)
    repeats = arg("repeats", 3)
    folder = arg("folder", tempfile.gettempdir())
    print(f"{n} Gaussians, {snapshots} snapshots, {steps} steps (a flush each) between them, "
          f"best of {repeats}; folder {folder}; load {open('/proc/loadavg').read().split()[:3]}")
    for swmr in (True, False):
        best = {}
        for _ in range(repeats):
            for reserve in (True, False):
                r = write_log(os.path.join(folder, f"bench-reserve-{os.getpid()}.h5"), swmr, n,
                              snapshots, steps, reserve)
                if reserve not in best or r["cpu"] < best[reserve]["cpu"]:
                    best[reserve] = r
        for reserve in (True, False):
            r = best[reserve]
            flushes = snapshots * (steps - 1)
            print(f"{'swmr' if swmr else 'v1  '} {'reserved' if reserve else 'plain   '}: "
                  f"whole log {r['cpu']:.2f} s CPU, {r['wall']:.2f} s wall; "
                  f"flush {1e3 * r['flush'][0] / flushes:.3f} ms CPU "
                  f"({1e3 * r['flush'][1] / flushes:.3f} ms wall); snapshot "
                  f"{r['snapshot'][0] / snapshots:.3f} s CPU ({r['snapshot'][1] / snapshots:.3f} s "
                  f"wall); {r['size'] / 1e6:.1f} MB")


if __name__ == "__main__":
    main()
