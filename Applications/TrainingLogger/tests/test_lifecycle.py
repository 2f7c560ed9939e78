# SPDX-License-Identifier: BSD-3-Clause
"""The cases a real run meets at its edges, on the gsplat hooks with the stand-in ops
(checked against gsplat's own in test_mocks_upstream.py): a loop that starts at step 0,
a model pruned to nothing, a model of one Gaussian, a run killed at any moment, and a run
resumed from a checkpoint. Every log is read back by h5py and by the C++ reader."""

import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest
import torch

import mock_gsplat_ops
import test_gsplat
from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger import CLONE, PRUNE, SPLIT, TrainingLogger, track_gsplat

HERE = os.path.dirname(os.path.abspath(__file__))


def make_splats(n, seed=0):
    params, optimizers, _ = test_gsplat.make_splats(n, seed)
    return params, optimizers


def test_step_zero_after_the_initial_snapshot(tmp_path):
    """gsplat's loop starts at step 0, after track_gsplat wrote the snapshot of 0."""
    params, optimizers = make_splats(5)
    path = str(tmp_path / "s0.h5")
    logger = TrainingLogger(path, snapshot_interval=2)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    for step in range(0, 5):
        logger.log_metrics(step, loss=1.0)
        logger.step(step)  # step(0) must not write (nor refuse) snapshot 0 again
    logger.close()
    with h5py.File(path, "r") as f:
        assert sorted(f["snapshots"]) == ["000000", "000002", "000004"]
        np.testing.assert_array_equal(f["metrics/iteration"][:], np.arange(5))
    # A second snapshot of one iteration is still refused when asked for explicitly.
    logger = TrainingLogger(str(tmp_path / "again.h5"))
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    with pytest.raises(ValueError, match="snapshot 0 is not after 0"):
        logger.snapshot(0)
    logger.close()


def test_model_pruned_to_nothing_and_regrown_from_one(tmp_path):
    params, optimizers = make_splats(3)
    state = {}
    path = str(tmp_path / "empty.h5")
    logger = TrainingLogger(path, snapshot_interval=1)
    tracker = track_gsplat(params, logger, modules=[mock_gsplat_ops])
    logger.log_metrics(1)
    mock_gsplat_ops.remove(params, optimizers, state, torch.tensor([True, False, True]))
    logger.step(1)  # one Gaussian
    logger.log_metrics(2)
    mock_gsplat_ops.duplicate(params, optimizers, state, torch.tensor([True]))
    mock_gsplat_ops.split(params, optimizers, state, torch.tensor([False, True]))
    logger.step(2)  # ids 1 (kept), 4 and 5 (split children of the clone 3)
    logger.log_metrics(3)
    mock_gsplat_ops.remove(params, optimizers, state, torch.ones(3, dtype=torch.bool))
    assert len(params["means"]) == 0
    logger.step(3)  # the empty model
    logger.log_metrics(4, num_gaussians=0)
    logger.close()
    assert tracker.next_id == 6
    check_format(path)
    events = read_events(path)
    assert events[1].tolist() == [PRUNE, PRUNE, CLONE, SPLIT, SPLIT, PRUNE, PRUNE, PRUNE]
    assert events[2].tolist() == [0, 2, 1, 3, 3, 1, 4, 5]
    alive, next_id = replay_genealogy(events, 3)
    assert alive == set() and next_id == 6
    with h5py.File(path, "r") as f:
        assert f["snapshots/000001/id"][:].tolist() == [1]
        assert f["snapshots/000002/id"][:].tolist() == [1, 4, 5]
        empty = f["snapshots/000003"]
        assert empty["id"].shape == (0,) and empty["sh"].shape == (0, 16, 3)
        assert empty["position"].shape == (0, 3)
    info = dump(path)
    if require_dump():
        assert info["snapshots"] == [0, 1, 2, 3] and info["counts"] == [3, 1, 3, 0]
        assert info["repairs"] == []


