# SPDX-License-Identifier: BSD-3-Clause
"""The stand-ins the always-run tests use (mock_gsplat_ops.py, mock_3dgs.py) against the
trainers' own code on the same inputs and the same random stream: they stay only as long
as this holds. Each part is skipped without its upstream copy (upstream.py says how).

What is compared: every parameter and every optimizer state row after duplicate, split
(plain and revised opacity) and remove, and after the original densify_and_prune. For
relocate and sample_add, the rows (which row is a copy of which: means, quats, sh) and
the sampled sources; the stand-in's compute_relocation is a simplified formula, so the
opacity and scale values of those rows are not compared (the logger never reads them).
"""

import inspect
import math
import types

import numpy as np
import pytest
import torch

import mock_3dgs
import mock_gsplat_ops
import mock_gsplat_strategy
import test_gsplat
import upstream


def _splats(n, seed):
    """test_gsplat's splats (one optimizer step taken) with varied opacities, SH rest and
    strategy state, so that every column is compared on distinct values."""
    params, optimizers, _ = test_gsplat.make_splats(n, seed)
    g = torch.Generator().manual_seed(seed + 1)
    with torch.no_grad():
        params["opacities"][:] = torch.randn(n, generator=g)
        params["shN"][:] = torch.randn(n, 15, 3, generator=g)
    state = {"grad2d": torch.rand(n, generator=g), "count": torch.rand(n, generator=g)}
    return params, optimizers, state


def _run(ops, name, seed, **kwargs):
    params, optimizers, state = _splats(40, 7)
    mask = torch.zeros(40, dtype=torch.bool)
    mask[[1, 5, 6, 20, 39]] = True
    torch.manual_seed(seed)
    fn = getattr(ops, name)
    if name in ("duplicate", "split", "remove", "relocate"):
        fn(params=params, optimizers=optimizers, state=state, mask=mask, **kwargs)
    else:
        fn(params=params, optimizers=optimizers, state=state, **kwargs)
    return params, optimizers, state


def _adam_state(params, optimizers):
    return {k: {s: v for s, v in optimizers[k].state[params[k]].items() if s != "step"}
            for k in optimizers}


@pytest.mark.parametrize("name,kwargs", [
    ("duplicate", {}), ("split", {}), ("split", {"revised_opacity": True}), ("remove", {}),
    ("relocate", {"binoms": None, "min_opacity": 0.005}),
    ("sample_add", {"n": 7, "binoms": None, "min_opacity": 0.005})])
def test_gsplat_ops_stand_in_matches_upstream(name, kwargs):
    ops = upstream.load_gsplat().ops  # skips without a copy
    if "binoms" in kwargs:
        kwargs = dict(kwargs, binoms=_binoms())
    theirs = _run(ops, name, 3, **kwargs)
    ours = _run(mock_gsplat_ops, name, 3, **kwargs)
    values_differ = {"opacities", "scales"} if name in ("relocate", "sample_add") else set()
    for key in theirs[0]:
        assert theirs[0][key].shape == ours[0][key].shape, key
        if key not in values_differ:
            torch.testing.assert_close(ours[0][key], theirs[0][key], rtol=0, atol=0)
    a, b = _adam_state(*theirs[:2]), _adam_state(*ours[:2])
    for key in a:
        if key in values_differ:
            continue
        for s in a[key]:
            torch.testing.assert_close(b[key][s], a[key][s], rtol=0, atol=0)
    for key in theirs[2]:
        torch.testing.assert_close(ours[2][key], theirs[2][key], rtol=0, atol=0)


def _binoms():
    binoms = torch.zeros(51, 51)
    for n in range(51):
        for k in range(n + 1):
            binoms[n, k] = float(math.comb(n, k))
    return binoms


