# SPDX-License-Identifier: BSD-3-Clause
"""Stand-ins for gsplat.strategy.default / .mcmc: like the real modules they import the
ops by name and call them through their module globals (which the tracker replaces)."""

import torch

from mock_gsplat_ops import duplicate, relocate, remove, sample_add, split  # noqa: F401


@torch.no_grad()
def grow_and_prune(params, optimizers, state, grow_grad2d=0.0002, grow_scale3d=0.01,
                   prune_opa=0.005, scene_scale=1.0):
    """DefaultStrategy._grow_gs then _prune_gs (duplicate, split, remove)."""
    count = state["count"]
    grads = state["grad2d"] / count.clamp_min(1)
    is_grad_high = grads > grow_grad2d
    is_small = torch.exp(params["scales"]).max(dim=-1).values <= grow_scale3d * scene_scale
    is_dupli = is_grad_high & is_small
    n_dupli = int(is_dupli.sum())
    is_large = ~is_small
    is_split = is_grad_high & is_large
    if n_dupli > 0:
        duplicate(params=params, optimizers=optimizers, state=state, mask=is_dupli)
    is_split = torch.cat([is_split, torch.zeros(n_dupli, dtype=torch.bool)])
    if int(is_split.sum()) > 0:
        split(params=params, optimizers=optimizers, state=state, mask=is_split)
    is_prune = torch.sigmoid(params["opacities"].flatten()) < prune_opa
    if int(is_prune.sum()) > 0:
        remove(params=params, optimizers=optimizers, state=state, mask=is_prune)
    state["grad2d"].zero_()
    state["count"].zero_()


@torch.no_grad()
def mcmc_relocate_and_add(params, optimizers, state, binoms, cap_max, min_opacity=0.005):
    """MCMCStrategy._relocate_gs then _add_new_gs."""
    dead_mask = torch.sigmoid(params["opacities"].flatten()) <= min_opacity
    if int(dead_mask.sum()) > 0:
        relocate(params=params, optimizers=optimizers, state=state, mask=dead_mask,
                 binoms=binoms, min_opacity=min_opacity)
    current = len(params["means"])
    n_target = min(cap_max, int(1.05 * current))
    n = max(0, n_target - current)
    if n > 0:
        sample_add(params=params, optimizers=optimizers, state=state, n=n, binoms=binoms,
                   min_opacity=min_opacity)