_CHILD = r"""
import sys, time, torch
sys.path[:0] = [sys.argv[2], sys.argv[3]]
import mock_gsplat_ops
from vis4gs_logger import TrainingLogger, track_gsplat
from test_lifecycle import make_splats
params, optimizers = make_splats(200)
logger = TrainingLogger(sys.argv[1], snapshot_interval=3, flush_every_s=0.0)
track_gsplat(params, logger, modules=[mock_gsplat_ops])
step = 0
while True:
    step += 1
    logger.log_metrics(step, loss=1.0 / step)
    n = len(params["means"])
    mask = torch.zeros(n, dtype=torch.bool)
    mask[step % n] = True
    mock_gsplat_ops.duplicate(params, optimizers, {}, mask)
    mock_gsplat_ops.remove(params, optimizers, {}, torch.roll(torch.cat([mask, mask[:1]]), 7))
    logger.step(step)
    print(step, flush=True)
"""


@pytest.mark.parametrize("delay_s", [0.0, 0.35, 0.8, 1.3, 2.1])
def test_killed_run_leaves_a_valid_log(tmp_path, delay_s):
    """SIGKILL at several moments (in __init__, mid-step, mid-snapshot, later): the file
    reads as a valid log up to its last flush."""
    path = str(tmp_path / "killed.h5")
    root = os.path.dirname(HERE)
    child = subprocess.Popen([sys.executable, "-c", _CHILD, path, HERE, root],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # Wait until the logger exists (the interpreter and torch take a while to start).
        first = child.stdout.readline() if delay_s > 0 else ""
        time.sleep(delay_s)
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=30)
    finally:
        if child.poll() is None:
            child.kill()
    if delay_s > 0:
        assert first.strip() == "1"
    if not os.path.exists(path):
        return  # killed before the file was created: nothing to read
    with h5py.File(path, "r"):
        pass  # opens
    if delay_s == 0.0 and not _has_format(path):
        return  # killed inside the creation of the file, before its first flush
    check_format(path)
    events = read_events(path)
    alive, _ = replay_genealogy(events, 200)
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["events"] == len(events[0])
        assert info["snapshots"][0] == 0 and info["counts"][0] == 200


def _has_format(path):
    try:
        with h5py.File(path, "r") as f:
            return "format" in f.attrs and "snapshots" in f
    except OSError:
        return False


def test_resumed_run_starts_a_clear_new_log(tmp_path):
    """3DGS --start_checkpoint: the loop restarts at checkpoint + 1; the old log is kept
    and the new one starts at the checkpoint with ids 0..N-1 of the checkpoint's rows."""
    params, optimizers = make_splats(4)
    path = str(tmp_path / "training_log.h5")
    logger = TrainingLogger(path, snapshot_interval=5)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    for it in range(1, 8):
        logger.log_metrics(it)
        if it == 3:
            mock_gsplat_ops.duplicate(params, optimizers, {}, torch.tensor([1, 0, 0, 1]).bool())
        logger.step(it)
    logger.close()
    checkpoint = 5  # the trainer saved its checkpoint at 5 (6 Gaussians) and crashed at 7
    with pytest.warns(RuntimeWarning, match="before-5"):
        logger = TrainingLogger(path, snapshot_interval=5, start_iteration=checkpoint)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    for it in range(checkpoint + 1, 11):
        logger.log_metrics(it)
        if it == 8:
            mock_gsplat_ops.remove(params, optimizers, {}, torch.tensor([1, 0, 0, 0, 0, 1]).bool())
        logger.step(it)
    logger.close()
    old = str(tmp_path / "training_log.before-5.h5")
    with h5py.File(old, "r") as f:
        assert sorted(f["snapshots"]) == ["000000", "000005"]
        assert "start_iteration" not in f.attrs
    check_format(path)
    with h5py.File(path, "r") as f:
        assert int(f.attrs["start_iteration"]) == 5
        assert sorted(f["snapshots"]) == ["000005", "000010"]
        assert f["snapshots/000005/id"][:].tolist() == list(range(6))
        assert f["snapshots/000010/id"][:].tolist() == [1, 2, 3, 4]
        assert f["metrics/iteration"][0] == 6
    events = read_events(path)
    assert events[0].tolist() == [8, 8] and events[2].tolist() == [0, 5]
    info = dump(path)
    if require_dump():
        assert info["snapshots"] == [5, 10] and info["repairs"] == []
