"""Every writer on a full file system and in a read-only folder (issue 35, part 3).

  CheckFullDisk.py WRITER VIS4GS WORKDIR SOURCE_DIR

For WRITER (one of WRITERS below) the script mounts a small tmpfs in WORKDIR and, in it:

1. runs the writer once, which must succeed: its outputs are "what was there before";
2. fills the file system (a filler file), leaving FREE bytes, and runs the writer again, for
   FREE = 0 (the first write fails) and FREE = a quarter of what the first run wrote (a later
   write fails, after some files were written);
3. remounts the file system read-only and runs it again.

Each failing run must exit with status 1 (a failure the program explains: not a crash, not 0;
the Python logger instead lets its training end, status 0, and warns), print a message naming
a path inside the mount and the problem ("No space left on device", "Read-only file system"),
leave no file behind (no partial output, no temporary) and leave the first run's files byte for
byte as they were. The Python training logger (FullDiskTraining.py, with either writer) is
also run with the disk filling while its training runs (LOGGER_MOMENTS): the same, with one
warning and no report of HDF5 meeting the full disk.

Mounting needs root (CI runs as root; a read-only folder has to be a read-only mount, since root
ignores permission bits). Without the permission the script exits 77 (skipped) saying so.
"""
import hashlib
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from Checks import check, finish  # noqa: E402

ENOSPC = os.strerror(28)  # "No space left on device"
EROFS = os.strerror(30)  # "Read-only file system"


def run(argv, env=None):
    started = time.time()
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=env, timeout=900)
    return p.returncode, p.stdout, time.time() - started


def mount_tmpfs(point, size):
    os.makedirs(point, exist_ok=True)
    p = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "vis4gs-full-disk", point],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode == 0, p.stdout.strip()


def umount(point):
    subprocess.run(["umount", point], check=False)


def snapshot(folder, skip=()):
    """{relative path: sha256} of every file under @p folder (hidden ones too), and the folders."""
    files = {}
    for root, dirs, names in os.walk(folder):
        for d in dirs:
            files[os.path.relpath(os.path.join(root, d), folder) + "/"] = "folder"
        for n in names:
            path = os.path.join(root, n)
            rel = os.path.relpath(path, folder)
            if rel in skip:
                continue
            with open(path, "rb") as f:
                files[rel] = hashlib.sha256(f.read()).hexdigest()
    return files


def used_bytes(folder):
    total = 0
    for root, _, names in os.walk(folder):
        for n in names:
            total += os.path.getsize(os.path.join(root, n))
    return total


def fill(point, free):
    """Fills the file system at @p point with one file, then gives back @p free bytes."""
    filler = os.path.join(point, "filler")
    block = b"\0" * 65536
    with open(filler, "wb", buffering=0) as f:
        for chunk in (65536, 4096, 1):
            data = block[:chunk]
            try:
                while True:
                    f.write(data)
            except OSError:
                pass
    size = os.path.getsize(filler)
    os.truncate(filler, max(0, size - free))
    return "filler"


#: when the disk fills while the training logger's loop runs (FullDiskTraining.py): during
#: the steps (between snapshots), inside a snapshot (after its first array), before close()
#: (which writes the final snapshot)
LOGGER_MOMENTS = ("step:23", "snapshot:10", "snapshot:35", "close")
#: HDF5's own reports of a failed write: the logger must stop before HDF5 meets a full disk
#: (after a failed write HDF5 1.10 crashes the process when it closes the file)
HDF5_FAILED = ("HDF5-DIAG", "Driver write request failed", "slist already enabled",
               "Segmentation fault", "Fatal Python error")


