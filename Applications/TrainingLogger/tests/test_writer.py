# SPDX-License-Identifier: BSD-3-Clause
"""The h5py writer on its own: format, crash safety (a writer process SIGKILL-ed mid-run
leaves a readable log up to its last flush) and input checks."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import h5py
import numpy as np
import pytest

from logcheck import check_format, dump, require_dump
from vis4gs_logger import TrainingLogWriter, open_log, read_snapshot, read_table, snapshot_iterations

HERE = os.path.dirname(os.path.abspath(__file__))


def test_format_and_sorting(tmp_path):
    path = str(tmp_path / "w.h5")
    with TrainingLogWriter(path, scene="s", sh_degree=1, iterations=10) as w:
        w.append_metrics(1, num_gaussians=3, loss=0.5, l1=None)
        w.append_events(1, 1, [0], [3])
        ids = np.array([3, 0, 2])  # unsorted: rows are sorted by id on write
        pos = np.arange(9, dtype=np.float32).reshape(3, 3)
        w.write_snapshot(5, ids, pos, np.zeros((3, 3)), np.ones((3, 4)), np.zeros(3),
                         np.zeros((3, 4, 3)))
        with pytest.raises(ValueError):
            w.write_snapshot(5, ids, pos, np.zeros((3, 3)), np.ones((3, 4)), np.zeros(3), np.zeros((3, 1, 3)))
        with pytest.raises(ValueError):
            w.write_snapshot(6, [1, 1, 2], pos, np.zeros((3, 3)), np.ones((3, 4)), np.zeros(3), np.zeros((3, 1, 3)))
    check_format(path)
    with open_log(path) as f:
        assert list(read_snapshot(f, 5)["id"]) == [0, 2, 3]
        np.testing.assert_array_equal(read_snapshot(f, 5)["position"], pos[[1, 2, 0]])
        assert np.isnan(f["metrics/l1"][0])
    with pytest.raises(RuntimeError):
        w.flush()



@pytest.mark.parametrize("snapshot_deflate", [None, 2])
def test_snapshot_compression_default(tmp_path, snapshot_deflate):
    # Snapshots uncompressed by default (as the C++ writer: fast history queries), tables
    # deflated; snapshot_deflate=N compresses the snapshots too.
    path = str(tmp_path / "c.h5")
    kwargs = {} if snapshot_deflate is None else dict(snapshot_deflate=snapshot_deflate)
    with TrainingLogWriter(path, sh_degree=0, iterations=10, **kwargs) as w:
        w.append_events(1, 1, [0], [3])
        n = 50
        w.write_snapshot(5, np.arange(n), np.ones((n, 3)), np.zeros((n, 3)), np.ones((n, 4)),
                         np.zeros(n), np.zeros((n, 1, 3)))
    check_format(path)
    with h5py.File(path, "r") as f:
        for name in ("id", "position", "sh"):
            d = f["snapshots/" + name]  # format version 2: the concatenated datasets
            if snapshot_deflate is None:
                assert d.compression is None and not d.shuffle, name
            else:
                assert d.compression == "gzip" and d.compression_opts == 2 and d.shuffle, name
        assert f["events/parent"].compression == "gzip"
        assert f["metrics/loss"].compression == "gzip"
        np.testing.assert_array_equal(read_snapshot(f, 5)["id"], np.arange(50))


WRITER = textwrap.dedent("""
    import sys, numpy as np
    sys.path.insert(0, {pkg!r})
    from vis4gs_logger import TrainingLogWriter
    w = TrainingLogWriter({path!r}, chunk_rows=4096, swmr={swmr!r})
    rng = np.random.default_rng(0)
    s = 0
    while True:
        for k in range(100):
            w.append_metrics(s * 100 + k, num_gaussians=s, loss=float(k))
            w.append_events(s * 100 + k, 1, [k], [1000000 + s * 100 + k])
        n = 30000 + 1000 * s
        w.write_snapshot(s * 100, np.arange(n), np.full((n, 3), s, np.float32),
                         rng.normal(size=(n, 3)), rng.normal(size=(n, 4)), rng.normal(size=n),
                         rng.normal(size=(n, 4, 3)))
        print(s, flush=True)
        s += 1
""")


@pytest.mark.parametrize("swmr", [True, False])
@pytest.mark.parametrize("delay", [0.0, 0.004, 0.02])
def test_killed_writer_leaves_readable_log(tmp_path, delay, swmr):
    path = str(tmp_path / "crash.h5")
    code = WRITER.format(pkg=os.path.dirname(HERE), path=path, swmr=swmr)
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    done = -1
    for _ in range(2):
        line = proc.stdout.readline()
        assert line, "the writer stopped early"
        done = int(line)
    time.sleep(delay)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL
    for line in proc.stdout:
        done = int(line)
    with open_log(path) as f:
        names = snapshot_iterations(f)
        assert len(names) >= done + 1
        for s, name in enumerate(names):
            assert name == 100 * s
            assert np.all(read_snapshot(f, name)["position"] == s)
        m = read_table(f, "metrics")["iteration"]
        assert np.array_equal(m, np.arange(len(m))) and len(m) >= 100 * len(names)
    check_format(path)
    info = dump(path)
    if require_dump():
        assert info["snapshots"] == [100 * s for s in range(len(names))]
        assert info["metrics"] == len(m)
