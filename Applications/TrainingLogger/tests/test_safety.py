# SPDX-License-Identifier: BSD-3-Clause
"""What the logger owes a training that runs for hours (issue 32): the final model is
always in the log, events carry the iteration of the step that made them, and a
bookkeeping problem never stops the training (it is a warning and a row of
/lineage_breaks, whose new roots the C++ reader and the genealogy know)."""

import os
import warnings

import numpy as np
import pytest
import torch

import mock_gsplat_ops
import test_gsplat
from logcheck import check_format, dump, read_events, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot, snapshot_iterations
from mock_3dgs import GaussianModel
from vis4gs_logger import CLONE, PRUNE, TrainingLogger, track_3dgs, track_gsplat


def _snapshots(path):
    with open_log(path) as f:
        return snapshot_iterations(f)


def test_gsplat_loop_ends_with_the_final_model(tmp_path):
    """gsplat's loop runs steps 0..max_steps-1: the last one is no multiple of the
    interval, and close() writes it (the ids and means of the model as it ended)."""
    params, optimizers, state = test_gsplat.make_splats(20, 0)
    path = str(tmp_path / "gsplat.h5")
    logger = TrainingLogger(path, snapshot_interval=4)
    tracker = track_gsplat(params, logger, modules=[mock_gsplat_ops])
    max_steps = 11
    for step in range(max_steps):
        logger.log_metrics(step, loss=1.0)
        if step == 9:  # densification late in the run: the final model differs from 8's
            mask = torch.zeros(len(params["means"]), dtype=torch.bool)
            mask[:3] = True
            mock_gsplat_ops.duplicate(params, optimizers, state, mask)
        logger.step(step)
    ids = tracker.ids.clone()
    means = params["means"].detach().clone()
    logger.close()
    assert _snapshots(path) == [0, 4, 8, max_steps - 1]
    with open_log(path) as f:
        g = read_snapshot(f, max_steps - 1)
        order = np.argsort(ids.numpy())
        np.testing.assert_array_equal(g["id"][:], ids.numpy()[order])
        np.testing.assert_array_equal(g["position"][:], means.numpy()[order])
    logger.close()  # twice: nothing more
    assert _snapshots(path) == [0, 4, 8, max_steps - 1]
    info = dump(path)
    if require_dump():
        assert info["snapshots"][-1] == max_steps - 1 and info["counts"][-1] == 23


def test_3dgs_loop_ends_with_the_final_model(tmp_path):
    """train.py runs iterations 1..N: 600 iterations at the default interval 500 ended at
    500 before; the log now ends with 600. A run that ends on the interval gets no
    second copy."""
    for iterations, expected in ((600, [0, 500, 600]), (1000, [0, 500, 1000])):
        g = GaussianModel(3)
        g.create_random(30, seed=1)
        path = str(tmp_path / f"gs3d_{iterations}.h5")
        logger = TrainingLogger(path, iterations=iterations)
        track_3dgs(g, logger)
        for iteration in range(1, iterations + 1):
            logger.step(iteration)
        logger.close()
        assert _snapshots(path) == expected


def test_events_carry_the_iteration_of_their_step(tmp_path):
    """Metrics logged every 10th step only: the events of step 13 are at 13 (they took the
    iteration of the last log_metrics call, 10, before)."""
    params, optimizers, state = test_gsplat.make_splats(10, 1)
    path = str(tmp_path / "events.h5")
    logger = TrainingLogger(path, snapshot_interval=0)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    made = []
    for step in range(25):
        if step % 10 == 0:
            logger.log_metrics(step, loss=1.0)
        if step in (0, 13, 17, 20, 24):
            mask = torch.zeros(len(params["means"]), dtype=torch.bool)
            mask[step % 5] = True
            mock_gsplat_ops.duplicate(params, optimizers, state, mask)
            made.append(step)
        if step == 21:
            mask = torch.zeros(len(params["means"]), dtype=torch.bool)
            mask[0] = True
            mock_gsplat_ops.remove(params, optimizers, state, mask)
            made.append(step)
        logger.step(step)
        # metrics of an ended step (logged after step()) do not move events back
        logger.log_metrics(step, loss=0.5, test=False) if step == 17 else None
    logger.close()
    it, kind, _, _ = read_events(path)
    assert it.tolist() == made
    assert kind.tolist() == [CLONE, CLONE, CLONE, CLONE, PRUNE, CLONE]


