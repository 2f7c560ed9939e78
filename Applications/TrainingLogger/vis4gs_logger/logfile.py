# SPDX-License-Identifier: BSD-3-Clause
"""Reading a training log of either layout with h5py (format version 1: a group per
snapshot; 2: concatenated snapshot rows, written in SWMR mode), also while its writer runs.

    with open_log("run/training_log.h5") as f:
        for iteration in snapshot_iterations(f):
            ids = read_snapshot(f, iteration)["id"]
        loss = read_table(f, "metrics")["loss"]

A version 2 file whose writer runs (or was killed) refuses a plain open; open_log then opens
it in SWMR read mode. Only the rows the writer counted in /committed are returned."""

import h5py
import numpy as np

from .writer import COMMITTED

__all__ = ["open_log", "committed", "snapshot_iterations", "read_snapshot", "read_table"]

_INDEX = ("iteration", "start", "count", "sh_degree")


def open_log(path):
    """h5py.File of the log, read-only: plainly, else in SWMR read mode (a live or killed
    version 2 writer); OSError naming the file when neither opens."""
    try:
        return h5py.File(path, "r", locking=False)
    except OSError as plain:
        try:
            return h5py.File(path, "r", swmr=True, locking=False)
        except OSError:
            raise OSError(f"{path}: cannot open the training log ({plain})") from plain


def committed(f):
    """{table: rows} of a version 2 log's /committed; None for version 1 (every row counts)."""
    if int(f.attrs.get("format_version", 1)) < 2:
        return None
    return dict(zip(COMMITTED, (int(v) for v in f["committed"][:])))


def _cap(f, table, rows):
    counts = committed(f)
    return rows if counts is None else min(rows, counts[table])


def snapshot_iterations(f):
    """The logged snapshot iterations, increasing."""
    if committed(f) is None:
        return sorted(int(g.attrs.get("iteration", name)) for name, g in f["snapshots"].items())
    s = f["snapshots"]
    if "iteration" not in s:
        return []
    return [int(i) for i in s["iteration"][: _cap(f, "snapshots", s["iteration"].shape[0])]]


def read_snapshot(f, iteration):
    """{dataset name: numpy array} of the snapshot of ``iteration`` (KeyError when absent)."""
    if committed(f) is None:
        g = f[f"snapshots/{int(iteration):06d}"]
        return {name: d[()] for name, d in g.items()}
    s = f["snapshots"]
    iterations = snapshot_iterations(f)
    if int(iteration) not in iterations:
        raise KeyError(f"{f.filename}: no snapshot at iteration {iteration} (logged: {iterations})")
    row = iterations.index(int(iteration))
    start, count = int(s["start"][row]), int(s["count"][row])
    out = {name: d[start:start + count] for name, d in s.items() if name not in _INDEX}
    if "sh_degree" in s:  # the coefficients of the snapshot's degree
        out["sh"] = out["sh"][:, : (int(s["sh_degree"][row]) + 1) ** 2]
    return out


def read_table(f, group):
    """{column: numpy array} of /metrics, /metrics/test, /events or /lineage_breaks ({} when
    absent), cut to the rows every column holds (and the writer committed)."""
    if group not in f:
        return {}
    g = f[group]
    columns = {name: d for name, d in g.items() if isinstance(d, h5py.Dataset)}
    rows = _cap(f, group, min((d.shape[0] for d in columns.values()), default=0))
    return {name: np.asarray(d[:rows]) for name, d in columns.items()}
