# SPDX-License-Identifier: BSD-3-Clause
"""Reading a log while a real writer process writes it (format version 2, SWMR mode), and
SIGKILL-ing that writer, in the middle of a snapshot too (issue 32 item 6). Readers: the
Python layer (vis4gs_logger.open_log and friends) and the C++ reader (TrainingLogDump, once
per read and with --refresh, as `vis4gs view --follow` refreshes)."""

import json
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from logcheck import check_format, dump, require_dump
from vis4gs_logger import open_log, read_snapshot, read_table, snapshot_iterations

HERE = os.path.dirname(os.path.abspath(__file__))

# Step s: metrics row s, one clone event (parent s, child 1000000 + s), a flush; every 4th
# step a snapshot of 20000 + 100 s Gaussians whose positions all equal s. "done s" after
# each step; with PAUSE, "inside" in the middle of snapshot 28, then it sleeps there.
WRITER = textwrap.dedent("""
    import sys, time, numpy as np
    sys.path.insert(0, {pkg!r})
    import vis4gs_logger.writer as wm
    from vis4gs_logger import TrainingLogWriter
    STEPS, PAUSE = {steps!r}, {pause!r}
    w = TrainingLogWriter({path!r}, sh_degree=1, chunk_rows=4096)
    if PAUSE:
        fit = wm.TrainingLogWriter._fit
        def pausing_fit(dataset, value, state={{"n": 0}}):
            state["n"] += w.last_snapshot_iteration == 24  # writing snapshot 28
            if state["n"] == 3:  # id and two arrays written, the rest not
                print("inside", flush=True)
                time.sleep(30)
            return fit(dataset, value)
        wm.TrainingLogWriter._fit = staticmethod(pausing_fit)
    for s in range(STEPS):
        w.append_metrics(s, num_gaussians=s, loss=1.0 / (s + 1))
        w.append_events(s, 1, [s], [1000000 + s])
        if s % 4 == 0:
            n = 20000 + 100 * s
            w.write_snapshot(s, np.arange(n), np.full((n, 3), s, np.float32), np.zeros((n, 3)),
                             np.ones((n, 4)), np.zeros(n), np.full((n, 4, 3), s))
        else:
            w.flush()
        print("done", s, flush=True)
        time.sleep(0.01)
    w.close()
""")


def start_writer(path, steps, pause=False):
    code = WRITER.format(pkg=os.path.dirname(HERE), path=path, steps=steps, pause=pause)
    return subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)


def check_python_view(path):
    """What the Python layer reads now: consistent, complete rows. Returns the counts."""
    with open_log(path) as f:
        its = snapshot_iterations(f)
        assert its == list(range(0, 4 * len(its), 4))
        for s in its[-2:]:
            snap = read_snapshot(f, s)
            assert len(snap["id"]) == 20000 + 100 * s
            assert np.all(snap["position"] == s) and np.all(snap["sh"] == s)
        m = read_table(f, "metrics")["iteration"]
        assert np.array_equal(m, np.arange(len(m)))
        e = read_table(f, "events")
        assert np.array_equal(e["child"], 1000000 + np.arange(len(e["child"])))
        return len(its), len(m), len(e["child"])


def test_readers_follow_a_live_writer(tmp_path):
    """Every read while the writer runs succeeds and sees at least what the previous saw."""
    path = str(tmp_path / "live.h5")
    proc = start_writer(path, steps=120)
    assert proc.stdout.readline().startswith("done")
    last_py, last_cpp, reads, first_py = (0, 0, 0), (0, 0), 0, None
    follower = None
    if require_dump():
        # One C++ reader that stays open and refreshes (the viewer's --follow).
        follower = subprocess.Popen([os.environ["VIS4GS_TRAINING_LOG_DUMP"], path,
                                     "--refresh=40"], stdout=subprocess.PIPE, text=True)
    while proc.poll() is None:
        counts = check_python_view(path)
        assert all(a >= b for a, b in zip(counts, last_py)), (counts, last_py)
        last_py = counts
        first_py = first_py or counts
        info = dump(path)  # the C++ reader, a fresh open each time
        if info is not None:
            assert info["format_version"] == 2
            assert info["snapshots"] == list(range(0, 4 * len(info["snapshots"]), 4))
            assert info["counts"] == [20000 + 100 * s for s in info["snapshots"]]
            now = (len(info["snapshots"]), info["metrics"])
            assert now[0] >= last_cpp[0] and now[1] >= last_cpp[1]
            last_cpp = now
        reads += 1
    assert proc.returncode == 0
    assert reads >= 5, "the writer finished before the readers could follow it"
    assert first_py[1] < 120, "no read happened while the writer was running"
    if follower is not None:
        out, _ = follower.communicate(timeout=60)
        assert follower.returncode == 0
        seen = [json.loads(line) for line in out.splitlines()]
        assert len(seen) == 41
        sizes = [len(s["snapshots"]) for s in seen]
        metrics = [s["metrics"] for s in seen]
        assert sizes == sorted(sizes) and metrics == sorted(metrics)
        assert sizes[-1] > sizes[0], "refreshing never showed a new snapshot"
    check_format(path)
    assert check_python_view(path) == (30, 120, 120)


def test_sigkill_inside_a_snapshot(tmp_path):
    """The writer is killed while it writes snapshot 28's arrays: the log opens, with every
    snapshot completed before (0 ... 24) and every committed row."""
    path = str(tmp_path / "killed.h5")
    proc = start_writer(path, steps=120, pause=True)
    done = -1
    for line in proc.stdout:
        if line.startswith("inside"):
            break
        done = int(line.split()[1])
    else:
        pytest.fail("the writer never reached the snapshot to kill it in")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert done == 27
    snaps, metrics, events = check_python_view(path)
    assert snaps == 7  # 0, 4, ..., 24; 28 was being written
    assert metrics >= done + 1 and events >= done + 1
    check_format(path)
    info = dump(path)
    if require_dump():
        assert info["snapshots"] == list(range(0, 28, 4)) and info["swmr"]
        assert info["counts"] == [20000 + 100 * s for s in range(0, 28, 4)]
        assert info["metrics"] == metrics and info["events"] == events