# ------------------------------------------------------------------------------------------
# The writers. Each is (tmpfs size, prepare(inputs folder) -> None, command(output) -> argv,
# output(mount) -> the path the command is given). Inputs live outside the mount.
def writers(vis4gs, work, source):
    demo_log = os.path.join(source, "Data", "Demo", "vis4gs-demo.h5")
    demo_scene = os.path.join(source, "Data", "Scenes", "demo.json")
    inputs = os.path.join(work, "inputs")

    def cleaned():
        """cleaned.ply of the demo log (analyze --select --delete), the input of repair."""
        path = os.path.join(inputs, "cleaned.ply")
        if not os.path.exists(path):
            rc, out, _ = run([vis4gs, "analyze", demo_log, "--scores=coverage",
                              "--select=views<=3", "--delete", "--overlay-views=0", "--top=1",
                              "--threads=2", "--output=" + inputs])
            if rc != 0:
                print(out)
                sys.exit("FAILED: could not make the cleaned scene for repair")
        return path

    logger_tests = os.path.join(source, "Applications", "TrainingLogger", "tests")
    here = os.path.dirname(os.path.abspath(__file__))

    def training(writer):
        return ("16m", lambda: None, lambda out: [
            sys.executable, os.path.join(here, "FullDiskTraining.py"), out + "/run.h5",
            logger_tests, writer], 0, "the training ended at step 52", LOGGER_MOMENTS)

    def convert(suffix):
        """vis4gs convert of the demo log's last snapshot into one output format."""
        return ("16m", lambda: None, lambda out: [
            vis4gs, "convert", demo_log, out + suffix])

    return {
        # scores.ply, scores.csv, report.html and an overlay image
        "analyze": ("32m", lambda: None, lambda out: [
            vis4gs, "analyze", demo_log, "--scores=coverage,shape", "--overlay-views=1",
            "--top=1", "--threads=2", "--output=" + out]),
        # the clean-up: selection.csv, selection-rule.txt, cleaned.ply, before-after.csv
        "cleanup": ("32m", lambda: None, lambda out: [
            vis4gs, "analyze", demo_log, "--scores=coverage", "--select=views<=3", "--delete",
            "--report", "--overlay-views=0", "--top=1", "--threads=2", "--output=" + out]),
        # the batch demo: analyze's outputs plus root-cause.txt
        "demo": ("48m", lambda: None, lambda out: [
            vis4gs, "demo", "--no-gui", "--top=1", "--output=" + out]),
        # a PNG (a scene file: the cleaned demo scene, seen from its bounds)
        "render": ("1m", cleaned, lambda out: [
            vis4gs, "render", os.path.join(inputs, "cleaned.ply"), "--resolution=64,64",
            "--output=" + out + ".png"]),
        "compare": ("16m", lambda: None, lambda out: [
            vis4gs, "compare", demo_log, demo_log, "--iteration-a=1600", "--output=" + out]),
        # repaired.h5 and repair.csv
        "repair": ("32m", cleaned, lambda out: [
            vis4gs, "repair", demo_log, os.path.join(inputs, "cleaned.ply"), "--iterations=2",
            "--warmup=0", "--threads=2", "--output=" + out]),
        # a training log written while the trainer runs
        "train": ("16m", lambda: None, lambda out: [
            vis4gs, "train", demo_scene, "--resolution=32", "--iterations=20",
            "--snapshot-interval=10", "--threads=2", "--output=" + out + "/run.h5"]),
        # the scene writer of the Python package (vtkGaussianPLYWriter, Core's PLY writer)
        "ply-writer": ("16m", lambda: None, lambda out: [
            os.path.join(os.path.dirname(vis4gs), "vis4gs-python"), "-c",
            "import sys, vis4gs\n"
            "r = vis4gs.vtkGaussianTrainingLogReader(); r.SetFileName(sys.argv[1]); r.Update()\n"
            "import os; os.makedirs(sys.argv[2], exist_ok=True)\n"
            "w = vis4gs.vtkGaussianPLYWriter(); w.SetInputConnection(r.GetOutputPort(0))\n"
            "w.SetFileName(sys.argv[2] + '/scene.ply')\n"
            "sys.exit(0 if w.Write() == 1 else 1)\n", demo_log, out]),
        # every format vis4gs convert writes
        "convert-ply": convert(".ply"),
        "convert-compressed-ply": convert(".compressed.ply"),
        "convert-splat": convert(".splat"),
        "convert-spz": convert(".spz"),
        "convert-glb": convert(".glb"),
        "convert-gltf": convert(".gltf"),
        # the Python training logger in a stand-in gsplat training loop (FullDiskTraining.py),
        # with its default writer (SWMR, format version 2) and format version 1: the training
        # must go on (exit status 0, its last line printed) whatever happens to the log,
        # also when the disk fills while it runs
        "logger": training("swmr"),
        "logger-v1": training("v1"),
    }