def _grow_outside(params, optimizers, n):
    """A fork's own densification: rows appended without gsplat's ops."""
    def param_fn(name, p):
        return torch.nn.Parameter(torch.cat([p, p[:n]]), requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return torch.cat([v, torch.zeros_like(v[:n])])

    mock_gsplat_ops._update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)


def _shrink_outside(params, optimizers, keep):
    def param_fn(name, p):
        return torch.nn.Parameter(p[keep], requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return v[keep]

    mock_gsplat_ops._update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)


def test_rows_changed_outside_the_wrappers_break_the_lineage_not_the_training(tmp_path):
    """A fork adds rows, then removes rows, outside the wrapped ops; a wrapped op and the
    snapshots follow. Nothing raises; one warning; each break is a row of /lineage_breaks;
    the appended rows keep the ids before them, after a removal every row is a new root."""
    params, optimizers, _ = test_gsplat.make_splats(8, 2)
    state = {}  # the fork keeps no per-row strategy state
    path = str(tmp_path / "break.h5")
    logger = TrainingLogger(path, snapshot_interval=2)
    tracker = track_gsplat(params, logger, modules=[mock_gsplat_ops])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for step in range(1, 8):
            logger.log_metrics(step, loss=1.0)
            if step == 3:
                _grow_outside(params, optimizers, 3)  # 8 -> 11 rows, ids 8..10 new roots
                mask = torch.zeros(11, dtype=torch.bool)
                mask[[1, 9]] = True
                mock_gsplat_ops.duplicate(params, optimizers, state, mask)  # 11, 12
            if step == 5:
                _shrink_outside(params, optimizers, torch.arange(1, 13))  # 13 -> 12 rows
            if step == 6:
                mask = torch.zeros(12, dtype=torch.bool)
                mask[0] = True
                mock_gsplat_ops.split(params, optimizers, state, mask)
            logger.step(step)
        logger.close()
    ours = [w for w in caught if "vis4gs_logger" in str(w.message)]
    assert len(ours) == 1 and "lineage lost at iteration 3" in str(ours[0].message)
    assert len(tracker.breaks) == 2
    with open_log(path) as f:
        b = f["lineage_breaks"]
        assert b["iteration"][:].tolist() == [3, 6]
        assert b["tracked"][:].tolist() == [8, 13] and b["rows"][:].tolist() == [11, 12]
        assert b["kept"][:].tolist() == [8, 0]
        assert b["first_new_id"][:].tolist() == [8, 13] and b["new_roots"][:].tolist() == [3, 12]
        assert b["event_row"][:].tolist() == [0, 2]
        assert "duplicate" in b["where"].asstr()[0] and "split" in b["where"].asstr()[1]
        assert read_snapshot(f, 4)["id"].tolist() == list(range(13))
        # after the second break: ids 13..24, the split of row 0 (id 13) gives 25, 26
        assert read_snapshot(f, 6)["id"].tolist() == list(range(14, 27))
    it, kind, parent, child = read_events(path)
    assert it.tolist() == [3, 3, 6, 6] and parent.tolist() == [1, 9, 13, 13]
    assert child.tolist() == [11, 12, 25, 26]
    check_format(path)
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["events"] == 4
        assert info["lineage_breaks"] == [
            {"iteration": 3, "event_row": 0, "tracked": 8, "rows": 11, "kept": 8,
             "first_new_id": 8, "new_roots": 3},
            {"iteration": 6, "event_row": 2, "tracked": 13, "rows": 12, "kept": 0,
             "first_new_id": 13, "new_roots": 12}]


