"""Checks the clean-up panel's "Fine-tune..." (issue 20) against `vis4gs repair` on the same
inputs. The view's self-test fine-tuned its previewed deletion of the demo log and wrote
cleanup-repaired.h5, cleanup-repair.csv (the panel's figures), cleanup-repair-deleted.csv (the
selection deleted) and cleanup-repair-cleaned.ply (the main window's "delete selection" export).
This runs `vis4gs repair LOG cleanup-repair-cleaned.ply` for as many iterations from the same
snapshot and checks, from the files (h5py, csv):
- the panel's log: its events are prune events at the source iteration naming exactly the
  deleted ids, and nothing else (densification off); so are repair's;
- both logs' snapshots are equal, dataset by dataset (the same fine-tune);
- the panel's figures equal repair.csv's, row by row, to repair.csv's printed precision.

Usage: CheckCleanupRepair.py VIS4GS LOG.h5 SHOTS_DIR OUTPUT_DIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from Checks import (check, finish, largest_relative_difference,  # noqa: E402
                    read_figures)



def prunes(log):
    kind = log["events"]["kind"][()]
    return (kind, log["events"]["iteration"][()], log["events"]["parent"][()])


def main(vis4gs_exe, log_path, shots, folder):
    panel_log = os.path.join(shots, "cleanup-repaired.h5")
    deleted = sorted(int(v) for v in
                     open(os.path.join(shots, "cleanup-repair-deleted.csv")).read().split()[1:])
    with h5py.File(panel_log, "r") as log:
        snaps = sorted(log["snapshots"].keys(), key=int)
        source, last = int(snaps[0]), int(snaps[-1])
        kind, iteration, parent = prunes(log)
    check(len(deleted) > 0 and len(kind) == len(deleted) and np.all(kind == 3) and
          np.all(iteration == source) and sorted(parent.tolist()) == deleted,
          f"the panel's log: {len(kind)} events, prune events at iteration {source} naming the "
          f"{len(deleted)} deleted ids, nothing else")

    result = subprocess.run([vis4gs_exe, "repair", log_path,
                             os.path.join(shots, "cleanup-repair-cleaned.ply"),
                             f"--iteration={source}", f"--iterations={last - source}",
                             "--threads=2", f"--output={folder}"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if result.returncode != 0:
        print(f"FAILED: vis4gs repair exited with {result.returncode}")
        sys.exit(1)
    repaired = os.path.join(folder, "repaired.h5")
    with h5py.File(panel_log, "r") as a, h5py.File(repaired, "r") as b:
        kind_b, iteration_b, parent_b = prunes(b)
        check(np.array_equal(kind, kind_b) and np.array_equal(iteration, iteration_b) and
              np.array_equal(parent, parent_b), "repair's log has the same prune events")
        names = sorted(b["snapshots"].keys(), key=int)
        same = names == snaps
        for name in names if same else []:
            for key in b["snapshots"][name].keys():
                same = same and np.array_equal(a["snapshots"][name][key][()],
                                               b["snapshots"][name][key][()])
        check(same, f"both logs' snapshots {names} are equal, dataset by dataset")

    panel = read_figures(os.path.join(shots, "cleanup-repair.csv"))
    command = read_figures(os.path.join(folder, "repair.csv"))
    columns = [c for c in next(iter(command.values())).keys() if c not in ("view", "split")]
    # repair.csv prints 9 significant digits.
    worst = largest_relative_difference(panel, command)
    check(panel.keys() == command.keys() and worst <= 1e-8,
          f"the panel's figures equal repair.csv's: {len(command)} rows, {len(columns)} columns "
          f"(largest relative difference {worst:.1e})")
    finish("the panel's fine-tune equals vis4gs repair")


if __name__ == "__main__":
    main(*sys.argv[1:5])
