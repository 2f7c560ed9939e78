# SPDX-License-Identifier: BSD-3-Clause
"""The logger on gsplat's own densification code (DefaultStrategy, MCMCStrategy and their
ops, loaded from a pinned copy by upstream.py; skipped with a message when there is none).

The loop is simple_trainer.py's, from step 0, with the README's lines in it. The
rasteriser (CUDA only) is replaced by a pinhole projection that gives the strategy what
gsplat's rasterization() gives it: means2d (with a gradient), radii, gaussian_ids, width,
height, n_cameras, packed or not. The loss pushes the gradients of some Gaussians over
the growth threshold and the opacities of others under the prune threshold, so every
operation happens.

The independent lineage check: splats["root"] holds each row's root id, a parameter
without an optimizer (requires_grad=False, which gsplat's ops allow) that duplicate,
split, remove, relocate and sample_add copy like every other one. At every step with
events, every row's root must equal the root reached through the logged parents of the
row's id.
"""

import os
import types

import numpy as np
import pytest
import torch

import upstream
from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot, snapshot_iterations
from test_lifecycle import FOCAL, HEIGHT, WIDTH, colmap_parser
from vis4gs_logger import CLONE, PRUNE, SPLIT

gsplat_strategy = upstream.load_gsplat()  # skips the module without a copy

def create_splats(n, seed, sh_degree=3):
    """create_splats_with_optimizers of simple_trainer.py on random points, plus "root"."""
    g = torch.Generator().manual_seed(seed)
    points = torch.rand(n, 3, generator=g) * 2.0 - 1.0
    points[:, 2] += 4.0  # in front of the cameras
    scales = torch.log(torch.where(torch.rand(n, 1, generator=g) < 0.5,
                                   torch.full((n, 1), 0.004), torch.full((n, 1), 0.05))
                       * torch.ones(n, 3))
    params = torch.nn.ParameterDict({
        "means": torch.nn.Parameter(points),
        "scales": torch.nn.Parameter(scales),
        "quats": torch.nn.Parameter(torch.rand(n, 4, generator=g)),
        "opacities": torch.nn.Parameter(torch.logit(torch.full((n,), 0.1))),
        "sh0": torch.nn.Parameter(torch.rand(n, 1, 3, generator=g)),
        "shN": torch.nn.Parameter(torch.zeros(n, (sh_degree + 1) ** 2 - 1, 3)),
        "root": torch.nn.Parameter(torch.arange(n, dtype=torch.int64), requires_grad=False),
    })
    lrs = {"means": 1.6e-4, "scales": 5e-3, "quats": 1e-3, "opacities": 5e-2, "sh0": 2.5e-3,
           "shN": 2.5e-3 / 20}
    optimizers = {k: torch.optim.Adam([{"params": params[k], "lr": lr, "name": k}], eps=1e-15)
                  for k, lr in lrs.items()}
    return params, optimizers


