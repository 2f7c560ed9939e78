# SPDX-License-Identifier: BSD-3-Clause
"""The training-loop side of the logger: iteration bookkeeping, metrics, cameras and
snapshots at an interval. Id tracking lives in the trackers (gs3d.py, gsplat_hooks.py)."""

import math
import time

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
    ``deflate``, ``snapshot_deflate`` (default 0: snapshots uncompressed), ``chunk_rows``
    and ``flush_every_s`` are passed to TrainingLogWriter.
    """

    def __init__(self, path, scene="", sh_degree=3, iterations=30000,
                 snapshot_interval=DEFAULT_SNAPSHOT_INTERVAL, snapshot_sh_rest=True,
                 snapshot_statistics=True, deflate=1, chunk_rows=4096, producer=None,
                 flush_every_s=300.0, snapshot_deflate=0):
        self.writer = TrainingLogWriter(path, scene=scene, sh_degree=sh_degree,
                                        iterations=iterations, producer=producer,
                                        deflate=deflate, chunk_rows=chunk_rows,
                                        flush_every_s=flush_every_s,
                                        snapshot_deflate=snapshot_deflate)
        self.path = self.writer.path
        self.snapshot_interval = int(snapshot_interval) if snapshot_interval else 0
        self.snapshot_sh_rest = snapshot_sh_rest
        self.snapshot_statistics = snapshot_statistics
        self.iteration = 0
        self.tracker = None
        self._start = time.perf_counter()
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
        if not test:
            self.iteration = int(iteration)
        if num_gaussians is None:
            num_gaussians = self.tracker.count() if self.tracker is not None else -1
        if elapsed_s is None:
            elapsed_s = time.perf_counter() - self._start
        self.writer.append_metrics(iteration, num_gaussians=num_gaussians, loss=loss, l1=l1,
                                   psnr=psnr, ssim=ssim, lpips=lpips, elapsed_s=elapsed_s,
                                   test=test)
        self.time_spent_s += time.perf_counter() - t0

    def log_events(self, kind, parents, children=None, iteration=None):
        """Records events of one kind at the current (or given) iteration."""
        t0 = time.perf_counter()
        it = self.iteration if iteration is None else iteration
        self.writer.append_events(it, kind, parents, children)
        self.time_spent_s += time.perf_counter() - t0

    # -- cameras -----------------------------------------------------------------------
    def log_cameras(self, names, widths, heights, fx, fy, cx, cy, world_to_camera,
                    splits=None, images=None):
        """Writes /cameras from columns (world_to_camera: [V,4,4], OpenCV convention)."""
        self.writer.write_cameras(names, widths, heights, fx, fy, cx, cy, world_to_camera,
                                  splits, images)

    def log_3dgs_cameras(self, train_cameras, test_cameras=(), image_paths=None,
                         embed_images=False):
        """Writes /cameras from the original trainer's Camera objects
        (scene.getTrainCameras(), scene.getTestCameras()).

        The world-to-camera matrix is world_view_transform transposed (the trainer stores
        it column-major for the rasteriser); fx = W / (2 tan(FoVx/2)), principal point at
        the image centre, as the rasteriser assumes. image_paths: optional dict name ->
        path stored as the image path; embed_images: store original_image in /images.
        """
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
                self.writer.write_image(str(cam.image_name), cam.original_image)
                images.append("/images/" + str(cam.image_name))
            elif image_paths is not None:
                images.append(str(image_paths.get(cam.image_name, "")))
            else:
                images.append(str(cam.image_name))
        self.log_cameras(names, widths, heights, fx, fy, cx, cy, np.array(w2c).reshape(-1, 4, 4),
                         splits, images)

    # -- snapshots ---------------------------------------------------------------------
    def should_snapshot(self, iteration):
        return self.snapshot_interval > 0 and int(iteration) % self.snapshot_interval == 0

    def step(self, iteration):
        """Call at the end of each iteration: writes a snapshot at the interval."""
        if self.should_snapshot(iteration):
            self.snapshot(iteration)

    def snapshot(self, iteration):
        """Writes a snapshot of the tracked model now (and flushes the file)."""
        if self.tracker is None:
            raise RuntimeError(f"{self.path}: no model is tracked (call track_3dgs or track_gsplat)")
        t0 = time.perf_counter()
        self.tracker.write_snapshot(int(iteration))
        self.time_spent_s += time.perf_counter() - t0

    def flush(self):
        self.writer.flush()

    def close(self):
        if self.tracker is not None:
            self.tracker.uninstall()
        self.writer.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