@pytest.mark.parametrize("kind", ["default", "mcmc"])
def test_gsplat_strategy_stand_in_matches_upstream(kind):
    """mock_gsplat_strategy's grow_and_prune = DefaultStrategy._grow_gs + _prune_gs (before
    the first opacity reset), mcmc_relocate_and_add = MCMCStrategy._relocate_gs +
    _add_new_gs, each with its own ops."""
    strategy = upstream.load_gsplat()

    def inputs():
        params, optimizers, state = _splats(60, 9)
        g = torch.Generator().manual_seed(3)
        with torch.no_grad():
            params["scales"][:] = torch.log(torch.where(torch.rand(60, 1, generator=g) < 0.5,
                                                        0.005, 0.05) * torch.ones(60, 3))
            params["opacities"][:] = torch.logit(torch.rand(60, generator=g) * 0.02)
        state["grad2d"] = torch.rand(60, generator=g) * 4e-4
        state["count"] = torch.ones(60)
        state["scene_scale"] = 1.0
        return params, optimizers, state

    theirs, ours = inputs(), inputs()
    torch.manual_seed(5)
    if kind == "default":
        upstream_strategy = strategy.DefaultStrategy()
        upstream_strategy._grow_gs(*theirs, step=600)
        upstream_strategy._prune_gs(*theirs, step=600)
    else:
        upstream_strategy = strategy.MCMCStrategy(cap_max=80)
        upstream_strategy._relocate_gs(*theirs[:2], _binoms())
        upstream_strategy._add_new_gs(*theirs[:2], _binoms())
    torch.manual_seed(5)
    if kind == "default":
        mock_gsplat_strategy.grow_and_prune(*ours, scene_scale=1.0)
    else:
        mock_gsplat_strategy.mcmc_relocate_and_add(*ours[:2], {}, _binoms(), cap_max=80)
    assert len(theirs[0]["means"]) != 60
    for key in theirs[0]:
        if kind == "mcmc" and key in ("opacities", "scales"):
            continue  # the stand-in's relocation formula is simplified
        torch.testing.assert_close(ours[0][key], theirs[0][key], rtol=0, atol=0, msg=key)


def test_3dgs_stand_in_matches_the_original_gaussian_model():
    GaussianModel, _ = upstream.load_3dgs_model()  # skips without a copy
    ours = mock_3dgs.GaussianModel(3)
    ours.create_random(120, seed=4)
    theirs = GaussianModel(3)
    for attr in ("_xyz", "_features_dc", "_features_rest", "_scaling", "_rotation", "_opacity"):
        setattr(theirs, attr, torch.nn.Parameter(getattr(ours, attr).detach().clone()))
    theirs.pretrained_exposures = None
    theirs._exposure = torch.nn.Parameter(torch.eye(3, 4)[None])
    theirs.spatial_lr_scale = 1.0
    opt = types.SimpleNamespace(
        percent_dense=ours.percent_dense, position_lr_init=1.6e-4, position_lr_final=1.6e-6,
        position_lr_delay_mult=0.01, position_lr_max_steps=30000, feature_lr=2.5e-3,
        opacity_lr=0.05, scaling_lr=0.005, rotation_lr=0.001, exposure_lr_init=0.01,
        exposure_lr_final=0.001, exposure_lr_delay_steps=0, exposure_lr_delay_mult=0.0,
        iterations=30000)
    theirs.training_setup(opt)
    theirs.max_radii2D = torch.zeros(120)
    for model in (ours, theirs):  # the same statistics and one optimizer step
        r = np.random.default_rng(2)
        with torch.no_grad():
            model.xyz_gradient_accum[:] = torch.from_numpy(r.uniform(0, 5e-4, (120, 1)).astype(np.float32))
            model.denom[:] = torch.from_numpy(r.integers(0, 3, (120, 1)).astype(np.float32))
            model._scaling[:] = torch.from_numpy(
                (r.choice([-6.0, -3.5], (120, 1)) + r.normal(0, 0.1, (120, 3))).astype(np.float32))
            model._opacity[:] = torch.logit(torch.from_numpy(r.uniform(0, 0.2, (120, 1)).astype(np.float32)))
            model.max_radii2D[:] = torch.from_numpy(r.uniform(0, 30, 120).astype(np.float32))
        (sum((p ** 2).sum() for p in (model._xyz, model._features_dc, model._scaling,
                                      model._rotation, model._opacity))).backward()
        model.optimizer.step()
        model.optimizer.zero_grad(set_to_none=True)
        torch.manual_seed(11)
        # the current upstream also takes render()'s radii (carried along as tmp_radii,
        # read by nothing in the densification); the stand-in has the older signature
        extra = (model.max_radii2D.clone(),) if model is theirs and "radii" in \
            inspect.signature(model.densify_and_prune).parameters else ()
        model.densify_and_prune(0.0002, 0.005, 1.0, 20, *extra)
    for attr in ("_xyz", "_features_dc", "_features_rest", "_scaling", "_rotation", "_opacity",
                 "xyz_gradient_accum", "denom", "max_radii2D"):
        torch.testing.assert_close(getattr(ours, attr), getattr(theirs, attr), rtol=0, atol=0,
                                   msg=attr)
    for g_ours, g_theirs in zip(ours.optimizer.param_groups, theirs.optimizer.param_groups):
        s_ours = ours.optimizer.state[g_ours["params"][0]]
        s_theirs = theirs.optimizer.state[g_theirs["params"][0]]
        assert set(s_ours) == set(s_theirs), g_ours["name"]  # f_rest: never stepped, empty
        for key in set(s_ours) & {"exp_avg", "exp_avg_sq"}:
            torch.testing.assert_close(s_ours[key], s_theirs[key], rtol=0, atol=0)
    assert len(ours._xyz) != 120  # something was densified and pruned
