# SPDX-License-Identifier: BSD-3-Clause
"""The training-loop side of the logger: iteration bookkeeping, metrics, cameras and
snapshots at an interval. Id tracking lives in the trackers (gs3d.py, gsplat_hooks.py)."""

import contextlib
import math
import os
import re
import sys
import time
import traceback
import warnings

import numpy as np

from .writer import TrainingLogWriter, to_numpy

__all__ = ["TrainingLogger", "DEFAULT_SNAPSHOT_INTERVAL"]

#: Snapshot every this many iterations by default (60 snapshots over 30k iterations).
DEFAULT_SNAPSHOT_INTERVAL = 500


class TrainingLogger:
    """Logs one training run into a Vis4GS training log.

    Call log_metrics(iteration, ...) every iteration before densification (it also tells
    the id tracker which iteration its events belong to) and step(iteration) at the end of
    each iteration (it writes a snapshot every ``snapshot_interval`` iterations). Metric
    values may be python floats or one-element tensors; values not measured are None
    (stored as NaN). ``elapsed_s`` defaults to the wall time since the logger was created.
    ``deflate``, ``snapshot_deflate`` (default 0: snapshots uncompressed; 1-9: gzip level),
    ``snapshot_sh_degree`` (default None: every SH degree), ``snapshot_sh_float16`` (default
    False), ``chunk_rows``, ``flush_every_s`` and ``swmr`` (default True: format version 2
    in SWMR mode, readable while the run writes it, from the first step on; with the default
    ``write_to_temporary`` the live file is ``<path>.tmp``, which `vis4gs view path --follow`
    finds) are passed to TrainingLogWriter. ``live_flush_s`` (default 0.5; None: off): with
    swmr, step() also flushes when this many seconds passed since the last flush, so that
    new metrics and events show within about 2 s (the cost: performance-history.md).

    Disk: after each snapshot the size of the whole run is projected (the snapshots so far,
    plus the last one's size for each snapshot still planned up to ``iterations``); a
    warning says so once when it exceeds the free space of the log's disk.
    ``snapshot_budget_bytes`` (default None: no budget): when the projection exceeds it, the
    snapshot interval doubles (as often as needed), so that the run thins its later
    snapshots instead of filling the disk; the snapshots written stay (HDF5 does not give
    freed space back in a file written crash-safely, see the writer).

    ``start_iteration``: the iteration of the checkpoint a resumed run starts from (3DGS
    ``--start_checkpoint``). The row-to-id map of the checkpoint is not in the trainer's
    checkpoint, so a resumed run starts a clear new log: its ids restart at 0 for the
    checkpoint's Gaussians, its first snapshot is the checkpoint's iteration and the root
    attribute ``start_iteration`` says so. An existing log at ``path`` is kept, renamed to
    ``<name>.before-<start_iteration>.h5`` (a warning names it).

    Failures of the disk never reach the training loop: the log is written as
    ``<path>.tmp`` and renamed onto ``path`` at close() (``write_to_temporary``, default True;
    a killed run leaves the temporary, valid up to its last flush).
    When the file cannot be created or written (a full disk, a read-only folder: any
    OSError), one RuntimeWarning names the path and the problem, logging stops (every later
    call does nothing, ``failure`` says why), the temporary is removed and an earlier log at
    ``path`` stays as it was. Errors of the caller (wrong shapes: ValueError) still raise.
    """

    def __init__(self, path, scene="", sh_degree=3, iterations=30000,
                 snapshot_interval=DEFAULT_SNAPSHOT_INTERVAL, snapshot_sh_rest=True,
                 snapshot_statistics=True, deflate=1, chunk_rows=4096, producer=None,
                 flush_every_s=300.0, snapshot_deflate=0, start_iteration=0,
                 snapshot_sh_degree=None, snapshot_sh_float16=False, snapshot_budget_bytes=None,
                 write_to_temporary=True, swmr=True, live_flush_s=0.5):
        self.start_iteration = int(start_iteration)
        self.path = os.fspath(path)
        #: why logging stopped ("PATH: problem"), None while it works
        self.failure = None
        self.writer = _StoppedWriter(self.path)
        with self._io("creating the log"):
            if self.start_iteration > 0 and os.path.exists(path):
                root, ext = os.path.splitext(self.path)
                kept = f"{root}.before-{self.start_iteration}{ext or '.h5'}"
                os.replace(path, kept)
                warnings.warn(f"vis4gs_logger: resuming at iteration {self.start_iteration}: "
                              f"the previous log is kept as {kept}; {path} is a new log",
                              RuntimeWarning, stacklevel=2)
            self.writer = TrainingLogWriter(path, scene=scene, sh_degree=sh_degree,
                                            iterations=iterations, producer=producer,
                                            deflate=deflate, chunk_rows=chunk_rows,
                                            flush_every_s=flush_every_s,
                                            snapshot_deflate=snapshot_deflate,
                                            start_iteration=self.start_iteration,
                                            snapshot_sh_degree=snapshot_sh_degree,
                                            snapshot_sh_float16=snapshot_sh_float16,
                                            write_to_temporary=write_to_temporary,
                                            swmr=swmr)
        self.live_flush_s = live_flush_s
        self.snapshot_interval = int(snapshot_interval) if snapshot_interval else 0
        self.iterations = int(iterations)
        self.snapshot_budget_bytes = snapshot_budget_bytes
        self._disk_warned = False
        self.snapshot_sh_rest = snapshot_sh_rest
        self.snapshot_statistics = snapshot_statistics
        self.iteration = self.start_iteration
        #: the iteration of the last step() call (None before the first)
        self.last_step = None
        self.tracker = None
        self._start = time.perf_counter()
        #: snapshots that could not be written ("iteration N: why")
        self.snapshot_failures = []
        #: seconds spent inside the logger (for measuring its overhead)
        self.time_spent_s = 0.0

    # -- iteration and metrics ---------------------------------------------------------
    def set_iteration(self, iteration):
        """Sets the iteration that events recorded from now on belong to."""
        self.iteration = int(iteration)

    def log_metrics(self, iteration, loss=None, l1=None, psnr=None, ssim=None, lpips=None,
                    num_gaussians=None, elapsed_s=None, test=False):
        """Appends a row to /metrics (test=True: /metrics/test)."""
        t0 = time.perf_counter()
        if not test and (self.last_step is None or int(iteration) > self.last_step):
            self.iteration = int(iteration)  # metrics of an ended step do not move it back
        if num_gaussians is None:
            num_gaussians = self.tracker.count() if self.tracker is not None else -1
        if elapsed_s is None:
            elapsed_s = time.perf_counter() - self._start
        with self._io("writing metrics"):  # a timed flush writes
            self.writer.append_metrics(iteration, num_gaussians=num_gaussians, loss=loss,
                                       l1=l1, psnr=psnr, ssim=ssim, lpips=lpips,
                                       elapsed_s=elapsed_s, test=test)
        self.time_spent_s += time.perf_counter() - t0

    def log_events(self, kind, parents, children=None, iteration=None):
        """Records events of one kind at the current (or given) iteration."""
        t0 = time.perf_counter()
        it = self.iteration if iteration is None else iteration
        self.writer.append_events(it, kind, parents, children)
        self.time_spent_s += time.perf_counter() - t0

    # -- cameras -----------------------------------------------------------------------
    def log_cameras(self, names, widths, heights, fx, fy, cx, cy, world_to_camera,
                    splits=None, images=None, source=None, image_dir=None):
        """Writes /cameras from columns (world_to_camera: [V,4,4], OpenCV convention).
        images: paths of the training images (absolute, or relative to the current
        directory); they are stored relative to the log so that ``vis4gs view LOG`` finds
        them without flags. source / image_dir: the scene's cameras.json or COLMAP folder
        and image folder, stored as attributes of /cameras."""
        if images is not None:
            images = [self._relative_image(p) for p in images]
        with self._io("writing the cameras"):
            self.writer.write_cameras(names, widths, heights, fx, fy, cx, cy, world_to_camera,
                                      splits, images, source=source, image_dir=image_dir)

    def _relative_image(self, image):
        image = str(image)
        if not image or image.startswith("/images/"):
            return image
        base = os.path.dirname(os.path.abspath(self.path))
        return os.path.relpath(os.path.abspath(image), base)

    def log_gsplat_cameras(self, parser, test_every=None):
        """Writes /cameras from gsplat's COLMAP ``Parser`` (examples/datasets/colmap.py):
        every image, split as simple_trainer's Dataset splits it (index % test_every == 0:
        test), intrinsics of the (undistorted) camera, the Parser's image paths."""
        test_every = parser.test_every if test_every is None else int(test_every)
        c2w = to_numpy(parser.camtoworlds, np.float64).reshape(-1, 4, 4)
        names, widths, heights, fx, fy, cx, cy, splits = ([] for _ in range(8))
        for i, name in enumerate(parser.image_names):
            cam = parser.camera_ids[i]
            k = to_numpy(parser.Ks_dict[cam], np.float64)
            w, h = parser.imsize_dict[cam]
            names.append(str(name))
            widths.append(int(w))
            heights.append(int(h))
            fx.append(k[0, 0])
            fy.append(k[1, 1])
            cx.append(k[0, 2])
            cy.append(k[1, 2])
            splits.append(1 if test_every > 0 and i % test_every == 0 else 0)
        image_dir = os.path.dirname(parser.image_paths[0]) if len(parser.image_paths) else None
        self.log_cameras(names, widths, heights, fx, fy, cx, cy, np.linalg.inv(c2w), splits,
                         list(parser.image_paths), source=getattr(parser, "data_dir", None),
                         image_dir=image_dir)

    def log_3dgs_cameras(self, train_cameras, test_cameras=(), image_paths=None,
                         embed_images=False, images_dir=None, source=None):
        """Writes /cameras from the original trainer's Camera objects
        (scene.getTrainCameras(), scene.getTestCameras()).

        The world-to-camera matrix is world_view_transform transposed (the trainer stores
        it column-major for the rasteriser); fx = W / (2 tan(FoVx/2)), principal point at
        the image centre, as the rasteriser assumes. images_dir: the scene's image folder
        (``os.path.join(dataset.source_path, dataset.images)``): the trainer's image names
        have no extension, the file of each is looked up there. image_paths: optional dict
        name -> path instead; embed_images: store original_image in /images. source: the
        scene folder (``dataset.source_path``), recorded as an attribute.
        """
        if image_paths is None and images_dir is not None:
            image_paths = _files_by_stem(images_dir)
        cams = list(train_cameras) + list(test_cameras)
        names, widths, heights, fx, fy, cx, cy, w2c, splits, images = ([] for _ in range(10))
        for i, cam in enumerate(cams):
            w, h = int(cam.image_width), int(cam.image_height)
            names.append(str(cam.image_name))
            widths.append(w)
            heights.append(h)
            fx.append(w / (2.0 * math.tan(float(cam.FoVx) / 2.0)))
            fy.append(h / (2.0 * math.tan(float(cam.FoVy) / 2.0)))
            cx.append(w / 2.0)
            cy.append(h / 2.0)
            if hasattr(cam, "world_view_transform"):
                w2c.append(to_numpy(cam.world_view_transform, np.float64).T)
            else:  # R is stored transposed (camera-to-world rotation), T world-to-camera
                m = np.eye(4)
                m[:3, :3] = to_numpy(cam.R, np.float64).T
                m[:3, 3] = to_numpy(cam.T, np.float64)
                w2c.append(m)
            splits.append(0 if i < len(list(train_cameras)) else 1)
            if embed_images and getattr(cam, "original_image", None) is not None:
                with self._io("writing the images"):
                    self.writer.write_image(str(cam.image_name), cam.original_image)
                images.append("/images/" + str(cam.image_name))
            elif image_paths is not None:
                images.append(str(image_paths.get(cam.image_name, "")))
            else:
                images.append("")  # a bare image name would resolve to nothing
        self.log_cameras(names, widths, heights, fx, fy, cx, cy, np.array(w2c).reshape(-1, 4, 4),
                         splits, images, source=source, image_dir=images_dir)

    # -- snapshots ---------------------------------------------------------------------
    def should_snapshot(self, iteration):
        return self.snapshot_interval > 0 and int(iteration) % self.snapshot_interval == 0

    def step(self, iteration):
        """Call at the end of each iteration: writes a snapshot at the interval, and events
        recorded from now on belong to iteration + 1 (until log_metrics names a later one),
        so that they carry their step's iteration however seldom metrics are logged.

        The snapshot of an iteration that already has one is not written again: gsplat's
        loop starts at step 0, after track_gsplat() wrote the snapshot of iteration 0 (and a
        resumed run starts at the checkpoint's iteration, which track_* wrote too). A
        snapshot that cannot be written (e.g. a full disk) is a warning, not an exception:
        the training goes on, and close() tries the final one again."""
        iteration = int(iteration)
        self.last_step = iteration
        self.iteration = iteration + 1
        if self.writer.swmr and not self.writer._file.swmr_mode:
            with self._io("entering SWMR mode"):  # the loop runs: readers may follow
                self.writer.start_swmr()
        if self.should_snapshot(iteration) and iteration != self.writer.last_snapshot_iteration:
            self._snapshot_or_warn(iteration)
        elif self.writer.swmr and self.live_flush_s is not None \
                and time.monotonic() - self.writer.last_flush >= self.live_flush_s:
            # For readers following the log: new metrics and events within about 2 s.
            t0 = time.perf_counter()
            with self._io("flushing"):
                self.writer.flush()
            self.time_spent_s += time.perf_counter() - t0

    def _snapshot_or_warn(self, iteration):
        try:
            self.snapshot(iteration)
        except Exception as error:  # noqa: BLE001 - never stop the training for the log
            self.snapshot_failures.append(f"iteration {iteration}: {error}")
            if len(self.snapshot_failures) == 1:
                warnings.warn(f"vis4gs_logger: {self.path}: the snapshot of iteration "
                              f"{iteration} could not be written ({type(error).__name__}: "
                              f"{error}); training goes on, later failures are counted in "
                              "snapshot_failures", RuntimeWarning, stacklevel=3)

    def snapshot(self, iteration):
        """Writes a snapshot of the tracked model now (and flushes the file)."""
        if self.tracker is None:
            raise RuntimeError(f"{self.path}: no model is tracked (call track_3dgs or track_gsplat)")
        if self.failure is not None:
            return
        t0 = time.perf_counter()
        before = self.writer.snapshot_bytes
        with self._io(f"writing the snapshot of iteration {int(iteration)}"):
            self.tracker.write_snapshot(int(iteration))
        if self.failure is None:
            self._plan_disk(int(iteration), self.writer.snapshot_bytes - before)
        self.time_spent_s += time.perf_counter() - t0

    def projected_bytes(self, iteration, last_bytes):
        """Snapshot bytes of the whole run if every snapshot still planned after
        ``iteration`` is as large as the last (``last_bytes``)."""
        left = 0
        if self.snapshot_interval > 0 and self.iterations > iteration:
            left = (self.iterations - iteration) // self.snapshot_interval + 1
        return self.writer.snapshot_bytes + left * last_bytes

    def _plan_disk(self, iteration, last_bytes):
        import shutil

        projected = self.projected_bytes(iteration, last_bytes)
        budget = self.snapshot_budget_bytes
        while budget is not None and self.snapshot_interval > 0 and projected > budget \
                and self.snapshot_interval < max(1, self.iterations):
            self.snapshot_interval *= 2
            projected = self.projected_bytes(iteration, last_bytes)
            warnings.warn(f"vis4gs_logger: {self.path}: the snapshots would take "
                          f"{projected / 1e9:.2f} GB beyond the budget of {budget / 1e9:.2f} GB: "
                          f"snapshot interval now {self.snapshot_interval}", RuntimeWarning,
                          stacklevel=4)
        if not self._disk_warned:
            free = shutil.disk_usage(os.path.dirname(os.path.abspath(self.path))).free
            if projected - self.writer.snapshot_bytes > free:
                self._disk_warned = True
                warnings.warn(f"vis4gs_logger: {self.path}: the log is projected to grow by "
                              f"{(projected - self.writer.snapshot_bytes) / 1e9:.2f} GB "
                              f"({last_bytes / 1e6:.1f} MB per snapshot) but its disk has "
                              f"{free / 1e9:.2f} GB free: pass snapshot_budget_bytes, "
                              "snapshot_sh_degree, snapshot_sh_float16 or a larger "
                              "snapshot_interval", RuntimeWarning, stacklevel=4)

    def flush(self):
        with self._io("flushing the log"):
            self.writer.flush()

    @contextlib.contextmanager
    def _io(self, what):
        """Runs a write; an OSError (a full disk, a read-only folder, a file HDF5 cannot
        write) stops the logging instead of the training (see the class)."""
        try:
            yield
        except Exception as error:  # noqa: BLE001 - sorted below
            if not _is_io_error(error):
                raise
            self._stop(what, error)

    def _stop(self, what, error):
        self.failure = f"{self.path}: {what} failed: {_problem(error)}"
        writer, self.writer = self.writer, _StoppedWriter(self.path)
        writer.abandon()
        earlier = "an earlier log there is kept as it was" if os.path.exists(self.path) \
            else "no log is written"
        warnings.warn(f"vis4gs_logger: {self.failure}; logging stops ({earlier}), the training "
                      "goes on", RuntimeWarning, stacklevel=_caller_level())

    def final_iteration(self):
        """The iteration of the model as it is now: the last step(), else the last
        iteration log_metrics named; None when neither was called."""
        if self.last_step is not None:
            return self.last_step
        return self.iteration if self.iteration > self.start_iteration else None

    def close(self):
        """Writes the snapshot of the final model (the last step's, when the interval did
        not write it: gsplat's loop ends at max_steps - 1, a 3DGS run's length need not be
        a multiple of the interval), then closes the file."""
        if self.failure is not None or self.writer._file is None:
            if self.tracker is not None:
                self.tracker.uninstall()
                self.tracker = None
            return
        final = self.final_iteration()
        if (self.tracker is not None and final is not None
                and final > self.writer.last_snapshot_iteration):
            self._snapshot_or_warn(final)
        if self.tracker is not None:
            self.tracker.uninstall()
        with self._io("closing the log"):
            self.writer.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def _files_by_stem(folder):
    """name without extension -> path of the file in folder (3DGS's image_name is the
    file name without its extension; its readers take the first file of each stem)."""
    files = {}
    for entry in sorted(os.listdir(folder)):
        path = os.path.join(folder, entry)
        if os.path.isfile(path):
            files.setdefault(os.path.splitext(entry)[0], path)
            files[entry] = path  # names given with their extension
    return files


