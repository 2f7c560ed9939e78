# SPDX-License-Identifier: BSD-3-Clause
"""Hooks for the original 3DGS trainer (graphdeco-inria/gaussian-splatting, 2023 and the
2024 update): wraps a GaussianModel instance's densify_and_clone, densify_and_split,
prune_points and densification_postfix (instance attributes, so the model's own
densify_and_prune calls the wrappers) and keeps a persistent id per row.

Index bookkeeping (reference §4.4-4.5):
* densify_and_clone: parents = rows of selected_pts_mask over N0; children appended at
  N0 + r in ascending parent order -> clone events (parent id, new id).
* densify_and_split: parents q_r of selected_pts_mask over N1; children appended as "all
  first samples, then all second samples" (q_r -> N1 + r and N1 + K + r) -> split events;
  then prune_points(prune_filter) removes the parents: the parent's end is the split,
  no prune event is recorded for it.
* prune_points(mask) outside a split: prune events (id, -1); survivors keep their order.

The selection masks are local variables of the trainer's methods, so the wrappers
recompute them with the trainer's own formulas on the same state just before calling the
original, and check them against what densification_postfix receives (counts, and for
clones the copied positions). A mismatch (a modified trainer) gives a warning and the new
rows get fresh ids without events.
"""

from .tracking import CLONE, SPLIT, IdTracker

__all__ = ["GaussianModelTracker", "track_3dgs"]


