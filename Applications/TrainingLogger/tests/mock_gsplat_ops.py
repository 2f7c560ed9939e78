# SPDX-License-Identifier: BSD-3-Clause
"""A CPU stand-in for gsplat.strategy.ops (gsplat 1.x) with the same row bookkeeping
(reference §4.5): duplicate -> [old, old[sel]]; split -> [old[rest], child0(sel),
child1(sel)]; remove -> old[~mask]; relocate -> p[dead] = p[sampled]; sample_add ->
[p, p[sampled]]. compute_relocation is simplified (it only changes values, not rows)."""

import numpy as np
import torch
import torch.nn.functional as F


def _multinomial_sample(weights, n, replacement=True):
    if weights.size(0) <= 2 ** 24:
        return torch.multinomial(weights, n, replacement=replacement)
    w = (weights / weights.sum()).cpu().numpy()
    return torch.from_numpy(np.random.choice(len(w), size=n, p=w, replace=replacement))


def compute_relocation(opacities, scales, ratios, binoms):
    new_opacities = 1.0 - torch.pow(1.0 - opacities, 1.0 / ratios.float())
    return new_opacities, scales / torch.sqrt(ratios.float())[:, None]


def normalized_quat_to_rotmat(quat):
    w, x, y, z = torch.unbind(quat, dim=-1)
    mat = torch.stack([1 - 2 * (y ** 2 + z ** 2), 2 * (x * y - w * z), 2 * (x * z + w * y),
                       2 * (x * y + w * z), 1 - 2 * (x ** 2 + z ** 2), 2 * (y * z - w * x),
                       2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x ** 2 + y ** 2)], dim=-1)
    return mat.reshape(quat.shape[:-1] + (3, 3))


@torch.no_grad()
def _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers, names=None):
    if names is None:
        names = list(params.keys())
    for name in names:
        param = params[name]
        new_param = param_fn(name, param)
        params[name] = new_param
        if name not in optimizers:
            continue
        optimizer = optimizers[name]
        for i in range(len(optimizer.param_groups)):
            param_state = optimizer.state[param]
            del optimizer.state[param]
            for key in param_state.keys():
                if key != "step":
                    param_state[key] = optimizer_fn(key, param_state[key])
            optimizer.param_groups[i]["params"] = [new_param]
            optimizer.state[new_param] = param_state


@torch.no_grad()
def duplicate(params, optimizers, state, mask):
    sel = torch.where(mask)[0]

    def param_fn(name, p):
        return torch.nn.Parameter(torch.cat([p, p[sel]]), requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return torch.cat([v, torch.zeros((len(sel), *v.shape[1:]))])

    _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)
    for k, v in state.items():
        if isinstance(v, torch.Tensor):
            state[k] = torch.cat((v, v[sel]))


@torch.no_grad()
def split(params, optimizers, state, mask, revised_opacity=False):
    sel = torch.where(mask)[0]
    rest = torch.where(~mask)[0]
    scales = torch.exp(params["scales"][sel])
    quats = F.normalize(params["quats"][sel], dim=-1)
    rotmats = normalized_quat_to_rotmat(quats)
    samples = torch.einsum("nij,nj,bnj->bni", rotmats, scales, torch.randn(2, len(scales), 3))

    def param_fn(name, p):
        repeats = [2] + [1] * (p.dim() - 1)
        if name == "means":
            p_split = (p[sel] + samples).reshape(-1, 3)
        elif name == "scales":
            p_split = torch.log(scales / 1.6).repeat(2, 1)
        elif name == "opacities" and revised_opacity:
            new_opacities = 1.0 - torch.sqrt(1.0 - torch.sigmoid(p[sel]))
            p_split = torch.logit(new_opacities).repeat(repeats)
        else:
            p_split = p[sel].repeat(repeats)
        return torch.nn.Parameter(torch.cat([p[rest], p_split]), requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return torch.cat([v[rest], torch.zeros((2 * len(sel), *v.shape[1:]))])

    _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)
    for k, v in state.items():
        if isinstance(v, torch.Tensor):
            repeats = [2] + [1] * (v.dim() - 1)
            state[k] = torch.cat((v[rest], v[sel].repeat(repeats)))


@torch.no_grad()
def remove(params, optimizers, state, mask):
    sel = torch.where(~mask)[0]

    def param_fn(name, p):
        return torch.nn.Parameter(p[sel], requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return v[sel]

    _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)
    for k, v in state.items():
        if isinstance(v, torch.Tensor):
            state[k] = v[sel]


@torch.no_grad()
def relocate(params, optimizers, state, mask, binoms, min_opacity=0.005):
    opacities = torch.sigmoid(params["opacities"])
    dead_indices = mask.nonzero(as_tuple=True)[0]
    alive_indices = (~mask).nonzero(as_tuple=True)[0]
    n = len(dead_indices)
    eps = torch.finfo(torch.float32).eps
    probs = opacities[alive_indices].flatten()
    sampled_idxs = _multinomial_sample(probs, n, replacement=True)
    sampled_idxs = alive_indices[sampled_idxs]
    new_opacities, new_scales = compute_relocation(
        opacities=opacities[sampled_idxs], scales=torch.exp(params["scales"])[sampled_idxs],
        ratios=torch.bincount(sampled_idxs)[sampled_idxs] + 1, binoms=binoms)
    new_opacities = torch.clamp(new_opacities, max=1.0 - eps, min=min_opacity)

    def param_fn(name, p):
        if name == "opacities":
            p[sampled_idxs] = torch.logit(new_opacities)
        elif name == "scales":
            p[sampled_idxs] = torch.log(new_scales)
        p[dead_indices] = p[sampled_idxs]
        return torch.nn.Parameter(p, requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        v[sampled_idxs] = 0
        return v

    _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)
    for k, v in state.items():
        if isinstance(v, torch.Tensor):
            v[sampled_idxs] = 0


@torch.no_grad()
def sample_add(params, optimizers, state, n, binoms, min_opacity=0.005):
    opacities = torch.sigmoid(params["opacities"])
    eps = torch.finfo(torch.float32).eps
    probs = opacities.flatten()
    sampled_idxs = _multinomial_sample(probs, n, replacement=True)
    new_opacities, new_scales = compute_relocation(
        opacities=opacities[sampled_idxs], scales=torch.exp(params["scales"])[sampled_idxs],
        ratios=torch.bincount(sampled_idxs)[sampled_idxs] + 1, binoms=binoms)
    new_opacities = torch.clamp(new_opacities, max=1.0 - eps, min=min_opacity)

    def param_fn(name, p):
        if name == "opacities":
            p[sampled_idxs] = torch.logit(new_opacities)
        elif name == "scales":
            p[sampled_idxs] = torch.log(new_scales)
        return torch.nn.Parameter(torch.cat([p, p[sampled_idxs]]), requires_grad=p.requires_grad)

    def optimizer_fn(key, v):
        return torch.cat([v, torch.zeros((len(sampled_idxs), *v.shape[1:]))])

    _update_param_with_optimizer(param_fn, optimizer_fn, params, optimizers)
    for k, v in state.items():
        if isinstance(v, torch.Tensor):
            state[k] = torch.cat((v, torch.zeros((len(sampled_idxs), *v.shape[1:]))))
