# SPDX-License-Identifier: BSD-3-Clause
"""The logger on the original trainer's own GaussianModel (graphdeco-inria/gaussian-
splatting scene/gaussian_model.py, loaded from a copy by upstream.py on the CPU; skipped
with a message when there is none).

The loop is train.py's, from iteration 1, with the README's lines in it; the model is
created by its own create_from_pcd (simple_knn's distCUDA2, CUDA only, replaced by the
same mean squared distance to the 3 nearest neighbours in torch). The rasteriser (CUDA
only) is replaced by a pinhole projection giving what render() gives the loop:
viewspace_points (whose gradient feeds add_densification_stats), visibility_filter and
radii. The lineage check: _features_rest[:, -1, 2] holds each row's root id; the loss
never reads _features_rest, so Adam never changes it, while densify_and_clone / _split
copy it into the children and prune_points removes it with its row."""

import inspect
import os
import types

import numpy as np
import pytest
import torch

import upstream
from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot, snapshot_iterations
from vis4gs_logger import CLONE, PRUNE, SPLIT

GaussianModel, REDIRECTED = upstream.load_3dgs_model()  # skips the module without a copy

WIDTH, HEIGHT, FOCAL = 64, 48, 60.0
#: the current densify_and_prune(max_grad, min_opacity, extent, max_screen_size, radii)
#: (since 2024-10; train.py passes render()'s radii), or the older one without radii
TAKES_RADII = "radii" in inspect.signature(GaussianModel.densify_and_prune).parameters
#: iterations of the run: not a multiple of the snapshot interval (10), so that the last
#: snapshot is the one close() writes of the final model
ITERATIONS = 83


def dist_cuda2(points):
    """simple_knn's distCUDA2: mean squared distance to the 3 nearest other points."""
    d2 = torch.cdist(points, points) ** 2
    d2.fill_diagonal_(float("inf"))
    return d2.topk(3, largest=False).values.mean(dim=1)


def optimization_params(iterations):
    """arguments/__init__.py OptimizationParams defaults, with the densification schedule
    shortened to fit a test (same relations: interval, reset, from/until)."""
    return types.SimpleNamespace(
        iterations=iterations, position_lr_init=0.00016, position_lr_final=0.0000016,
        position_lr_delay_mult=0.01, position_lr_max_steps=iterations, feature_lr=0.0025,
        opacity_lr=0.025, scaling_lr=0.005, rotation_lr=0.001, exposure_lr_init=0.01,
        exposure_lr_final=0.001, exposure_lr_delay_steps=0, exposure_lr_delay_mult=0.0,
        percent_dense=0.01, lambda_dssim=0.2, densification_interval=10,
        opacity_reset_interval=40, densify_from_iter=5, densify_until_iter=70,
        densify_grad_threshold=0.0002)


def render(g, weights, directions, push):
    """What render() returns to the loop, and a loss with fixed per-root weights."""
    means = g.get_xyz
    z = means[:, 2:3]
    xy = FOCAL * means[:, :2] / z + torch.tensor([WIDTH / 2.0, HEIGHT / 2.0])
    viewspace = torch.cat([xy, torch.zeros_like(z)], dim=1)
    viewspace.retain_grad()
    radius = (3.0 * FOCAL * g.get_scaling.max(dim=1).values / z[:, 0]).ceil()
    radii = torch.where((xy[:, 0] > 0) & (xy[:, 0] < WIDTH), radius, torch.zeros_like(radius))
    root = g._features_rest[:, -1, 2].detach().long()
    image_term = (viewspace[:, :2] * (weights[root, None] * directions[root])).sum()
    loss = image_term + 1e-3 * (push[root, None] * g._opacity).sum() \
        + 1e-3 * (g._features_dc ** 2).sum()
    return loss, viewspace, radii > 0, radii


def root_through_events(events, n0):
    root = {i: i for i in range(n0)}
    for k, p, c in zip(events[1], events[2], events[3]):
        if k in (CLONE, SPLIT):
            root[int(c)] = root[int(p)]
    return root