class GaussianModelTracker(IdTracker):
    """Tracks the ids of one GaussianModel; created by track_3dgs()."""

    _METHODS = ("densify_and_clone", "densify_and_split", "prune_points", "densification_postfix")

    def __init__(self, gaussians, logger):
        super().__init__(logger)
        self.g = gaussians
        self._pending = None  # ("clone" | "split", mask, n_per_parent)
        self._in_split = False
        self._originals = {}

    # -- model access --------------------------------------------------------------------
    def count(self):
        return int(self.g.get_xyz.shape[0])

    def _device(self):
        return self.g.get_xyz.device

    # -- masks as the trainer computes them ----------------------------------------------
    def _clone_mask(self, grads, grad_threshold, scene_extent):
        import torch

        g = self.g
        mask = torch.where(torch.norm(grads, dim=-1) >= grad_threshold, True, False)
        return torch.logical_and(
            mask, torch.max(g.get_scaling, dim=1).values <= g.percent_dense * scene_extent)

    def _split_mask(self, grads, grad_threshold, scene_extent):
        import torch

        g = self.g
        n_init = g.get_xyz.shape[0]
        padded = torch.zeros((n_init,), device=grads.device)
        padded[: grads.shape[0]] = grads.squeeze()
        mask = torch.where(padded >= grad_threshold, True, False)
        return torch.logical_and(
            mask, torch.max(g.get_scaling, dim=1).values > g.percent_dense * scene_extent)

    # -- wrappers ------------------------------------------------------------------------
    def install(self):
        if self._originals:
            return self
        g = self.g
        for name in self._METHODS:
            if not hasattr(g, name):
                raise AttributeError(f"the model has no method {name}: not a 3DGS GaussianModel")
            self._originals[name] = getattr(g, name)
        orig = self._originals
        tracker = self

        def densify_and_clone(grads, grad_threshold, scene_extent, *args, **kwargs):
            def before():
                mask = tracker._clone_mask(grads, grad_threshold, scene_extent)
                tracker._pending = ("clone", mask, 1)

            try:
                return tracker.guarded("densify_and_clone", orig["densify_and_clone"],
                                       (grads, grad_threshold, scene_extent) + args, kwargs,
                                       before, lambda state, result: None)
            finally:
                tracker._pending = None

        def densify_and_split(grads, grad_threshold, scene_extent, *args, **kwargs):
            def before():
                n = kwargs.get("N", args[0] if args else 2)
                mask = tracker._split_mask(grads, grad_threshold, scene_extent)
                tracker._pending = ("split", mask, int(n))
                tracker._in_split = True

            try:
                return tracker.guarded("densify_and_split", orig["densify_and_split"],
                                       (grads, grad_threshold, scene_extent) + args, kwargs,
                                       before, lambda state, result: None)
            finally:
                tracker._pending = None
                tracker._in_split = False

        def densification_postfix(new_xyz, *args, **kwargs):
            def before():
                ids = tracker.ids
                n_new = int(new_xyz.shape[0])
                pending = tracker._pending
                if pending is None:
                    return len(ids), n_new, None, None
                kind, mask, per = pending
                selected = ids[mask.to(ids.device)]
                if len(selected) * per != n_new:
                    tracker._warn(
                        f"{kind} at iteration {tracker.logger.iteration}: the trainer added {n_new} "
                        f"Gaussians where its {kind} rule selects {len(selected)} parents x {per}; "
                        "recording them without parents")
                    return len(ids), n_new, None, None
                if kind == "clone" and n_new > 0 and not bool(
                        (new_xyz.detach() == tracker.g.get_xyz.detach()[mask]).all()):
                    tracker._warn(
                        f"clone at iteration {tracker.logger.iteration}: the new Gaussians are "
                        "not copies of the rows the clone rule selects; recording them without parents")
                    return len(ids), n_new, None, None
                # Children order "all first samples, then all second samples".
                return len(ids), n_new, kind, selected.repeat(per) if per > 1 else selected

            def after(state, result):
                m, n_new, kind, parents = state
                added = tracker.count() - m
                if parents is not None and added != n_new:
                    tracker._warn(f"densification_postfix added {added} Gaussians for {n_new} "
                                  "new rows; recording them without parents")
                    parents = None
                if parents is None:
                    tracker.append_orphans(added)
                else:
                    tracker.append_children(CLONE if kind == "clone" else SPLIT, parents)

            return tracker.guarded("densification_postfix", orig["densification_postfix"],
                                   (new_xyz,) + args, kwargs, before, after)

        def prune_points(mask, *args, **kwargs):
            def before():
                mask_ = mask.to(tracker.ids.device).bool()
                if len(mask_) != len(tracker.ids):
                    raise ValueError(f"a mask of {len(mask_)} rows for {len(tracker.ids)} Gaussians")
                return mask_

            def after(mask_, result):
                # Inside a split the removed rows are the split parents: their end is the split.
                tracker.remove_rows(mask_, record=not tracker._in_split)

            return tracker.guarded("prune_points", orig["prune_points"], (mask,) + args, kwargs,
                                   before, after)

        g.densify_and_clone = densify_and_clone
        g.densify_and_split = densify_and_split
        g.densification_postfix = densification_postfix
        g.prune_points = prune_points
        return self

    def uninstall(self):
        for name in self._originals:
            try:
                delattr(self.g, name)  # the class methods show through again
            except AttributeError:
                pass
        self._originals = {}

    # -- snapshots -----------------------------------------------------------------------
    def write_snapshot(self, iteration):
        import torch

        g = self.g
        ids = self._ensure()
        self._check("a snapshot")
        with torch.no_grad():
            if self.logger.snapshot_sh_rest:
                sh = torch.cat([g._features_dc, g._features_rest], dim=1)
            else:
                sh = g._features_dc
            grad_accum = denom = None
            if self.logger.snapshot_statistics and hasattr(g, "xyz_gradient_accum"):
                d = g.denom.reshape(-1)
                grad_accum = g.xyz_gradient_accum.reshape(-1) / d
                grad_accum[grad_accum.isnan()] = 0.0
                denom = d
            self.logger.writer.write_snapshot(
                iteration, ids, g._xyz, g._scaling, g._rotation, g._opacity, sh,
                grad_accum=grad_accum, denom=denom)


def track_3dgs(gaussians, logger, snapshot_initial=True):
    """Starts tracking a GaussianModel (call after Scene(...) has created its Gaussians):
    wraps its densification methods and, by default, writes a snapshot at iteration 0
    (logger.start_iteration for a resumed run)."""
    tracker = GaussianModelTracker(gaussians, logger).install()
    tracker._ensure()
    if snapshot_initial:
        logger.snapshot(logger.start_iteration)
    return tracker