def _caller_level():
    """The stacklevel of warnings.warn that names the trainer's line, the first frame outside
    this package and contextlib (which the failures pass through)."""
    package = os.path.dirname(os.path.abspath(__file__))
    level, frame = 1, sys._getframe(1)
    while frame is not None and (frame.f_code.co_filename.startswith(package)
                                 or frame.f_code.co_filename == contextlib.__file__):
        level += 1
        frame = frame.f_back
    return level


def _is_io_error(error):
    """An OSError, or any error raised inside h5py (HDF5 reports a failed write as a
    RuntimeError or ValueError: "Unable to flush file's cached information (file write
    failed: ..., errno = 28, ...)")."""
    if isinstance(error, OSError):
        return True
    return any("h5py" in frame.filename for frame in traceback.extract_tb(error.__traceback__))


def _problem(error):
    """The problem in a few words: the system's message for an errno that HDF5 reports
    inside its own text, then HDF5's first line, then the error as Python says it."""
    text = str(error)
    found = re.search(r"errno = (\d+)", text)
    if isinstance(error, OSError) and error.errno:
        return os.strerror(error.errno)
    if found:
        return os.strerror(int(found.group(1)))
    return f"{type(error).__name__}: {text.splitlines()[0] if text else ''}"


class _StoppedWriter:
    """Takes the writer's place when logging stopped (or before it started): the trackers
    and the logger call it as they call the writer, and nothing is written."""

    last_snapshot_iteration = -1
    snapshot_bytes = 0
    swmr = False
    _file = None

    def __init__(self, path):
        self.path = path

    def abandon(self):
        pass

    def __getattr__(self, name):
        return lambda *args, **kwargs: None