class Run:
    """The scene, the model and the loss weights of one test run."""

    def __init__(self, tmp_path, n0=300, iterations=ITERATIONS):
        self.n0, self.iterations = n0, iterations
        g = torch.Generator().manual_seed(1)
        self.pcd = types.SimpleNamespace(points=(torch.rand(n0, 3, generator=g) * 2 - 1
                                                 + torch.tensor([0.0, 0.0, 4.0])).numpy(),
                                         colors=torch.rand(n0, 3, generator=g).numpy())
        self.cams = [types.SimpleNamespace(image_name=f"view{i}") for i in range(2)]
        upstream.sys.modules["scene.gaussian_model"].distCUDA2 = dist_cuda2
        gaussians = GaussianModel(3)
        gaussians.create_from_pcd(self.pcd, self.cams, spatial_lr_scale=1.0)
        with torch.no_grad():
            gaussians._features_rest[:, -1, 2] = torch.arange(n0, dtype=torch.float32)
            # half small (cloned), half large (split) against percent_dense * extent = 0.01
            small = torch.rand(n0, generator=g) < 0.5
            gaussians._scaling[:] = torch.where(small[:, None], np.log(0.004), np.log(0.05))
        self.weights = torch.rand(n0, generator=g) * 2.5e-4  # around the threshold
        self.directions = torch.nn.functional.normalize(torch.randn(n0, 2, generator=g), dim=1)
        self.push = torch.where(torch.rand(n0, generator=g) < 0.3, 1.0, -0.2)
        with torch.no_grad():  # the pushed-down ones start near the prune threshold
            gaussians._opacity[self.push > 0] = float(np.log(0.008 / 0.992))
        self.opt = optimization_params(iterations)
        gaussians.training_setup(self.opt)
        self.gaussians = gaussians
        source = tmp_path / "scene"
        (source / "images").mkdir(parents=True)
        for cam in self.cams:
            (source / "images" / f"{cam.image_name}.png").write_bytes(b"")
            cam.image_width, cam.image_height, cam.FoVx, cam.FoVy = WIDTH, HEIGHT, 1.0, 0.8
            cam.world_view_transform = torch.eye(4)
        self.dataset = types.SimpleNamespace(model_path=str(tmp_path), source_path=str(source),
                                             sh_degree=3, images="images")
        self.scene = types.SimpleNamespace(getTrainCameras=lambda: self.cams[:1],
                                           getTestCameras=lambda: self.cams[1:])
        self.readme = upstream.readme_fragments("## Original 3DGS")

    def restart_from(self, checkpoint):
        """train.py with --start_checkpoint: a new model, training_setup, restore."""
        gaussians = GaussianModel(3)
        gaussians.create_from_pcd(self.pcd, self.cams, spatial_lr_scale=1.0)
        gaussians.training_setup(self.opt)
        (model_params, first_iter) = torch.load(checkpoint)
        gaussians.restore(model_params, self.opt)
        self.gaussians = gaussians
        return first_iter

    def train(self, first_iter, last_iter, root_value, checkpoint=None):
        """train.py's loop from first_iter + 1 (its `first_iter += 1`) to last_iter with
        the README's lines; after every iteration, every row's carried root equals
        root_value(root of its id through the logged parents)."""
        gaussians, opt, readme = self.gaussians, self.opt, self.readme
        ns = {"os": os, "dataset": self.dataset, "opt": opt, "scene": self.scene,
              "gaussians": gaussians, "first_iter": first_iter}
        exec(readme[""], ns)
        exec(readme[TRACK], ns)
        logger, tracker = ns["logger"], ns["tracker"]
        logger.snapshot_interval = 10  # (default 500) to see several in 83 iterations
        n_start = len(tracker.ids)
        first_iter += 1  # train.py
        all_events = []
        for iteration in range(first_iter, last_iter + 1):
            gaussians.update_learning_rate(iteration)
            loss, viewspace_point_tensor, visibility_filter, radii = render(
                gaussians, self.weights, self.directions, self.push)
            Ll1 = loss.detach()
            loss.backward()
            ns.update(iteration=iteration, loss=loss, Ll1=Ll1)
            exec(readme["in the loop, right after loss.backward() (before densification):"], ns)
            with torch.no_grad():
                if iteration < opt.densify_until_iter:
                    gaussians.max_radii2D[visibility_filter] = torch.max(
                        gaussians.max_radii2D[visibility_filter], radii[visibility_filter])
                    gaussians.add_densification_stats(viewspace_point_tensor, visibility_filter)
                    if iteration > opt.densify_from_iter and iteration % opt.densification_interval == 0:
                        size_threshold = 20 if iteration > opt.opacity_reset_interval else None
                        extra = (radii,) if TAKES_RADII else ()
                        gaussians.densify_and_prune(opt.densify_grad_threshold, 0.005,
                                                    1.0, size_threshold, *extra)
                    if iteration % opt.opacity_reset_interval == 0:
                        gaussians.reset_opacity()
                if iteration < opt.iterations:
                    gaussians.exposure_optimizer.step()
                    gaussians.exposure_optimizer.zero_grad(set_to_none=True)
                    gaussians.optimizer.step()
                    gaussians.optimizer.zero_grad(set_to_none=True)
                if checkpoint is not None and iteration == checkpoint[1]:
                    torch.save((gaussians.capture(), iteration), checkpoint[0])
            pend = logger.writer._pending_events
            if pend:
                all_events.append(tuple(np.concatenate([e[j] for e in pend]) for j in range(4)))
            if iteration in (40, self.iterations):  # train.py's test_iterations
                ns.update(l1_test=0.1, psnr_test=25.0)
                exec(readme["in training_report, where the test views are evaluated:"], ns)
            exec(readme["last line of the loop body:"], ns)
            events = tuple(np.concatenate([e[j] for e in all_events]) if all_events
                           else np.zeros(0) for j in range(4))
            root_of = root_through_events(events, n_start)
            stored = gaussians._features_rest[:, -1, 2].detach().long().tolist()
            ids = tracker.ids.tolist()
            assert len(ids) == len(stored) == len(set(ids))
            for row, gid in enumerate(ids):
                assert stored[row] == root_value(root_of[gid]), \
                    f"iteration {iteration}, row {row}, id {gid}"
        final = tracker.ids.clone()
        self.final_means = gaussians.get_xyz.detach().clone()
        exec(readme["after the loop:"], ns)
        assert tracker.warnings == []
        return ns["logger"].path, final, n_start


