"""Checks `vis4gs repair SCENE CLEANED` (issue 20) on a scene with cameras and images built
from the demo log without Vis4GS: the last snapshot as a 3DGS PLY with an id property (written
here with numpy), the training cameras as cameras.json (LogCamerasJson.py) and the embedded
/images/<name> ([H,W,3] u8) as PNG files (written here with zlib: lossless 8-bit, so the
training images are the same bytes on both paths).

- `vis4gs repair SCENE.ply CLEANED --cameras=... --images=... --iteration=SOURCE` and
  `vis4gs repair LOG CLEANED` (both 2 iterations; CLEANED is analyze --select="views<=3"
  --delete's cleaned.ply) agree on every training row of repair.csv (the scene has only the
  training cameras: the trainer's cameras.json holds no test views). The source and deleted
  columns only involve the same float32 parameters and 8-bit images (PNG is lossless), the
  training sees the same cameras in the same order at the same iteration numbers, and the
  poses survive cameras.json's float64 centre and R^T: the figures are identical, digit for
  digit;
- the scene run's repaired.h5 holds exactly the deletion as prune events at SOURCE;
- the Python layer: vis4gs.open(SCENE.ply, cameras=, images=).repair(ids=deleted) gives the
  command's figures before and after the deletion.
- errors: no cameras, an image folder lacking a camera's image, ids not a subset name the file.

Usage: CheckRepairScene.py VIS4GS LOG.h5 ANALYZE_DIR OUTPUT_DIR
"""
import csv
import os
import shutil
import struct
import subprocess
import sys
import zlib

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CleanupReport import read_ply  # noqa: E402
import LogCamerasJson  # noqa: E402

problems = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        problems.append(what)


def write_png(path, rgb):
    """A plain 8-bit RGB PNG (no filter), independent of Vis4GS's and VTK's writers."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def write_scene_ply(path, snap):
    """The snapshot as the original trainer's PLY (f_rest channel-major) plus an int id."""
    pos = snap["position"][()]
    sh = snap["sh"][()]
    n, k, _ = sh.shape
    names = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"]
    names += [f"f_rest_{i}" for i in range(3 * (k - 1))]
    names += ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    rest = sh[:, 1:, :].transpose(0, 2, 1).reshape(n, -1)
    cols = np.concatenate([pos, np.zeros((n, 3), np.float32), sh[:, 0, :], rest,
                           snap["opacity_logit"][()][:, None], snap["log_scale"][()],
                           snap["rotation"][()]], axis=1).astype("<f4")
    dtype = [(name, "<f4") for name in names] + [("id", "<i4")]
    rows = np.empty(n, dtype=dtype)
    for i, name in enumerate(names):
        rows[name] = cols[:, i]
    rows["id"] = snap["id"][()].astype(np.int32)
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % n +
              "".join(f"property float {name}\n" for name in names) +
              "property int id\nend_header\n")
    with open(path, "wb") as f:
        f.write(header.encode() + rows.tobytes())


def read_csv(path):
    with open(path) as f:
        return {(r["view"], r["split"]): r for r in csv.DictReader(f)}


def run(args, expect_ok=True):
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if expect_ok and result.returncode != 0:
        print(f"FAILED: {' '.join(args)} exited with {result.returncode}")
        sys.exit(1)
    return result