def test_ops_imported_before_tracking_and_failing_bookkeeping(tmp_path, monkeypatch):
    """A custom strategy that imported gsplat's op before track_gsplat calls the unwrapped
    op: the next wrapped op finds the rows changed and breaks the lineage. A failure inside
    the bookkeeping itself is a warning and a break too; the trainer's op still runs, and
    the trainer's own exceptions still reach it."""
    params, optimizers, _ = test_gsplat.make_splats(6, 3)
    state = {}
    unwrapped_duplicate = mock_gsplat_ops.duplicate
    path = str(tmp_path / "early.h5")
    logger = TrainingLogger(path, snapshot_interval=0)
    tracker = track_gsplat(params, logger, modules=[mock_gsplat_ops])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        logger.step(0)
        unwrapped_duplicate(params, optimizers, state, torch.tensor([1, 1, 0, 0, 0, 0]).bool())
        mock_gsplat_ops.remove(params, optimizers, state, torch.zeros(8, dtype=torch.bool))
        logger.step(1)
        monkeypatch.setattr(tracker, "append_children",
                            lambda *a, **k: (_ for _ in ()).throw(KeyError("boom")))
        mock_gsplat_ops.duplicate(params, optimizers, state, torch.ones(8, dtype=torch.bool))
        assert len(params["means"]) == 16  # the op ran
        logger.step(2)
        with pytest.raises(IndexError):  # the trainer's own error is not swallowed
            mock_gsplat_ops.duplicate(params, optimizers, state, torch.ones(40, dtype=torch.bool))
        logger.close()
    messages = [str(w.message) for w in caught if "vis4gs_logger" in str(w.message)]
    assert any("bookkeeping of duplicate failed at iteration 2" in m for m in messages)
    with open_log(path) as f:
        b = f["lineage_breaks"]
        assert b["iteration"][:].tolist() == [1, 2]
        assert b["kept"][:].tolist() == [6, 0] and b["new_roots"][:].tolist() == [2, 16]
        assert read_snapshot(f, 2)["id"].tolist() == list(range(8, 24))
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["snapshots"] == [0, 2]


def test_a_snapshot_that_fails_in_the_tracker_does_not_stop_the_training(tmp_path, monkeypatch):
    """An error that is not the disk's (here the tracker's) skips that snapshot only."""
    params, optimizers, state = test_gsplat.make_splats(4, 4)
    path = str(tmp_path / "bookkeeping.h5")
    logger = TrainingLogger(path, snapshot_interval=1)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])

    def broken(*args, **kwargs):
        raise IndexError("a row the tracker does not know")

    original = logger.writer.write_snapshot
    monkeypatch.setattr(logger.writer, "write_snapshot", broken)
    with pytest.warns(RuntimeWarning, match="snapshot of iteration 1 could not be written"):
        logger.step(1)
        logger.step(2)
    assert len(logger.snapshot_failures) == 2 and logger.failure is None
    monkeypatch.setattr(logger.writer, "write_snapshot", original)
    logger.step(3)
    logger.close()
    assert _snapshots(path) == [0, 3]


