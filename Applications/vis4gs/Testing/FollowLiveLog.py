# SPDX-License-Identifier: BSD-3-Clause
"""A training log read while `vis4gs train` writes it (issue 32 item 6).

`vis4gs train` writes its log as LOG.tmp in SWMR mode (renamed at the end): analyze reads the
.tmp, `vis4gs view LOG --follow` finds it. While it trains: `vis4gs analyze` on the
live log succeeds (twice, the second seeing at least the first's snapshot), and `vis4gs view
LOG --follow` (under Xvfb) reports new snapshots as they come ("following LOG: S snapshots"
lines, S increasing). Then the trainer is SIGKILL-ed: the log still opens, with at least the
snapshots seen before. Usage: FollowLiveLog.py VIS4GS SCENE.json WORKDIR"""

import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

vis4gs, scene, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
log = os.path.join(work, "run.h5")
live = log + ".tmp"  # the trainer's file until it ends


def fail(message):
    print("FAILED:", message)
    sys.exit(1)


def analyze(tag):
    """The iteration of the snapshot `vis4gs analyze` read from the live log."""
    out = subprocess.run([vis4gs, "analyze", live, "--scores=shape",
                          "--output=" + os.path.join(work, tag)],
                         capture_output=True, text=True, timeout=600)
    if out.returncode != 0:
        fail(f"vis4gs analyze on the live log ({tag}): status {out.returncode}\n"
             f"{out.stdout}{out.stderr}")
    found = re.search(r"snapshot of iteration (\d+),", out.stdout)
    if not found:
        fail(f"analyze ({tag}) names no snapshot:\n{out.stdout}")
    return int(found.group(1))


trainer = subprocess.Popen([vis4gs, "train", scene, "--resolution=32", "--iterations=1000000",
                            "--snapshot-interval=20", "--metrics-interval=10", "--threads=1",
                            "--output=" + log],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
viewer = None
try:
    # The log is followable after its first snapshot (iteration 0).
    deadline = time.monotonic() + 300
    first = None
    while first is None:
        if trainer.poll() is not None:
            fail("vis4gs train ended: " + trainer.stdout.read())
        if time.monotonic() > deadline:
            fail("no readable log in 5 minutes")
        time.sleep(1)
        if os.path.exists(live):
            probe = subprocess.run([vis4gs, "analyze", live, "--scores=shape",
                                    "--output=" + os.path.join(work, "probe")],
                                   capture_output=True, text=True, timeout=600)
            if probe.returncode == 0:
                first = analyze("first")
    print(f"analyze on the live log: snapshot {first}")

    viewer = subprocess.Popen([vis4gs, "view", log, "--follow", "--resolution=800,600"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seen = []  # (seconds, snapshots, last iteration)
    start = time.monotonic()

    def read_viewer():
        for line in viewer.stdout:
            m = re.search(r"following .*: (\d+) snapshots \(last (-?\d+)\)", line)
            if m:
                seen.append((time.monotonic() - start, int(m.group(1)), int(m.group(2))))

    reader = threading.Thread(target=read_viewer, daemon=True)
    reader.start()
    while time.monotonic() - start < 240 and len({s[1] for s in seen}) < 3:
        if viewer.poll() is not None:
            fail(f"vis4gs view --follow ended with status {viewer.returncode}")
        time.sleep(0.5)
    counts = [s[1] for s in seen]
    print("vis4gs view --follow:", ", ".join(f"{t:.1f} s: {n} snapshots (last {i})"
                                               for t, n, i in seen))
    if len(set(counts)) < 3:
        fail("the following viewer did not show two new snapshots in 4 minutes")
    if counts != sorted(counts):
        fail(f"the snapshot counts went back: {counts}")

    second = analyze("second")
    print(f"analyze on the live log again: snapshot {second}")
    if second < first:
        fail(f"the second analyze read snapshot {second}, before the first's {first}")
finally:
    if viewer is not None and viewer.poll() is None:
        viewer.terminate()
        try:
            viewer.wait(timeout=30)
        except subprocess.TimeoutExpired:
            viewer.kill()
    if trainer.poll() is None:
        trainer.send_signal(signal.SIGKILL)
    trainer.wait()

after = analyze("killed")
print(f"analyze after SIGKILL of the trainer: snapshot {after}")
if after < max(second, seen[-1][2]):
    fail(f"the killed log ends at snapshot {after}, before one already seen")
print("followed a live log: analyze and view --follow saw it grow; the killed log reads")
