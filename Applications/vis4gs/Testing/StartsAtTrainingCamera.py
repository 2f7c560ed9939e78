"""`vis4gs view` starts at the first training camera, even when a test camera comes first in
the log's camera table (issue 33).

Copies the demo log with its camera rows rotated so that the test cameras come first (h5py,
every /cameras dataset permuted the same way), opens the copy with `vis4gs view --benchmark`
and reads which table camera the scene view stands on: it must be the first training row of
the copy, at its centre.

Usage: StartsAtTrainingCamera.py VIS4GS LOG WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np


def main(vis4gs, log, work):
    os.makedirs(work, exist_ok=True)
    copy = os.path.join(work, "test-cameras-first.h5")
    shutil.copyfile(log, copy)
    with h5py.File(copy, "r+") as f:
        cams = f["cameras"]
        split = cams["split"][:]
        order = np.concatenate([np.flatnonzero(split != 0), np.flatnonzero(split == 0)])
        for name in list(cams.keys()):
            data = cams[name][:]
            if data.shape[:1] == split.shape:
                del cams[name]
                cams.create_dataset(name, data=data[order])
        first_train = int(np.flatnonzero(cams["split"][:] == 0)[0])
        names = [n.decode() if isinstance(n, bytes) else n for n in cams["name"][:]]
    if first_train == 0:
        print("FAILED: the copy still starts with a training camera")
        return 1
    run = subprocess.run([vis4gs, "view", copy, "--benchmark", "--resolution=800,600"],
                         capture_output=True, text=True, timeout=600)
    sys.stdout.write(run.stdout)
    sys.stderr.write(run.stderr)
    if run.returncode != 0:
        print(f"FAILED: vis4gs view exited with {run.returncode}")
        return 1
    m = re.search(r"scene camera at start: row (\d+) \(([^,]+), (\w+)\), (\S+) from its centre",
                  run.stdout)
    if not m:
        print("FAILED: no start camera reported")
        return 1
    row, name, split, distance = int(m.group(1)), m.group(2), m.group(3), float(m.group(4))
    if row != first_train or name != names[first_train] or split != "train" or distance > 1e-6:
        print(f"FAILED: starts at row {row} ({name}, {split}) {distance} from it, expected "
              f"row {first_train} ({names[first_train]})")
        return 1
    print(f"starts at the first training camera, row {row} ({name}), after "
          f"{first_train} test cameras")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: StartsAtTrainingCamera.py VIS4GS LOG WORKDIR")
    sys.exit(main(*sys.argv[1:]))