@pytest.mark.parametrize("earlier", [False, True])
def test_a_full_disk_stops_the_logging_not_the_training(tmp_path, monkeypatch, earlier):
    """A failed write (an OSError, as h5py raises for ENOSPC) in a snapshot: one warning naming
    the path and the problem, nothing written after it and no exception into the loop; the
    temporary is removed, an earlier log at path stays byte for byte as it was.
    (CheckFullDisk.py logger runs the same on a real full and read-only file system.)"""
    params, optimizers, state = test_gsplat.make_splats(4, 4)
    path = tmp_path / "full.h5"
    if earlier:
        path.write_bytes(b"an earlier log")
    logger = TrainingLogger(str(path), snapshot_interval=1)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    assert (tmp_path / "full.h5.tmp").exists()

    def full_disk(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(logger.writer, "write_snapshot", full_disk)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        logger.step(1)
        for step in (2, 3):
            logger.log_metrics(step, loss=0.5)
            mock_gsplat_ops.duplicate(params, optimizers, state, torch.tensor([True, False, False,
                                                                               False]))
            logger.step(step)
        logger.flush()
        logger.close()
    said = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert len(said) == 1, said
    assert str(path) in said[0] and "No space left on device" in said[0]
    assert "snapshot of iteration 1" in logger.failure
    assert sorted(p.name for p in tmp_path.iterdir()) == (["full.h5"] if earlier else [])
    if earlier:
        assert path.read_bytes() == b"an earlier log"


def test_a_read_only_folder_stops_the_logging_not_the_training(tmp_path):
    """The log cannot be created: the same warning, the calls of a training do nothing."""
    if os.geteuid() == 0:
        pytest.skip("root writes into a read-only folder (CheckFullDisk.py logger mounts one)")
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    params, optimizers, state = test_gsplat.make_splats(4, 4)
    with pytest.warns(RuntimeWarning, match="creating the log failed: Permission denied"):
        logger = TrainingLogger(str(folder / "run.h5"), snapshot_interval=1)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    logger.log_metrics(1, loss=0.5)
    logger.step(1)
    logger.close()
    assert list(folder.iterdir()) == []


@pytest.mark.parametrize("swmr", [True, False])
def test_every_write_stays_inside_its_reservation(tmp_path, monkeypatch, swmr):
    """The writer reserves a write's file space before HDF5 writes (a full disk must never
    reach HDF5, see TrainingLogWriter): after every write (a flush, a snapshot, the cameras,
    an image, the close) the file's size and HDF5's end of allocation are within the
    reservation, for compressed and uncompressed tables and snapshots, packed snapshots
    crossing chunk boundaries and growing models."""
    import contextlib

    from vis4gs_logger import writer as writer_module

    seen = []
    original = writer_module.TrainingLogWriter._writing

    @contextlib.contextmanager
    def checked(self, nbytes):
        with original(self, nbytes):
            yield
        end = max(os.path.getsize(self.write_path), int(self._file.id.get_filesize()))
        seen.append(end)
        assert end <= self.reserved_end, (end, self.reserved_end)

    monkeypatch.setattr(writer_module.TrainingLogWriter, "_writing", checked)
    for deflate, snapshot_deflate, n, chunk_rows, float16 in ((1, 0, 1500, 1024, False),
                                                               (0, 6, 400, 256, True)):
        path = tmp_path / f"run-{deflate}.h5"
        params, optimizers, state = test_gsplat.make_splats(n, 6)
        logger = TrainingLogger(str(path), snapshot_interval=4, iterations=30, swmr=swmr,
                                deflate=deflate, snapshot_deflate=snapshot_deflate,
                                chunk_rows=chunk_rows, snapshot_sh_float16=float16)
        v = 12
        logger.log_cameras([f"view{i}" for i in range(v)], [64] * v, [48] * v, [50.0] * v,
                           [50.0] * v, [32.0] * v, [24.0] * v, np.tile(np.eye(4), (v, 1, 1)))
        logger.writer.write_image("view0", np.random.default_rng(0).integers(0, 255, (70, 64, 3),
                                                                             dtype=np.uint8))
        track_gsplat(params, logger, modules=[mock_gsplat_ops])
        for step in range(1, 31):
            logger.log_metrics(step, loss=1.0 / step)
            mask = torch.rand(len(params["means"]), generator=torch.Generator().manual_seed(step))
            mock_gsplat_ops.duplicate(params, optimizers, state, mask < 0.05)
            logger.step(step)
            if step == 17:  # structure added in SWMR mode (the file is reopened)
                logger.writer.write_image("late", np.zeros((10, 8, 3), np.uint8))
        logger.close()
        assert logger.failure is None and path.exists()
        assert snapshot_iterations(open_log(str(path))) == [0, 4, 8, 12, 16, 20, 24, 28, 30]
    assert len(seen) > 40


def test_a_failed_reservation_at_any_write_leaves_the_training_running(tmp_path):
    """The disk fills before the k-th write (its reservation fails with ENOSPC), in a
    training process of its own: one warning naming the log and the problem, the training
    runs to its end and the process exits with status 0 (HDF5 crashed it at exit when it met
    the full disk itself), and no temporary is left. (CheckFullDisk.py logger runs this on a
    real full file system.)"""
    import subprocess
    import sys

    here = os.path.dirname(os.path.abspath(__file__))
    script = (
        "import errno, os, sys, warnings\n"
        "sys.path[:0] = [sys.argv[3], os.path.dirname(sys.argv[3])]\n"
        "import torch, mock_gsplat_ops, test_gsplat\n"
        "from vis4gs_logger import TrainingLogger, track_gsplat, writer\n"
        "calls, real = [0], writer._reserve_blocks\n"
        "def reserve(fd, offset, length):\n"
        "    calls[0] += 1\n"
        "    if calls[0] >= int(sys.argv[2]):\n"
        "        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))\n"
        "    real(fd, offset, length)\n"
        "writer._reserve_blocks = reserve\n"
        "warnings.simplefilter('always')\n"
        "params, optimizers, state = test_gsplat.make_splats(300, 7)\n"
        "logger = TrainingLogger(sys.argv[1], snapshot_interval=5, iterations=23, swmr=sys.argv[4] == '1')\n"
        "track_gsplat(params, logger, modules=[mock_gsplat_ops])\n"
        "for step in range(1, 24):\n"
        "    logger.log_metrics(step, loss=1.0 / step)\n"
        "    mock_gsplat_ops.duplicate(params, optimizers, state, torch.rand(len(params['means'])) < 0.1)\n"
        "    logger.step(step)\n"
        "logger.close()\n"
        "print('ended at', step, 'reservations', calls[0])\n")
    # the k-th reservation: at the creation, the first snapshot, later flushes and snapshots
    for swmr, k in ((1, 1), (1, 3), (1, 9), (0, 2), (0, 5)):
        folder = tmp_path / f"{swmr}-{k}"
        folder.mkdir()
        log = folder / "run.h5"
        p = subprocess.run([sys.executable, "-c", script, str(log), str(k), here, str(swmr)],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           timeout=300)
        what = f"swmr={swmr}, the disk full from reservation {k}: {p.stdout[-2000:]}"
        assert p.returncode == 0, what
        assert "ended at 23" in p.stdout, what
        assert p.stdout.count("No space left on device; logging stops") == 1, what
        assert str(log) in p.stdout and "HDF5-DIAG" not in p.stdout, what
        assert list(folder.iterdir()) == [], what


def test_snapshot_options_sh_degree_float16_and_compression(tmp_path):
    """SH degree kept, float16 colours and a compression level: the stored values are the
    trainer's (the first (d+1)^2 coefficients; float16 within half a unit in the last place),
    fewer bytes per Gaussian, and the C++ reader reads them."""
    params, optimizers, state = test_gsplat.make_splats(2000, 5)
    with torch.no_grad():
        params["shN"].normal_()
    sh = torch.cat([params["sh0"], params["shN"]], dim=1).detach().numpy()
    sizes = {}
    for name, options in (("full", {}), ("dc", {"snapshot_sh_degree": 0}),
                          ("deg1", {"snapshot_sh_degree": 1}),
                          ("half", {"snapshot_sh_float16": True}),
                          ("gzip", {"snapshot_deflate": 4})):
        path = str(tmp_path / f"{name}.h5")
        logger = TrainingLogger(path, snapshot_interval=0, **options)
        track_gsplat(params, logger, modules=[mock_gsplat_ops])
        logger.close()
        sizes[name] = logger.writer.snapshot_bytes
        with open_log(path) as f:
            stored = read_snapshot(f, 0)["sh"]
            k = {"dc": 1, "deg1": 4}.get(name, 16)
            assert stored.shape == (2000, k, 3)
            if name == "half":
                assert stored.dtype == np.float16
                np.testing.assert_allclose(stored[:], sh, rtol=2 ** -11, atol=2 ** -24)
            else:
                assert stored.dtype == np.float32
                np.testing.assert_array_equal(stored[:], sh[:, :k])
            packed = f["snapshots/sh"]  # format version 2: the concatenated dataset
            assert (packed.compression == "gzip") == (name == "gzip")
        info = dump(path)
        if require_dump():
            assert info["counts"] == [2000] and info["repairs"] == []
    # ids 8 + position 12 + log_scale 12 + rotation 16 + opacity 4 = 52 bytes, + 12 per
    # coefficient (6 in float16); chunks are whole rows here, so the sizes are exact.
    assert sizes["full"] == 2000 * (52 + 16 * 12)
    assert sizes["dc"] == 2000 * (52 + 12) and sizes["deg1"] == 2000 * (52 + 4 * 12)
    assert sizes["half"] == 2000 * (52 + 16 * 6)
    assert sizes["gzip"] < sizes["full"]


def test_disk_warning_and_size_budget(tmp_path, monkeypatch):
    """The projected log (snapshots so far + the last one's size for each one planned)
    against the free disk: one warning. A budget doubles the interval until the projection
    fits."""
    import shutil
    from collections import namedtuple

    params, optimizers, state = test_gsplat.make_splats(1000, 6)
    per_snapshot = 1000 * (52 + 16 * 12)
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda p: usage(10 ** 9, 0, 5 * per_snapshot))
    path = str(tmp_path / "disk.h5")
    with pytest.warns(RuntimeWarning, match="projected to grow by") as caught:
        logger = TrainingLogger(path, iterations=100, snapshot_interval=10)
        track_gsplat(params, logger, modules=[mock_gsplat_ops])  # snapshot 0: 10 more planned
        for step in range(1, 31):
            logger.step(step)
        logger.close()
    assert len([w for w in caught if "projected" in str(w.message)]) == 1
    assert _snapshots(path) == [0, 10, 20, 30]

    monkeypatch.setattr(shutil, "disk_usage", lambda p: usage(10 ** 12, 0, 10 ** 11))
    path = str(tmp_path / "budget.h5")
    with pytest.warns(RuntimeWarning, match="snapshot interval now 40"):
        logger = TrainingLogger(path, iterations=100, snapshot_interval=10,
                                snapshot_budget_bytes=4 * per_snapshot)
        track_gsplat(params, logger, modules=[mock_gsplat_ops])
        for step in range(1, 101):
            logger.step(step)
        logger.close()
    # 0, then every 40: 40, 80, and the final model 100 (the budget bounds the planned ones)
    assert _snapshots(path) == [0, 40, 80, 100]


