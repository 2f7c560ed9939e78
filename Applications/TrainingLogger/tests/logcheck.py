# SPDX-License-Identifier: BSD-3-Clause
"""Independent checks of a written log: the format read back with h5py, and (when the
build provides it) the same log read by the C++ reader through TrainingLogDump."""

import json
import os
import subprocess

import numpy as np

from vis4gs_logger.logfile import committed, open_log, read_snapshot, read_table, snapshot_iterations


def read_events(path):
    with open_log(path) as f:
        e = read_table(f, "events")
        return (e["iteration"], e["kind"], e["parent"], e["child"])


def check_format(path):
    """Asserts the contract of DESIGN §3 on the file (names, types, shapes, order), in
    either layout (format version 2: packed snapshots and /committed; 1: a group each)."""
    with open_log(path) as f:
        assert f.attrs["format"] == "vis4gs-training-log"
        version = int(f.attrs["format_version"])
        assert version in (1, 2)
        for key in ("producer", "scene", "sh_degree", "iterations"):
            assert key in f.attrs
        m = f["metrics"]
        assert m["iteration"].dtype == np.int32 and m["num_gaussians"].dtype == np.int64
        for c in ("loss", "l1", "psnr", "ssim", "lpips", "elapsed_s"):
            assert m[c].dtype == np.float64 and m[c].shape == m["iteration"].shape
        e = f["events"]
        assert e["iteration"].dtype == np.int32 and e["kind"].dtype == np.uint8
        assert e["parent"].dtype == np.int64 and e["child"].dtype == np.int64
        if version == 2:
            counts = committed(f)
            # All committed when closed; a killed writer may leave uncounted rows after them.
            assert counts["metrics"] <= m["iteration"].shape[0]
            assert counts["events"] <= e["iteration"].shape[0]
            assert counts["snapshots"] == len(snapshot_iterations(f))
        last = -1
        for iteration in snapshot_iterations(f):
            assert iteration > last
            last = iteration
            g = read_snapshot(f, iteration)
            ids = g["id"]
            n = len(ids)
            assert ids.dtype == np.int64 and np.all(np.diff(ids) > 0)
            assert g["position"].shape == (n, 3) and g["position"].dtype == np.float32
            assert g["log_scale"].shape == (n, 3)
            assert g["rotation"].shape == (n, 4)
            assert g["opacity_logit"].shape == (n,)
            assert g["sh"].ndim == 3 and g["sh"].shape[0] == n and g["sh"].shape[2] == 3
        datasets = (f[f"snapshots/{name}/position"] for name in f["snapshots"]) if version == 1 \
            else ([f["snapshots/position"]] if "position" in f["snapshots"] else [])
        for d in datasets:
            # Chunked; uncompressed by default (snapshot_deflate=0), gzip when asked.
            assert d.chunks is not None
            assert d.compression in (None, "gzip")
        assert e["parent"].compression == "gzip"


def snapshot_names(path):
    """The snapshot iterations of the log at path."""
    with open_log(path) as f:
        return snapshot_iterations(f)


def dump(path, *args):
    """Runs the C++ reader on the log (TrainingLogDump); None when it is not built."""
    exe = os.environ.get("VIS4GS_TRAINING_LOG_DUMP")
    if not exe:
        return None
    out = subprocess.run([exe, path] + list(args), check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def require_dump():
    """Under CTest the C++ reader is always given; standalone pytest may lack it."""
    return os.environ.get("VIS4GS_TRAINING_LOG_DUMP") is not None


def replay_genealogy(events, n0):
    """Replays events: returns the set of alive ids, asserting every rule of DESIGN §3."""
    it, kind, parent, child = events
    alive = set(range(n0))
    ended = {}
    next_id = n0
    for i in range(len(it)):
        p = int(parent[i])
        if kind[i] in (1, 2):
            assert int(child[i]) == next_id, "new ids must be the next unused id"
            next_id += 1
            assert p in alive or (kind[i] == 2 and ended.get(p) == ("split", int(it[i])))
            alive.add(int(child[i]))
            if kind[i] == 2:
                alive.discard(p)
                ended[p] = ("split", int(it[i]))
        else:
            assert kind[i] == 3 and int(child[i]) == -1
            assert p in alive, f"prune of id {p} which is not alive"
            alive.discard(p)
            ended[p] = ("prune", int(it[i]))
        if i > 0:
            assert it[i] >= it[i - 1]
    return alive, next_id
