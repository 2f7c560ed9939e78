# SPDX-License-Identifier: BSD-3-Clause
"""Hooks for gsplat's densification strategies (nerfstudio-project/gsplat).

DefaultStrategy and MCMCStrategy call module-level functions imported from
gsplat.strategy.ops (``duplicate``, ``split``, ``remove``; ``relocate``, ``sample_add``).
GsplatTracker replaces those names in the strategy modules by wrappers that keep one id
per row of the splats (reference §4.5):

* duplicate(mask): sel = where(mask); rows become [old, old[sel]] -> clone events
  (id[sel[r]], new id).
* split(mask): rows become [old[rest], child0(sel), child1(sel)] -> split events
  (id[sel[r]] -> two new ids); the parents end by the split (no prune).
* remove(mask): prune events (id, -1); survivors keep their order.
* relocate(mask = dead): each dead row d is overwritten by a copy of a sampled live row s.
  Recorded as a prune of the dead Gaussian followed by a clone s -> new id; row d then
  carries the new id. The sources are captured from the sampler the op calls
  (``_multinomial_sample``, or ``torch.multinomial`` in older releases); if neither can be
  captured they are found by matching the copied means.
* sample_add(n): n rows appended as copies of sampled rows -> clone events.

Ids are no longer increasing in row order after a relocation; snapshots sort rows by id.
"""

import importlib
import inspect

from .tracking import CLONE, SPLIT, IdTracker

__all__ = ["GsplatTracker", "track_gsplat"]

_OPS = ("duplicate", "split", "remove", "relocate", "sample_add")