TRACK = ("after `gaussians.training_setup(opt)` and, for --start_checkpoint, "
         "`gaussians.restore(...)`:")


def test_original_gaussian_model_train_loop(tmp_path):
    torch.manual_seed(0)
    run = Run(tmp_path)
    n0, iterations = run.n0, run.iterations
    path, final, _ = run.train(0, iterations, root_value=lambda r: r)
    with open_log(path) as f:
        np.testing.assert_array_equal(f["metrics/test/iteration"][:], [40, iterations])
        assert list(f["cameras/split"][:]) == [0, 1]
        for rel in f["cameras/image"].asstr()[:]:
            assert os.path.isfile(os.path.join(tmp_path, rel)), rel
    check_format(path)
    events = read_events(path)
    kinds = set(events[1].tolist())
    assert kinds == {CLONE, SPLIT, PRUNE}, kinds
    alive, _ = replay_genealogy(events, n0)
    assert alive == set(final.tolist())
    with open_log(path) as f:
        snaps = snapshot_iterations(f)
        assert iterations % 10 != 0
        assert snaps == list(range(0, iterations + 1, 10)) + [iterations]
        assert f["metrics/iteration"][0] == 1
        # the last snapshot is the final model: its ids, and each id's position
        last = read_snapshot(f, iterations)
        order = np.argsort(final.numpy())
        np.testing.assert_array_equal(last["id"], final.numpy()[order])
        np.testing.assert_array_equal(last["position"], run.final_means.numpy()[order])
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["events"] == len(events[0])
        assert all(os.path.isfile(os.path.join(tmp_path, p)) for p in info["camera_images"])
    counts = {k: int((events[1] == k).sum()) for k in (CLONE, SPLIT, PRUNE)}
    print(f"original 3DGS {GaussianModel.commit} (densify_and_prune with radii: "
          f"{TAKES_RADII}): {REDIRECTED} device redirections; "
          f"{n0} -> {len(final)} Gaussians; events clone {counts[CLONE]}, split "
          f"{counts[SPLIT]}, prune {counts[PRUNE]}; snapshots {snaps}")


def test_original_gaussian_model_resumed_from_checkpoint(tmp_path):
    """Checkpoint at 35, run on until 52 (stopped there), --start_checkpoint: a clear new
    log from 35 whose ids are the checkpoint's rows; the old log is kept."""
    torch.manual_seed(0)
    run = Run(tmp_path)
    checkpoint = str(tmp_path / "chkpnt35.pth")
    run.train(0, 52, root_value=lambda r: r, checkpoint=(checkpoint, 35))
    first_iter = run.restart_from(checkpoint)
    assert first_iter == 35
    roots_at_checkpoint = run.gaussians._features_rest[:, -1, 2].detach().long().tolist()
    with pytest.warns(RuntimeWarning, match="before-35"):
        path, final, n_start = run.train(first_iter, run.iterations,
                                         root_value=lambda r: roots_at_checkpoint[r])
    assert n_start == len(roots_at_checkpoint)
    check_format(path)
    events = read_events(path)
    assert events[0].min() > 35 and {CLONE, SPLIT} <= set(events[1].tolist())
    alive, _ = replay_genealogy(events, n_start)
    assert alive == set(final.tolist())
    with open_log(path) as f:
        assert int(f.attrs["start_iteration"]) == 35
        assert snapshot_iterations(f) == [35, 40, 50, 60, 70, 80, ITERATIONS]
        assert read_snapshot(f, 35)["id"].tolist() == list(range(n_start))
        assert f["metrics/iteration"][0] == 36
    with open_log(str(tmp_path / "training_log.before-35.h5")) as f:
        assert snapshot_iterations(f) == [0, 10, 20, 30, 40, 50, 52]  # 52: its close()
    info = dump(path)
    if require_dump():
        assert info["repairs"] == [] and info["snapshots"] == [35, 40, 50, 60, 70, 80, ITERATIONS]
