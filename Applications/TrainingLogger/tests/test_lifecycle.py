# SPDX-License-Identifier: BSD-3-Clause
"""The cases a real run meets at its edges (and the cameras it logs), on the gsplat hooks
with the stand-in ops (checked against gsplat's own in test_mocks_upstream.py): a loop
that starts at step 0, a model pruned to nothing, a model of one Gaussian, a run killed
at any moment, and a run resumed from a checkpoint. Every log is read back by h5py and
by the C++ reader."""

import os
import signal
import subprocess
import sys
import time
import types

import numpy as np
import pytest
import torch

import mock_gsplat_ops
import test_gsplat
from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot, snapshot_iterations
from vis4gs_logger import CLONE, PRUNE, SPLIT, TrainingLogger, track_gsplat

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH, HEIGHT, FOCAL = 64, 48, 60.0


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
    with open_log(path) as f:
        assert snapshot_iterations(f) == [0, 2, 4]
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
    with open_log(path) as f:
        assert read_snapshot(f, 1)["id"].tolist() == [1]
        assert read_snapshot(f, 2)["id"].tolist() == [1, 4, 5]
        empty = read_snapshot(f, 3)
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
import os, signal
from vis4gs_logger import writer
if len(sys.argv) > 4:  # die inside the writer: at the N-th call of one of its methods
    method, nth = sys.argv[4].split(":")
    raw, calls = writer.TrainingLogWriter.__dict__[method], [0]
    original = getattr(writer.TrainingLogWriter, method)
    def dying(*args, **kwargs):
        calls[0] += 1
        if calls[0] == int(nth):
            os.kill(os.getpid(), signal.SIGKILL)
        return original(*args, **kwargs)
    setattr(writer.TrainingLogWriter, method,
            staticmethod(dying) if isinstance(raw, staticmethod) else dying)
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


@pytest.mark.parametrize("steps", [0, 1, 2, 5, 14, 40])
def test_killed_run_leaves_a_valid_log(tmp_path, steps):
    """SIGKILL as soon as the run has reported `steps` finished steps (0: at once, before
    or while the file is created); the process is then anywhere in the next step (in
    densification, a flush or a snapshot). The log is written as <path>.tmp until close():
    that file reads as a valid log that holds at least every snapshot of the finished
    steps, and nothing is at path."""
    final = str(tmp_path / "killed.h5")
    path = final + ".tmp"
    root = os.path.dirname(HERE)
    child = subprocess.Popen([sys.executable, "-c", _CHILD, final, HERE, root],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        for k in range(steps):
            assert child.stdout.readline().strip() == str(k + 1), child.stderr.read()
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=30)
    finally:
        if child.poll() is None:
            child.kill()
    assert not os.path.exists(final)
    if steps == 0 and not _has_format(path):
        return  # killed before the file's first flush: there is no log to read
    check_format(path)
    events = read_events(path)
    replay_genealogy(events, 200)
    with open_log(path) as f:
        snaps = snapshot_iterations(f)
        assert set(range(0, steps + 1, 3)) <= set(snaps)
        assert len(f["metrics/iteration"]) >= steps - 1
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["events"] == len(events[0])
        assert info["snapshots"] == snaps and info["counts"][0] == 200


@pytest.mark.parametrize("where", ["_fit:20", "_fit:45", "_append:30", "_append:61"])
def test_run_killed_inside_the_writer_leaves_a_valid_log(tmp_path, where):
    """SIGKILL in the middle of writing a snapshot (between two of its datasets) or of a
    flush (between two appended columns): the log (<path>.tmp) is the one of the last flush."""
    final = str(tmp_path / "killed.h5")
    path = final + ".tmp"
    child = subprocess.run([sys.executable, "-c", _CHILD, final, HERE, os.path.dirname(HERE),
                            where], capture_output=True, text=True, timeout=120)
    assert not os.path.exists(final)
    assert child.returncode == -signal.SIGKILL, child.stderr
    reported = [int(line) for line in child.stdout.split()]
    assert reported, "killed before the first step"
    check_format(path)
    replay_genealogy(read_events(path), 200)
    with open_log(path) as f:
        snaps = snapshot_iterations(f)
        assert set(range(0, reported[-1] + 1, 3)) <= set(snaps)
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["snapshots"] == snaps