class Scene:
    """Fixed per-Gaussian loss weights drawn once per root, so that every Gaussian and its
    copies keep their behaviour: a gradient on means2d around the growth threshold and a
    push of the opacity up or down."""

    def __init__(self, n0, seed, cameras=2):
        g = torch.Generator().manual_seed(seed + 1)
        self.cameras = cameras
        self.direction = torch.randn(n0, 2, generator=g)
        self.direction /= self.direction.norm(dim=-1, keepdim=True)
        # scaled gradient norm (what grad2d accumulates) in [0, 2.5e-4]: ~half over 2e-4
        scaled = torch.rand(n0, generator=g) * 2.5e-4
        self.weight = scaled / (WIDTH / 2.0 * cameras)
        self.opacity_push = torch.where(torch.rand(n0, generator=g) < 0.3, 1.0, -0.2)

    def rasterize(self, splats, packed, absgrad):
        """The fields of gsplat's rasterization() info the strategies read."""
        means = splats["means"]
        n = len(means)
        shifts = torch.tensor([[0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [0.0, 0.3, 0.0]])[: self.cameras]
        cam = means[None, :, :] - shifts[:, None, :]  # [C, N, 3]
        z = cam[..., 2:3]
        means2d = FOCAL * cam[..., :2] / z + torch.tensor([WIDTH / 2.0, HEIGHT / 2.0])
        radius = (3.0 * FOCAL * torch.exp(splats["scales"]).max(dim=-1).values / z[..., 0]).ceil()
        inside = (means2d[..., 0] > -radius) & (means2d[..., 0] < WIDTH + radius) \
            & (means2d[..., 1] > -radius) & (means2d[..., 1] < HEIGHT + radius)
        radii = torch.where(inside, radius, torch.zeros_like(radius)).to(torch.int32)
        radii = torch.stack([radii, radii], dim=-1)  # [C, N, 2]
        info = {"width": WIDTH, "height": HEIGHT, "n_cameras": self.cameras}
        if packed:
            sel = (radii > 0).all(dim=-1)
            camera_ids, gaussian_ids = torch.where(sel)
            info.update(means2d=means2d[sel], radii=radii[sel], camera_ids=camera_ids,
                        gaussian_ids=gaussian_ids)
        else:
            info.update(means2d=means2d, radii=radii, gaussian_ids=None)
        root = splats["root"]
        w = self.weight[root]
        d = self.direction[root]
        if packed:
            gids = info["gaussian_ids"]
            image_term = (info["means2d"] * (w[gids, None] * d[gids])).sum()
        else:
            image_term = (info["means2d"] * (w[None, :, None] * d[None])).sum()
        opacity_term = (self.opacity_push[root] * splats["opacities"]).sum()
        loss = image_term + 1e-3 * opacity_term + 1e-3 * (splats["sh0"] ** 2).sum()
        return loss, info, n


def root_through_events(events, n0):
    """id -> root id, from the logged parents alone."""
    it, kind, parent, child = events
    root = {i: i for i in range(n0)}
    for k, p, c in zip(kind, parent, child):
        if k in (CLONE, SPLIT):
            root[int(c)] = root[int(p)]
    return root


def check_lineage(splats, tracker, root_of):
    ids = tracker.ids.tolist()
    assert len(ids) == len(splats["means"]) == len(set(ids))
    stored = splats["root"].tolist()
    for row, gid in enumerate(ids):
        assert stored[row] == root_of[gid], f"row {row}: id {gid}"


def pending_events(logger):
    pend = logger.writer._pending_events
    if not pend:
        return (np.zeros(0, np.int32), np.zeros(0, np.uint8), np.zeros(0, np.int64),
                np.zeros(0, np.int64))
    return tuple(np.concatenate([e[j] for e in pend]) for j in range(4))


def train(tmp_path, strategy, max_steps, n0=300, packed=False, seed=0, name="run",
          before_step=None, snapshot_interval=10):
    """simple_trainer.py's loop (from step 0) with the README's lines."""
    torch.manual_seed(seed)
    splats, optimizers = create_splats(n0, seed)
    strategy.check_sanity(splats, optimizers)
    is_mcmc = isinstance(strategy, gsplat_strategy.MCMCStrategy)
    strategy_state = strategy.initialize_state() if is_mcmc else \
        strategy.initialize_state(scene_scale=1.0)
    scene = Scene(n0, seed)
    result_dir = tmp_path / name
    result_dir.mkdir()
    readme = upstream.readme_fragments("## gsplat")
    runner = types.SimpleNamespace(splats=splats, strategy_state=strategy_state,
                                   parser=colmap_parser(tmp_path / f"{name}-data"))
    cfg = types.SimpleNamespace(result_dir=str(result_dir), sh_degree=3, max_steps=max_steps)
    ns = {"self": runner, "cfg": cfg}
    exec(readme[""], ns)
    exec(readme["in Runner.__init__, after self.strategy_state = ...initialize_state(...):"], ns)
    logger, tracker = ns["logger"], ns["tracker"]
    logger.snapshot_interval = snapshot_interval  # (default 500) to see several in a short run
    scheduler = torch.optim.lr_scheduler.ExponentialLR(optimizers["means"],
                                                       gamma=0.01 ** (1.0 / max_steps))
    seen = set()
    logged = [0]  # events already checked (written ones are read back from the file)
    all_events = []
    for step in range(0, max_steps):
        if before_step is not None:
            before_step(step, strategy)
        loss, info, _ = scene.rasterize(splats, packed, getattr(strategy, "absgrad", False))
        strategy.step_pre_backward(params=splats, optimizers=optimizers,
                                   state=strategy_state, step=step, info=info)
        loss.backward()
        if getattr(strategy, "absgrad", False):
            # what gsplat's rasterizer backward stores next to .grad (|grad| per pixel, summed)
            info["means2d"].absgrad = info["means2d"].grad.abs()
        l1loss = loss.detach()
        ns.update(step=step, loss=loss, l1loss=l1loss)
        exec(readme["in the loop, after loss.backward():"], ns)
        for optimizer in optimizers.values():
            optimizer.step()
            optimizer.zero_grad(set_to_none=True)
        scheduler.step()
        if is_mcmc:
            strategy.step_post_backward(params=splats, optimizers=optimizers,
                                        state=strategy_state, step=step, info=info,
                                        lr=scheduler.get_last_lr()[0])
        else:
            strategy.step_post_backward(params=splats, optimizers=optimizers,
                                        state=strategy_state, step=step, info=info,
                                        packed=packed)
        new = pending_events(logger)
        if len(new[0]):
            all_events.append(new)
            seen.update(int(k) for k in new[1])
        exec(readme["at the end of the step (after strategy.step_post_backward):"], ns)
        if step in (39, max_steps - 1):  # simple_trainer's eval_steps are i - 1
            ns["stats"] = {"psnr": 20.0 + step / 10.0, "ssim": 0.5, "lpips": 0.25}
            exec(readme["in eval(), after `stats` is computed (LPIPS as the trainer computes it):"], ns)
        events = tuple(np.concatenate([e[j] for e in all_events]) if all_events
                       else np.zeros(0) for j in range(4))
        check_lineage(splats, tracker, root_through_events(events, n0))
        logged[0] += 1
    final_ids = tracker.ids.clone()
    final_means = splats["means"].detach().clone()
    exec(readme["after the loop:"], ns)
    path = f"{result_dir}/training_log.h5"
    with open_log(path) as f:  # test metrics, LPIPS, cameras with their image files
        np.testing.assert_array_equal(f["metrics/test/iteration"][:], [39, max_steps - 1])
        np.testing.assert_array_equal(f["metrics/test/lpips"][:], [0.25, 0.25])
        assert list(f["cameras/split"][:]) == [1, 0, 0, 0, 1, 0]
        for rel in f["cameras/image"].asstr()[:]:
            assert not os.path.isabs(rel) and os.path.isfile(os.path.join(result_dir, rel))
        assert f["cameras"].attrs["source"] == runner.parser.data_dir
    events = read_events(path)
    check_lineage(splats, type("T", (), {"ids": final_ids})(), root_through_events(events, n0))
    # The last snapshot is the final step's model: its ids and means as the loop left them.
    with open_log(path) as f:
        last = read_snapshot(f, max_steps - 1)
        order = np.argsort(final_ids.numpy(), kind="stable")
        np.testing.assert_array_equal(last["id"][:], final_ids.numpy()[order])
        np.testing.assert_array_equal(last["position"][:], final_means.numpy()[order])
    return path, splats, final_ids, seen, events, tracker


def check_log(path, splats, final_ids, n0, max_steps, events, snapshot_interval=10):
    check_format(path)
    alive, _ = replay_genealogy(events, n0)
    assert alive == set(final_ids.tolist())
    with open_log(path) as f:
        snaps = snapshot_iterations(f)
        expected = sorted(set(range(0, max_steps, snapshot_interval)) | {max_steps - 1})
        assert snaps[0] == 0 and snaps == expected, snaps
        assert f["metrics/iteration"][0] == 0 and len(f["metrics/iteration"]) == max_steps
        # The lineage check on the logged snapshots too: each snapshot's rows exist.
        last = read_snapshot(f, snaps[-1])
        assert set(last["id"][:].tolist()) <= set(range(n0)) | set(events[3].tolist())
    info = dump(path)
    if require_dump():
        assert info["events"] == len(events[0]) and info["repairs"] == []
        assert info["snapshots"] == snaps
        # the C++ reader gives the paths the application resolves against the log's folder
        for rel in info["camera_images"]:
            assert os.path.isfile(os.path.join(os.path.dirname(path), rel)), rel


@pytest.mark.parametrize("packed,absgrad,revised", [(False, False, False), (True, False, False),
                                                    (False, True, False), (True, False, True)])
def test_default_strategy(tmp_path, packed, absgrad, revised):
    strategy = gsplat_strategy.DefaultStrategy(
        refine_start_iter=5, refine_every=10, reset_every=30, refine_stop_iter=70,
        absgrad=absgrad, revised_opacity=revised,
        grow_grad2d=0.0002 if not absgrad else 0.0002)
    max_steps = 80
    path, splats, final_ids, seen, events, tracker = train(
        tmp_path, strategy, max_steps, packed=packed, seed=int(packed) + 2 * int(absgrad))
    assert seen == {CLONE, SPLIT, PRUNE}, seen
    assert tracker.warnings == []
    check_log(path, splats, final_ids, 300, max_steps, events)
    if revised:  # the split children's opacity is 1 - sqrt(1 - parent's): recorded as is
        with open_log(path) as f:
            assert np.isfinite(read_snapshot(f, 70)["opacity_logit"]).all()


def test_mcmc_strategy(tmp_path):
    strategy = gsplat_strategy.MCMCStrategy(cap_max=400, refine_start_iter=5, refine_every=10,
                                            refine_stop_iter=70, min_opacity=0.005)
    max_steps = 80
    path, splats, final_ids, seen, events, tracker = train(tmp_path, strategy, max_steps)
    assert seen == {CLONE, PRUNE}, seen  # relocate: prune + clone; sample_add: clone
    assert len(final_ids) == 400
    assert tracker.warnings == []
    check_log(path, splats, final_ids, 300, max_steps, events)


def test_mcmc_strategy_long(tmp_path):
    """MCMC for 1,000 steps: relocations and additions every 25 steps up to the cap, with
    the lineage checked at every step and the final model in the log."""
    strategy = gsplat_strategy.MCMCStrategy(cap_max=900, refine_start_iter=25, refine_every=25,
                                            refine_stop_iter=900, min_opacity=0.005)
    max_steps = 1000
    path, splats, final_ids, seen, events, tracker = train(tmp_path, strategy, max_steps,
                                                           snapshot_interval=100)
    assert seen == {CLONE, PRUNE}, seen
    assert len(final_ids) == 900
    assert tracker.warnings == [] and tracker.breaks == []
    check_log(path, splats, final_ids, 300, max_steps, events, snapshot_interval=100)


def test_pinned_commit_is_recorded():
    """The tests say which upstream code they ran."""
    assert len(gsplat_strategy.commit) >= 7, gsplat_strategy.commit


def test_default_strategy_from_one_gaussian_to_none(tmp_path):
    """One Gaussian grows by gsplat's own duplicate/split, then its prune removes every
    Gaussian: the last snapshot is the empty model."""
    def prune_all_at_the_last_refine(step, strategy):
        if step == 40:
            strategy.prune_opa = 1.0  # every opacity is below 1

    strategy = gsplat_strategy.DefaultStrategy(refine_start_iter=5, refine_every=10,
                                               reset_every=1000, grow_grad2d=0.0)
    path, splats, final_ids, seen, events, tracker = train(
        tmp_path, strategy, 41, n0=1, seed=5, before_step=prune_all_at_the_last_refine)
    assert len(final_ids) == 0 and PRUNE in seen and seen & {CLONE, SPLIT}, seen
    check_log(path, splats, final_ids, 1, 41, events)
    with open_log(path) as f:
        counts = [len(read_snapshot(f, s)["id"]) for s in (0, 10, 20, 30, 40)]
    assert counts[0] == 1 and counts[1] == 2 and counts[-1] == 0, counts