def main():
    if len(sys.argv) != 5:
        sys.exit("usage: CheckFullDisk.py WRITER VIS4GS WORKDIR SOURCE_DIR")
    name, vis4gs, work, source = sys.argv[1:5]
    table = writers(vis4gs, work, source)
    if name not in table:
        sys.exit(f"FAILED: unknown writer {name} (one of {', '.join(table)})")
    # A writer that must fail says so with exit status 1; the logger must let its training
    # end normally (status 0, its last line printed) and only warn.
    size, prepare, command, status, ended, moments = (table[name] + (1, None, ()))[:6]
    os.makedirs(os.path.join(work, "inputs"), exist_ok=True)
    point = os.path.join(work, "mount")
    if os.path.ismount(point):
        umount(point)
    ok, why = mount_tmpfs(point, size)
    if not ok:
        print(f"skipped: cannot mount a tmpfs at {point} ({why or 'not permitted'}); the full-disk "
              "and read-only tests need root (or CAP_SYS_ADMIN), as CI has")
        sys.exit(77)
    try:
        prepare()
        out = os.path.join(point, "out")
        rc, text, seconds = run(command(out))
        if not check(rc == 0, f"{name}: the first run, with space, succeeds (status {rc}, "
                     f"{seconds:.1f} s)"):
            print(text)
            finish("")
        before = snapshot(point)
        written = used_bytes(point)
        print(f"{name}: the first run wrote {len(before)} entries, {written} bytes")

        # (label, bytes left free before the run or None: read-only, problem, the moment
        # the disk fills while the program runs)
        scenarios = [("full, 0 bytes free", 0, ENOSPC, None),
                     (f"full, {written // 4} bytes free", written // 4, ENOSPC, None),
                     ("read-only", None, EROFS, None)]
        scenarios += [(f"the disk fills at {m}", -1, ENOSPC, m) for m in moments]
        for label, free, problem, moment in scenarios:
            filler = None
            if free is None:
                subprocess.run(["mount", "-o", "remount,ro", point], check=True)
            elif free >= 0:
                filler = fill(point, free)
            else:
                filler = "filler"  # filled by the program itself (FullDiskTraining.py)
            rc, text, seconds = run(command(out) + ([moment] if moment else []))
            after = snapshot(point, skip=(filler,) if filler else ())
            what = f"{name}, {label}"
            check(rc == status, f"{what}: exit status {status} (got {rc})")
            if ended:
                check(ended in text, f"{what}: the program goes on to its end ('{ended}')")
            check(problem in text and point in text,
                  f"{what}: the message names a path in {point} and '{problem}'")
            if moments:  # the training logger: one warning, before HDF5 meets the full disk
                said = text.count(f"{problem}; logging stops")
                check(said == 1, f"{what}: one warning says logging stops (said {said} times)")
                hdf5 = [m for m in HDF5_FAILED if m in text]
                check(not hdf5, f"{what}: HDF5 never met the full disk (found {hdf5})")
            added = sorted(set(after) - set(before))
            check(not added, f"{what}: nothing left behind (found {added})")
            changed = sorted(k for k in before if after.get(k) != before[k])
            check(not changed, f"{what}: the first run's files are untouched (changed or gone: "
                  f"{changed})")
            if rc != status or problem not in text or point not in text or added or changed:
                print("--- its output:\n" + text[-3000:] + "\n---")
            if filler and os.path.exists(os.path.join(point, filler)):
                os.remove(os.path.join(point, filler))
            else:
                subprocess.run(["mount", "-o", "remount,rw", point], check=True)
    finally:
        umount(point)
    finish(f"{name}: fails cleanly on a full file system and in a read-only folder")


if __name__ == "__main__":
    main()