def main(vis4gs_exe, log_path, analyze, folder):
    os.makedirs(os.path.join(folder, "images"), exist_ok=True)
    cleaned = os.path.join(analyze, "cleaned.ply")
    with h5py.File(log_path, "r") as log:
        last = sorted(log["snapshots"].keys())[-1]
        source = int(last)
        snap = log["snapshots"][last]
        src_ids = snap["id"][()].astype(np.int64)
        write_scene_ply(os.path.join(folder, "scene.ply"), snap)
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in log["cameras"]["name"]]
        for name in names:
            write_png(os.path.join(folder, "images", name + ".png"), log["images"][name][()])
    LogCamerasJson.main(log_path, os.path.join(folder, "cameras.json"))
    scene = os.path.join(folder, "scene.ply")
    cams = os.path.join(folder, "cameras.json")
    images = os.path.join(folder, "images")
    deleted = np.setdiff1d(src_ids, read_ply(cleaned)["id"].astype(np.int64))

    common = [cleaned, "--iterations=2", "--threads=2"]
    run([vis4gs_exe, "repair", scene] + common + [f"--cameras={cams}", f"--images={images}",
        f"--iteration={source}", f"--output={folder}/scene-run"])
    run([vis4gs_exe, "repair", log_path] + common + [f"--output={folder}/log-run"])
    from_scene = read_csv(os.path.join(folder, "scene-run", "repair.csv"))
    from_log = read_csv(os.path.join(folder, "log-run", "repair.csv"))
    train_rows = [key for key in from_log if key[1] == "train"]
    check(sorted(from_scene) == sorted(train_rows),
          f"the scene run has the log run's {len(train_rows)} training rows (mean + views)")
    worst = 0.0
    for key in train_rows:
        for column, value in from_log[key].items():
            if column in ("view", "split"):
                continue
            a, b = float(value), float(from_scene[key][column])
            worst = max(worst, abs(a - b) / max(1.0, abs(a)))
    print(f"largest relative difference between the two repair.csv: {worst:.3g}")
    check(worst == 0.0, "the scene run's training figures equal the log run's exactly")
    mean = from_scene[("mean", "train")]
    print("scene run: training PSNR source %s, deleted %s, repaired %s" %
          (mean["psnr_source"], mean["psnr_deleted"], mean["psnr_repaired"]))

    with h5py.File(os.path.join(folder, "scene-run", "repaired.h5"), "r") as out:
        ev = {k: out["events"][k][()] for k in ("iteration", "kind", "parent", "child")}
        check(len(ev["kind"]) == deleted.size and np.all(ev["kind"] == 3) and
              np.all(ev["iteration"] == source) and np.all(ev["child"] == -1) and
              np.array_equal(np.sort(ev["parent"]), deleted),
              f"repaired.h5: {len(ev['kind'])} prune events at iteration {source}, exactly the "
              f"{deleted.size} ids cleaned.ply lacks")
        snaps = sorted(out["snapshots"].keys())
        check(np.array_equal(out["snapshots"][snaps[0]]["id"][()], src_ids) and
              int(snaps[-1]) == source + 2,
              f"its snapshots {snaps[0]} (the scene's ids) and {snaps[-1]}")

    # The Python layer on the same scene file.
    import vis4gs
    # A scene file opens at iteration None; iteration=SOURCE makes Scene.repair continue the
    # same iteration numbers as the command's --iteration=SOURCE, so every training figure of
    # the two runs is the same (as repair.csv prints it), the repaired one included.
    opened = vis4gs.open(scene, cameras=cams, images=images, id_property="id")
    repaired = opened.repair(ids=deleted, iterations=2, threads=2, iteration=source,
                             output=os.path.join(folder, "python-run.h5"))
    fig = repaired.figures
    row = list(fig["view"]).index("mean")
    differ = [c for c in fig if c not in ("view", "split") and "%.9g" % fig[c][row] != mean[c]]
    print(f"Python Scene.repair(iteration={source}) vs the command, training means: "
          f"repaired PSNR {fig['psnr_repaired'][row]:.4f} dB, columns that differ: {differ}")
    check(not differ, "Scene.repair(iteration=SOURCE) on vis4gs.open(SCENE.ply, cameras, images) "
          "gives the command's training means, repaired included")
    with h5py.File(os.path.join(folder, "python-run.h5"), "r") as out:
        events = out["events"]["iteration"][()]
        snaps = sorted(int(k) for k in out["snapshots"].keys())
    check(repaired.iteration == source + 2 and snaps == [source, source + 2] and
          events.size == deleted.size and np.all(events == source),
          f"its log continues iteration {source}: snapshots {snaps}, the deletion at {source}")

    # Errors name the file and the problem.
    lonely = os.path.join(folder, "lonely")
    os.makedirs(lonely, exist_ok=True)
    # A copy: the scene stays for the view's clean-up test (CheckCleanupScene.py).
    shutil.copyfile(scene, os.path.join(lonely, "scene.ply"))
    r = run([vis4gs_exe, "repair", os.path.join(lonely, "scene.ply"), cleaned,
             f"--output={folder}/no-cameras"], expect_ok=False)
    check(r.returncode == 1 and "scene.ply: no cameras found" in r.stdout,
          "no cameras: exit 1 naming the scene")
    partial = os.path.join(folder, "partial")
    os.makedirs(partial, exist_ok=True)
    r = run([vis4gs_exe, "repair", os.path.join(lonely, "scene.ply"), cleaned,
             f"--cameras={cams}", f"--images={partial}", f"--output={folder}/no-images"],
            expect_ok=False)
    check(r.returncode == 1 and f"{partial}: no image for camera" in r.stdout,
          "an image folder without the camera's image: exit 1 naming the folder and camera")
    r = run([vis4gs_exe, "repair", cleaned, os.path.join(lonely, "scene.ply"),
             f"--cameras={cams}", f"--images={images}", f"--output={folder}/not-subset"],
            expect_ok=False)
    check(r.returncode == 1 and "scene.ply: holds" in r.stdout and "ids that" in r.stdout,
          "ids not a subset: exit 1 naming the file")
    check(not os.path.exists(os.path.join(folder, "not-subset", "repaired.h5")),
          "nothing written on an error")

    if problems:
        print("FAILED: " + "; ".join(problems))
        sys.exit(1)
    print("repair of a scene file agrees")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit("usage: CheckRepairScene.py VIS4GS LOG.h5 ANALYZE_DIR OUTPUT_DIR")
    main(*sys.argv[1:])
