# SPDX-License-Identifier: BSD-3-Clause
"""Stable Gaussian ids (DESIGN §3): the initial Gaussians are 0..N0-1, every new Gaussian
gets the next unused id, ids are never reused. One int64 id per row of the model, kept on
the model's device and permuted exactly as the trainer permutes its rows."""

import time

from .writer import CLONE, PRUNE, SPLIT  # noqa: F401 (re-exported to the trackers)

__all__ = ["IdTracker"]


class IdTracker:
    """Base of the trainer-specific trackers: holds ``ids`` (a torch int64 tensor)."""

    def __init__(self, logger):
        self.logger = logger
        self.ids = None
        self.next_id = 0
        self.warnings = []
        logger.tracker = self

    # subclasses: count(), current arrays for snapshots, install()/uninstall()
    def count(self):
        raise NotImplementedError

    def _device(self):
        raise NotImplementedError

    def _ensure(self):
        import torch

        if self.ids is None:
            n = self.count()
            self.ids = torch.arange(n, dtype=torch.int64, device=self._device())
            self.next_id = n
        return self.ids

    def _check(self, where):
        n = self.count()
        if self.ids is not None and len(self.ids) != n:
            raise RuntimeError(
                f"{self.logger.path}: id tracking lost sync after {where}: the model has {n} "
                f"Gaussians but {len(self.ids)} ids are tracked (an operation changed the "
                "model without going through the wrapped methods)")

    def _warn(self, message):
        import warnings

        self.warnings.append(message)
        warnings.warn("vis4gs_logger: " + message, RuntimeWarning, stacklevel=3)

    def _record(self, kind, parents, children=None):
        t0 = time.perf_counter()
        self.logger.writer.append_events(self.logger.iteration, kind, parents, children)
        self.logger.time_spent_s += time.perf_counter() - t0

    def _new_ids(self, n):
        import torch

        new = torch.arange(self.next_id, self.next_id + n, dtype=torch.int64, device=self.ids.device)
        self.next_id += n
        return new

    # -- operations --------------------------------------------------------------------
    def append_children(self, kind, parent_ids):
        """Rows appended at the end, child i of parent_ids[i]; records clone/split events."""
        import torch

        ids = self._ensure()
        new = self._new_ids(len(parent_ids))
        self.ids = torch.cat([ids, new])
        self._record(kind, parent_ids, new)
        return new

    def append_orphans(self, n):
        """Rows appended with no known parent (recorded nowhere; a warning says why)."""
        import torch

        ids = self._ensure()
        new = self._new_ids(n)
        self.ids = torch.cat([ids, new])
        return new

    def remove_rows(self, mask, record=True):
        """Removes the rows where mask is True (order kept); records prunes if asked."""
        ids = self._ensure()
        mask = mask.to(ids.device).bool()
        if record and bool(mask.any()):
            self._record(PRUNE, ids[mask])
        self.ids = ids[~mask]

    def write_snapshot(self, iteration):
        raise NotImplementedError

    def uninstall(self):
        pass

