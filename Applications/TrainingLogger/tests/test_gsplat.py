# SPDX-License-Identifier: BSD-3-Clause
"""The gsplat hooks against stand-ins of gsplat.strategy.ops / default / mcmc that perform
the same row operations. sh0[:, 0, 1] carries each Gaussian's id as an independent witness
(duplicate, split, relocate and sample_add copy it like every other parameter)."""

import numpy as np
import pytest
import torch

import mock_gsplat_ops
import mock_gsplat_strategy
from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot
from vis4gs_logger import CLONE, PRUNE, SPLIT, TrainingLogger, track_gsplat


def make_splats(n, seed):
    g = torch.Generator().manual_seed(seed)
    params = torch.nn.ParameterDict({
        "means": torch.nn.Parameter(torch.randn(n, 3, generator=g)),
        "scales": torch.nn.Parameter(torch.randn(n, 3, generator=g) * 0.5 - 4.0),
        "quats": torch.nn.Parameter(torch.rand(n, 4, generator=g)),
        "opacities": torch.nn.Parameter(torch.logit(torch.full((n,), 0.1))),
        "sh0": torch.nn.Parameter(torch.randn(n, 1, 3, generator=g)),
        "shN": torch.nn.Parameter(torch.zeros(n, 15, 3)),
    })
    optimizers = {k: torch.optim.Adam([{"params": [v], "lr": 1e-3, "name": k}], eps=1e-15)
                  for k, v in params.items()}
    # One optimizer step so that they hold state, as in training.
    loss = sum((v ** 2).sum() for v in params.values())
    loss.backward()
    for o in optimizers.values():
        o.step()
        o.zero_grad()
    with torch.no_grad():
        params["sh0"][:, 0, 1] = torch.arange(n).float()
    state = {"grad2d": torch.zeros(n), "count": torch.zeros(n), "radii": torch.zeros(n)}
    return params, optimizers, state


def witness(params):
    return params["sh0"][:, 0, 1].detach().long()


def reset_witness(params, ids):
    with torch.no_grad():
        params["sh0"][:, 0, 1] = ids.float()


def check_step(params, tracker, new_events):
    """Each row carries its own id, or (new rows) the id of the parent recorded for it."""
    born = {}
    for it, kind, parents, children in new_events:
        for p, ch in zip(parents, children):
            if kind[0] in (CLONE, SPLIT):
                born[int(ch)] = int(p)
    w = witness(params)
    ids = tracker.ids
    assert len(ids) == len(params["means"]) and len(set(ids.tolist())) == len(ids)
    def origin(i):  # a child of a child born in the same step carries the first parent's id
        while i in born:
            i = born[i]
        return i

    for row in range(len(ids)):
        assert int(w[row]) == origin(int(ids[row]))
    reset_witness(params, ids)


def test_default_and_mcmc_strategies(tmp_path):
    torch.manual_seed(0)
    rng = np.random.default_rng(5)
    params, optimizers, state = make_splats(300, 1)
    path = str(tmp_path / "gsplat.h5")
    logger = TrainingLogger(path, scene="mock-gsplat", snapshot_interval=100)
    tracker = track_gsplat(params, logger, strategy_state=state,
                           modules=[mock_gsplat_strategy, mock_gsplat_ops])
    seen = set()
    for step in range(1, 501):
        logger.log_metrics(step, loss=1.0 / step)
        if step % 100 == 50:
            e0 = len(logger.writer._pending_events)
            n = len(params["means"])
            with torch.no_grad():
                state["grad2d"][:] = torch.from_numpy(rng.uniform(0, 0.0005, n).astype(np.float32))
                state["count"][:] = 1
                params["scales"][:] = torch.from_numpy(
                    (rng.choice([-6.0, -3.0], (n, 1)) + rng.normal(0, 0.1, (n, 3))).astype(np.float32))
                params["opacities"][:] = torch.logit(torch.from_numpy(rng.uniform(0, 0.1, n).astype(np.float32)))
            if step < 300:
                mock_gsplat_strategy.grow_and_prune(params, optimizers, state, scene_scale=1.0)
            else:
                binoms = torch.zeros(51, 51)
                mock_gsplat_strategy.mcmc_relocate_and_add(params, optimizers, state, binoms,
                                                           cap_max=2000)
            new_events = logger.writer._pending_events[e0:]
            for e in new_events:
                seen.add(int(e[1][0]))
            check_step(params, tracker, new_events)
        logger.step(step)
    assert seen == {CLONE, SPLIT, PRUNE}
    final = tracker.ids.clone()
    logger.close()

    check_format(path)  # includes: snapshot rows sorted by id after relocations
    events = read_events(path)
    alive, next_id = replay_genealogy(events, 300)
    assert alive == set(final.tolist()) and next_id == tracker.next_id
    with open_log(path) as f:
        snap = read_snapshot(f, 500)
        order = np.argsort(final.numpy())
        np.testing.assert_array_equal(snap["id"][:], final.numpy()[order])
        np.testing.assert_array_equal(snap["position"][:], params["means"].detach().numpy()[order])
        assert snap["sh"].shape[1:] == (16, 3)
        np.testing.assert_array_equal(snap["opacity_logit"][:], params["opacities"].detach().numpy()[order])
        assert "grad_accum" in snap
    info = dump(path, "--history=1,2,3," + ",".join(str(int(i)) for i in final[-3:]))
    if require_dump():
        assert info["events"] == len(events[0]) and info["repairs"] == []
        assert info["counts"][-1] == len(final)
        assert info["snapshots"] == [0, 100, 200, 300, 400, 500]
        # The history of the last-born ids ends at the last snapshot with their values.
        last_rows = [h for h in info["history"] if h["iteration"] == 500]
        for h in last_rows:
            row = int(np.nonzero(final.numpy() == h["id"])[0][0])
            assert h["opacity_logit"] == pytest.approx(float(params["opacities"][row]), abs=0)
    # Uninstalled on close: the strategy module calls the original ops again.
    assert not getattr(mock_gsplat_strategy.duplicate, "_vis4gs_wrapped", False)
    assert not getattr(mock_gsplat_ops.relocate, "_vis4gs_wrapped", False)


def test_relocate_without_capturable_sampler_matches_by_value(tmp_path):
    """Older gsplat: the sampler cannot be captured; sources are found by their means."""
    torch.manual_seed(3)
    params, optimizers, state = make_splats(60, 2)
    logger = TrainingLogger(str(tmp_path / "r.h5"), snapshot_interval=0)
    tracker = track_gsplat(params, logger, modules=[mock_gsplat_ops], snapshot_initial=False)
    dead = torch.zeros(60, dtype=torch.bool)
    dead[[3, 10, 11, 40]] = True
    with torch.no_grad():
        params["opacities"][dead] = -10.0

    # Simulate the capture failing (e.g. numpy sampling of huge models).
    tracker._call_capturing = lambda fn, a, k: (fn(*a, **k), None)
    e0 = len(logger.writer._pending_events)
    mock_gsplat_ops.relocate(params, optimizers, state, dead, torch.zeros(51, 51))
    check_step(params, tracker, logger.writer._pending_events[e0:])
    kinds = [int(e[1][0]) for e in logger.writer._pending_events[e0:]]
    assert kinds == [PRUNE, CLONE]
    assert sorted(logger.writer._pending_events[e0][2].tolist()) == [3, 10, 11, 40]
    logger.close()