class GsplatTracker(IdTracker):
    """Tracks the ids of one gsplat ``splats`` ParameterDict; created by track_gsplat()."""

    def __init__(self, params, logger, strategy_state=None):
        super().__init__(logger)
        self.params = params
        self.strategy_state = strategy_state
        self._patched = []  # (module, name, original)

    def count(self):
        return int(self.params["means"].shape[0])

    def _device(self):
        return self.params["means"].device

    # -- installing ----------------------------------------------------------------------
    def install(self, modules=None):
        """Wraps the ops in ``modules`` (default: gsplat.strategy.default, .mcmc and .ops)."""
        if modules is None:
            modules = []
            for name in ("gsplat.strategy.default", "gsplat.strategy.mcmc", "gsplat.strategy.ops"):
                try:
                    modules.append(importlib.import_module(name))
                except ImportError:
                    pass
            if not modules:
                raise ImportError("gsplat is not installed: pass the strategy modules explicitly")
        for module in modules:
            for name in _OPS:
                fn = getattr(module, name, None)
                if fn is None:
                    continue
                # An op already wrapped by another tracker is wrapped again: each wrapper
                # handles only its own params and passes other calls through.
                wrapper = self._wrap(name, fn)
                setattr(module, name, wrapper)
                self._patched.append((module, name, fn))
        return self

    def uninstall(self):
        for module, name, fn in reversed(self._patched):
            setattr(module, name, fn)
        self._patched = []

    def _wrap(self, name, fn):
        signature = inspect.signature(fn)
        handler = getattr(self, "_on_" + name)
        tracker = self

        def wrapper(*args, **kwargs):
            try:
                bound = signature.bind(*args, **kwargs)
                bound.apply_defaults()
            except TypeError:
                return fn(*args, **kwargs)  # the op itself reports the wrong call
            if bound.arguments.get("params") is not tracker.params:
                return fn(*args, **kwargs)  # another model: not ours
            return handler(fn, bound, args, kwargs)

        wrapper._vis4gs_wrapped = True
        wrapper.__name__ = name
        wrapper.__doc__ = fn.__doc__
        return wrapper

    # -- handlers: what each op does to the rows (before / after it runs) ----------------
    def _on_duplicate(self, fn, bound, args, kwargs):
        import torch

        def before():
            return self.ids[torch.where(bound.arguments["mask"].to(self.ids.device))[0]]

        def after(parents, result):
            self.append_children(CLONE, parents)

        return self.guarded("duplicate", fn, args, kwargs, before, after)

    def _on_split(self, fn, bound, args, kwargs):
        import torch

        def before():
            mask = bound.arguments["mask"].to(self.ids.device).bool()
            return self.ids[torch.where(mask)[0]], self.ids[torch.where(~mask)[0]]

        def after(state, result):
            parents, rest = state
            self.ids = rest  # compaction happens inside split; the parents end by the split
            self.append_children(SPLIT, parents.repeat(2))

        return self.guarded("split", fn, args, kwargs, before, after)

    def _on_remove(self, fn, bound, args, kwargs):
        def before():
            mask = bound.arguments["mask"].to(self.ids.device).bool()
            if len(mask) != len(self.ids):
                raise ValueError(f"a mask of {len(mask)} rows for {len(self.ids)} Gaussians")
            return mask

        def after(mask, result):
            self.remove_rows(mask, record=True)

        return self.guarded("remove", fn, args, kwargs, before, after)

    def _call_capturing(self, fn, args, kwargs):
        """Calls fn capturing the indices returned by the sampler it uses."""
        import torch

        captured = []
        g = getattr(fn, "__globals__", {})
        if "_multinomial_sample" in g:
            original = g["_multinomial_sample"]

            def sampler(*a, **k):
                out = original(*a, **k)
                captured.append(out)
                return out

            g["_multinomial_sample"] = sampler
            try:
                result = fn(*args, **kwargs)
            finally:
                g["_multinomial_sample"] = original
        else:
            original = torch.multinomial

            def sampler(*a, **k):
                out = original(*a, **k)
                captured.append(out)
                return out

            torch.multinomial = sampler
            try:
                result = fn(*args, **kwargs)
            finally:
                torch.multinomial = original
        return result, (captured[0] if len(captured) == 1 else None)

    def _match_sources(self, rows, candidates):
        """Rows whose means equal the means of a candidate row: the candidate (by value)."""
        import numpy as np

        means = self.params["means"].detach().cpu().numpy()
        cand = candidates.cpu().numpy()
        keys = np.ascontiguousarray(means[cand]).view(np.dtype((np.void, 12))).reshape(-1)
        order = np.argsort(keys)
        sorted_keys = keys[order]
        wanted = np.ascontiguousarray(means[rows.cpu().numpy()]).view(np.dtype((np.void, 12))).reshape(-1)
        pos = np.searchsorted(sorted_keys, wanted)
        pos = np.clip(pos, 0, len(sorted_keys) - 1)
        ok = sorted_keys[pos] == wanted
        return cand[order[pos]], ok

    def _on_relocate(self, fn, bound, args, kwargs):
        import torch

        captured = {}

        def call(*a, **k):
            result, captured["sampled"] = self._call_capturing(fn, a, k)
            return result

        def before():
            mask = bound.arguments["mask"].to(self.ids.device).bool()
            return torch.where(mask)[0], torch.where(~mask)[0]

        def after(state, result):
            dead, alive = state
            ids = self.ids
            if len(dead) == 0:
                return
            sampled = captured.get("sampled")
            if sampled is not None and len(sampled) == len(dead):
                sources = alive[sampled.to(ids.device)]
            else:
                src, ok = self._match_sources(dead, alive)
                if not ok.all():
                    self._warn(f"relocate at iteration {self.logger.iteration}: "
                               f"{int((~ok).sum())} sources not found")
                sources = torch.as_tensor(src, device=ids.device)
            self._record(3, ids[dead])  # the dead Gaussians end (prune) ...
            new = self._new_ids(len(dead))
            self._record(CLONE, ids[sources], new)  # ... and sources clone into their rows
            ids = ids.clone()
            ids[dead] = new
            self.ids = ids

        return self.guarded("relocate", call, args, kwargs, before, after)

    def _on_sample_add(self, fn, bound, args, kwargs):
        import torch

        captured = {}

        def call(*a, **k):
            result, captured["sampled"] = self._call_capturing(fn, a, k)
            return result

        def before():
            return len(self.ids)

        def after(n0, result):
            ids = self.ids
            n_new = self.count() - n0
            sampled = captured.get("sampled")
            if sampled is not None and len(sampled) == n_new:
                sources = sampled.to(ids.device)
            else:
                rows = torch.arange(n0, n0 + n_new)
                src, ok = self._match_sources(rows, torch.arange(n0))
                if not ok.all():
                    self._warn(f"sample_add at iteration {self.logger.iteration}: sources not found")
                sources = torch.as_tensor(src, device=ids.device)
            self.append_children(CLONE, ids[sources])

        return self.guarded("sample_add", call, args, kwargs, before, after)

    # -- snapshots -----------------------------------------------------------------------
    def write_snapshot(self, iteration):
        import torch

        p = self.params
        ids = self._ensure()
        self._check("a snapshot")
        with torch.no_grad():
            sh0 = p["sh0"] if "sh0" in p else None
            if sh0 is None:  # appearance-feature models: no SH, store zeros as DC
                sh = torch.zeros((self.count(), 1, 3))
            elif self.logger.snapshot_sh_rest and "shN" in p:
                sh = torch.cat([sh0, p["shN"]], dim=1)
            else:
                sh = sh0
            grad_accum = denom = None
            state = self.strategy_state
            if self.logger.snapshot_statistics and state is not None and "grad2d" in state \
                    and state.get("grad2d") is not None and len(state["grad2d"]) == len(ids):
                count = state["count"].reshape(-1).float()
                grad_accum = state["grad2d"].reshape(-1) / count.clamp_min(1)
                denom = count
            self.logger.writer.write_snapshot(
                iteration, ids, p["means"], p["scales"], p["quats"], p["opacities"].reshape(-1),
                sh, grad_accum=grad_accum, denom=denom)


def track_gsplat(splats, logger, strategy_state=None, modules=None, snapshot_initial=True):
    """Starts tracking gsplat's ``splats`` (ParameterDict with means, scales, quats,
    opacities, sh0, shN): wraps the strategy ops and, by default, writes a snapshot at
    iteration 0 (logger.start_iteration for a resumed run). Pass the strategy state dict
    to log grad2d/count as grad_accum/denom."""
    tracker = GsplatTracker(splats, logger, strategy_state).install(modules)
    tracker._ensure()
    if snapshot_initial:
        logger.snapshot(logger.start_iteration)
    return tracker