def _has_format(path):
    try:
        with open_log(path) as f:
            return "format" in f.attrs and "snapshots" in f and "committed" in f
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
    checkpoint = 5  # the trainer saved its checkpoint at 5 (6 Gaussians) and stopped at 7
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
    with open_log(old) as f:
        # close() kept the model of the last step (7) besides the interval's.
        assert snapshot_iterations(f) == [0, 5, 7]
        assert "start_iteration" not in f.attrs
    check_format(path)
    with open_log(path) as f:
        assert int(f.attrs["start_iteration"]) == 5
        assert snapshot_iterations(f) == [5, 10]
        assert read_snapshot(f, 5)["id"].tolist() == list(range(6))
        assert read_snapshot(f, 10)["id"].tolist() == [1, 2, 3, 4]
        assert f["metrics/iteration"][0] == 6
    events = read_events(path)
    assert events[0].tolist() == [8, 8] and events[2].tolist() == [0, 5]
    info = dump(path)
    if require_dump():
        assert info["snapshots"] == [5, 10] and info["repairs"] == []


def colmap_parser(folder, views=6):
    """The attributes of gsplat's examples/datasets/colmap.py Parser that
    log_gsplat_cameras reads, with image files on disk."""
    images = folder / "images_4"
    images.mkdir(parents=True)
    names = [f"frame_{i:03d}.jpg" for i in range(views)]
    for n in names:
        (images / n).write_bytes(b"")
    c2w = np.repeat(np.eye(4)[None], views, axis=0)
    c2w[:, 0, 3] = np.arange(views) * 0.1
    k = np.array([[FOCAL, 0, WIDTH / 2], [0, FOCAL, HEIGHT / 2], [0, 0, 1]])
    return types.SimpleNamespace(
        data_dir=str(folder), test_every=4, image_names=names,
        image_paths=[str(images / n) for n in names], camtoworlds=c2w,
        camera_ids=[1] * views, Ks_dict={1: k}, imsize_dict={1: (WIDTH, HEIGHT)})


def test_cameras_lead_to_their_images(tmp_path):
    """Relative image paths that the C++ reader returns and the application resolves
    against the log's folder: gsplat's Parser, and 3DGS cameras whose image names have no
    extension; world_to_camera is the inverse of the Parser's camera-to-world."""
    parser = colmap_parser(tmp_path / "garden")
    out = tmp_path / "results" / "run"
    out.mkdir(parents=True)
    params, _ = make_splats(4)
    path = str(out / "training_log.h5")
    logger = TrainingLogger(path)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    logger.log_gsplat_cameras(parser)
    logger.close()
    with open_log(path) as f:
        c = f["cameras"]
        images = list(c["image"].asstr()[:])
        assert images == [os.path.join("..", "..", "garden", "images_4", n)
                          for n in parser.image_names]
        assert list(c["split"][:]) == [1, 0, 0, 0, 1, 0]
        assert c.attrs["source"] == parser.data_dir
        assert c.attrs["image_dir"] == os.path.dirname(parser.image_paths[0])
        w2c = c["world_to_camera"][:]
        np.testing.assert_allclose(w2c[3] @ parser.camtoworlds[3], np.eye(4), atol=1e-12)
        assert c["fx"][0] == FOCAL and c["cx"][0] == WIDTH / 2 and c["width"][0] == WIDTH
    info = dump(path)
    if require_dump():
        assert info["camera_images"] == images
        assert all(os.path.isfile(os.path.join(out, p)) for p in images)

    # 3DGS: names without extension, looked up in the image folder; unknown ones stay "".
    (tmp_path / "scene" / "images").mkdir(parents=True)
    (tmp_path / "scene" / "images" / "a.JPG").write_bytes(b"")
    cams = [types.SimpleNamespace(image_name=n, image_width=WIDTH, image_height=HEIGHT,
                                  FoVx=1.0, FoVy=0.8, world_view_transform=torch.eye(4))
            for n in ("a", "missing")]
    path = str(out / "gs3d.h5")
    logger = TrainingLogger(path)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    logger.log_3dgs_cameras(cams[:1], cams[1:], images_dir=str(tmp_path / "scene" / "images"),
                            source=str(tmp_path / "scene"))
    logger.close()
    with open_log(path) as f:
        assert list(f["cameras/image"].asstr()[:]) == [
            os.path.join("..", "..", "scene", "images", "a.JPG"), ""]
