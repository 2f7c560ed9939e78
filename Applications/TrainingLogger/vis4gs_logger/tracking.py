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
        #: messages of the lineage breaks recorded so far
        self.breaks = []
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
        """Keeps the ids in step with the model's rows: when they differ (an operation
        changed the rows outside the wrapped methods) the lineage is broken there, recorded
        in /lineage_breaks, and the training goes on (see lineage_break)."""
        n = self.count()
        if self.ids is not None and len(self.ids) != n:
            self.lineage_break(where, n)

    def lineage_break(self, where, rows=None, placed=None):
        """Records a loss of lineage and starts new roots for the rows it cannot place.

        Rows added at the end (more rows than ids, the way every trainer appends) keep the
        ids of the rows before them and the appended rows become new roots; otherwise
        (rows removed, or ``placed=0``: the logger's own bookkeeping failed) no row can be
        placed: every tracked id ends here and every row becomes a new root. Warns once
        per tracker; each break is a row of /lineage_breaks."""
        import torch

        ids = self._ensure()
        n = self.count() if rows is None else int(rows)
        m = len(ids)
        kept = (m if n >= m else 0) if placed is None else int(placed)
        new = self._new_ids(n - kept)
        self.ids = torch.cat([ids[:kept], new])
        first = int(new[0]) if len(new) else self.next_id
        message = (f"lineage lost at iteration {self.logger.iteration} after {where}: the "
                   f"model has {n} Gaussians but {m} ids were tracked; {n - kept} rows start "
                   "new roots (an operation changed the model without going through the "
                   "wrapped methods)")
        self.breaks.append(message)
        if len(self.breaks) == 1:
            self._warn(message + "; recorded in /lineage_breaks, further breaks without a warning")
        self.logger.writer.append_lineage_break(
            self.logger.iteration, tracked=m, rows=n, kept=kept, first_new_id=first,
            new_roots=n - kept, where=where)

    def guarded(self, where, fn, args, kwargs, before, after):
        """Calls the trainer's ``fn`` between the tracker's ``before()`` and
        ``after(state, result)``. An exception of fn is the trainer's and propagates; one of
        the bookkeeping becomes a warning and a lineage break (never an exception into the
        training loop)."""
        t0 = time.perf_counter()
        try:
            self._check("an operation before " + where)
            state = before()
        except Exception as error:  # noqa: BLE001 - the training must go on
            self.logger.time_spent_s += time.perf_counter() - t0
            result = fn(*args, **kwargs)  # first: an error of the trainer's op is its own
            self._failed(where, error)
            return result
        self.logger.time_spent_s += time.perf_counter() - t0
        result = fn(*args, **kwargs)
        t0 = time.perf_counter()
        try:
            after(state, result)
            self._check(where)
        except Exception as error:  # noqa: BLE001
            self._failed(where, error)
        self.logger.time_spent_s += time.perf_counter() - t0
        return result

    def _failed(self, where, error):
        self._warn(f"the bookkeeping of {where} failed at iteration {self.logger.iteration} "
                   f"({type(error).__name__}: {error}); the lineage is broken there")
        try:
            self.lineage_break(where + " (bookkeeping failed)", placed=0)
        except Exception as again:  # noqa: BLE001 - e.g. the log is closed
            self.warnings.append(f"could not record the lineage break: {again}")

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

