"""vis4gs.Scene.refresh() on a training log a real writer process is writing (issue 32).

  TestFollowLog.py LOGGER_PACKAGE_DIR WORKDIR

The writer is the Python logger's TrainingLogWriter (format version 2, SWMR mode) in its own
process: step s appends a metrics row and flushes; every 4th step writes a snapshot of
500 + 10 s Gaussians whose x positions all equal s. The reader opens the log as soon as it has
a snapshot and calls refresh() until the writer ends: every refresh succeeds, the snapshot
list only grows, a Scene opened without iteration= is always at the latest snapshot with
that snapshot's Gaussians. At the end it holds every snapshot, and a Scene opened at an
iteration stays there. (One following reader per file and process: a second open of the file
in the process shares the first's HDF5 file, whose view of a live file can stay behind; see
TrainingLogReader::Refresh.)"""
import os
import shutil
import subprocess
import sys
import textwrap
import time

import numpy as np

import vis4gs

package, work = sys.argv[1:3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
log = os.path.join(work, "live.h5")
STEPS = 160
writer = subprocess.Popen([sys.executable, "-c", textwrap.dedent(f"""
    import sys, time, numpy as np
    sys.path.insert(0, {package!r})
    from vis4gs_logger import TrainingLogWriter
    w = TrainingLogWriter({log!r}, sh_degree=0)
    for s in range({STEPS}):
        w.append_metrics(s, num_gaussians=s, loss=1.0 / (s + 1))
        if s % 4 == 0:
            n = 500 + 10 * s
            pos = np.zeros((n, 3), np.float32)
            pos[:, 0] = s
            w.write_snapshot(s, np.arange(n), pos, np.full((n, 3), -4.0), np.tile([1.0, 0, 0, 0], (n, 1)),
                             np.zeros(n), np.full((n, 1, 3), 0.1))
        else:
            w.flush()
        time.sleep(0.03)
    w.close()
""")])


def fail(message):
    writer.kill()
    print("FAILED:", message)
    sys.exit(1)


deadline = time.monotonic() + 120
while True:
    try:
        latest = vis4gs.open(log)
        break
    except Exception as error:  # not created, or no snapshot yet
        if time.monotonic() > deadline or writer.poll() not in (None, 0):
            fail(f"the live log never opened: {error}")
        time.sleep(0.1)

refreshes, grew = 0, 0
history = [list(latest.iterations)]
while True:
    done = writer.poll() is not None
    new = latest.refresh()
    refreshes += 1
    grew += bool(new)
    its = latest.iterations
    if its[: len(history[-1])] != history[-1] or its != list(range(0, 4 * len(its), 4)):
        fail(f"the snapshot list went back or has a gap: {history[-1]} -> {its}")
    if new != its[len(history[-1]):]:
        fail(f"refresh() returned {new}, the list grew by {its[len(history[-1]):]}")
    history.append(list(its))
    if latest.iteration != its[-1]:
        fail(f"the following Scene is at {latest.iteration}, the latest snapshot is {its[-1]}")
    if len(latest) != 500 + 10 * latest.iteration or \
            not np.all(latest.positions[:, 0] == latest.iteration):
        fail(f"the Scene at {latest.iteration} does not hold that snapshot's Gaussians")
    if done:
        break
    time.sleep(0.05)
if writer.returncode != 0:
    fail(f"the writer ended with status {writer.returncode}")
if latest.iterations != list(range(0, STEPS, 4)):
    fail(f"after the writer closed: {latest.iterations}")
fixed = vis4gs.open(log, iteration=0)
if fixed.refresh() != [] or fixed.iteration != 0 or len(fixed) != 500:
    fail(f"a Scene opened at iteration 0 moved to {fixed.iteration}")
if grew < 3:
    fail(f"only {grew} of {refreshes} refreshes saw new snapshots: the reader did not follow")
print(f"{refreshes} refreshes while the writer ran, {grew} with new snapshots; "
      f"the Scene followed to iteration {latest.iteration}")