def _png(path, rgb):
    import struct
    import zlib

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    h, w, _ = rgb.shape
    raw = b"".join(b"\0" + rgb[y].tobytes() for y in range(h))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def test_analyze_computes_what_needs_no_image_when_an_image_is_bad(tmp_path):
    """`vis4gs analyze --scores=coverage,needle,shape` on a logger's log whose third
    training image is not a PNG: exit 0, a warning naming the file, View Coverage and Needle
    Shape over every view, the Needle score from the readable views: equal to a run where
    that view has no image at all."""
    import csv
    import os
    import subprocess

    from test_lifecycle import colmap_parser

    exe = os.environ.get("VIS4GS_EXECUTABLE")
    if not exe:
        pytest.skip("VIS4GS_EXECUTABLE (the vis4gs program) is not set: run under CTest")
    parser = colmap_parser(tmp_path / "scene", views=4)
    rng = np.random.default_rng(7)
    for i, p in enumerate(parser.image_paths):
        _png(p, rng.integers(0, 255, (48, 64, 3), dtype=np.uint8))
    bad = parser.image_paths[2]
    with open(bad, "wb") as f:
        f.write(b"this is no PNG")
    params, _, _ = test_gsplat.make_splats(200, 8)
    with torch.no_grad():
        params["means"][:, :2] = torch.rand(200, 2) * 2 - 1
        params["means"][:, 2] = 4.0 + torch.rand(200)
        params["scales"][:] = -3.0
        params["scales"][:, 0] = -1.5  # elongated: a Needle Shape above 0
        params["opacities"][:] = 2.0
    path = str(tmp_path / "run" / "training_log.h5")
    os.makedirs(os.path.dirname(path))
    logger = TrainingLogger(path, snapshot_interval=0)
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    logger.log_gsplat_cameras(parser, test_every=0)
    logger.close()

    def analyze(out):
        run = subprocess.run([exe, "analyze", path, "--scores=coverage,needle,shape",
                              f"--output={out}"], capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stdout + run.stderr
        with open(os.path.join(out, "scores.csv")) as f:
            rows = list(csv.DictReader(f))
        return run.stdout + run.stderr, rows

    text, rows = analyze(str(tmp_path / "bad"))
    assert bad in text or os.path.basename(bad) in text, text
    assert len(rows) == 200
    coverage = np.array([float(r["ViewCoverage"]) for r in rows])
    assert coverage.max() == 1.0  # every view counts for coverage, the bad one too
    os.remove(bad)
    text2, rows2 = analyze(str(tmp_path / "absent"))
    for key in ("ViewCoverage", "NeedleScore", "NeedleShape"):
        assert [r[key] for r in rows] == [r[key] for r in rows2], key
    assert any(float(r["NeedleScore"]) > 0 for r in rows)
