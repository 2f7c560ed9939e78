"""Holds `vis4gs render` and `vis4gs analyze` to the special-value table
(Documentation/special-values.md) on a PLY: the per-reason counts they print must equal the
counts taken here with numpy from the file's raw floats, and the render of a copy with every
skipped Gaussian removed must be bit-identical to the render of the file (what is skipped
leaves no trace; what is drawn is drawn). Adds one Gaussian per "no answer" row first.

Usage: CheckSpecialValues.py VIS4GS INPUT.ply WORK_DIR   (uses INPUT's folder's cameras.json
when there is one, else render's default framing)
"""

import os
import re
import subprocess
import sys

import numpy as np


def read_ply(path):
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                sys.exit("%s: no end_header" % path)
            header += line
        lines = header.decode().splitlines()
        if "format binary_little_endian 1.0" not in lines:
            sys.exit("%s: only binary little-endian PLYs are checked here" % path)
        props = [l.split()[-1] for l in lines if l.startswith("property")]
        if any(l.split()[1] != "float" for l in lines if l.startswith("property")):
            sys.exit("%s: only float properties are checked here" % path)
        n = int([l for l in lines if l.startswith("element vertex")][0].split()[-1])
        data = np.frombuffer(f.read(4 * n * len(props)), dtype="<f4").reshape(n, len(props))
    return props, data.copy()


def write_ply(path, props, data):
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(data)
    header += "".join("property float %s\n" % p for p in props) + "end_header\n"
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(data.astype("<f4").tobytes())


def classify(props, data):
    """Independent reading of the table: returns a dict of counts and the drawn mask."""
    col = {p: i for i, p in enumerate(props)}
    pos = data[:, [col["x"], col["y"], col["z"]]]
    ls = data[:, [col["scale_0"], col["scale_1"], col["scale_2"]]]
    rot = data[:, [col["rot_0"], col["rot_1"], col["rot_2"], col["rot_3"]]]
    logit = data[:, col["opacity"]]
    nan = np.isnan(pos).any(1) | np.isnan(ls).any(1) | np.isnan(rot).any(1) | np.isnan(logit)
    inf_pos = ~nan & np.isinf(pos).any(1)
    inf_ls = ~nan & ~inf_pos & (np.isposinf(ls)).any(1)
    inf_rot = ~nan & ~inf_pos & ~inf_ls & np.isinf(rot).any(1)
    drawn = ~(nan | inf_pos | inf_ls | inf_rot)
    dc = data[:, [col["f_dc_0"], col["f_dc_1"], col["f_dc_2"]]]
    counts = {
        "a NaN parameter": int(nan.sum()),
        "an infinite position": int(inf_pos.sum()),
        "a log-scale of +inf": int(inf_ls.sum()),
        "an infinite rotation component": int(inf_rot.sum()),
        "an infinite or NaN SH coefficient": int((drawn & ~np.isfinite(dc).all(1)).sum()),
        "opacity logit +inf (opacity 1)": int((drawn & np.isposinf(logit)).sum()),
        "opacity logit -inf (opacity 0)": int((drawn & np.isneginf(logit)).sum()),
        "a log-scale of -inf (scale 0)": int((drawn & np.isneginf(ls).any(1)).sum()),
        "a zero quaternion (no rotation)": int((drawn & (rot == 0).all(1)).sum()),
    }
    return counts, drawn & np.isfinite(dc).all(1)


def printed_counts(text):
    return {m.group(2): int(m.group(1))
            for m in re.finditer(r"(\d+) with ([^,;\n]+?)(?=, \d+ with |;|\s*\(Doc|\n|$)", text)}


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        sys.exit("FAILED: %s exited with %d:\n%s" % (" ".join(cmd), p.returncode, p.stdout))
    return p.stdout


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    vis4gs, source, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    props, data = read_ply(source)
    col = {p: i for i, p in enumerate(props)}
    # One Gaussian per "no answer" row, copied from Gaussian 0 so they would be visible.
    extra = np.repeat(data[:1], 5, axis=0)
    extra[0, col["x"]] = np.nan
    extra[1, col["y"]] = -np.inf
    extra[2, col["scale_1"]] = np.inf
    extra[3, col["rot_2"]] = np.inf
    extra[4, col["f_dc_1"]] = np.nan
    data = np.vstack([data, extra])
    scene = os.path.join(work, "special.ply")
    write_ply(scene, props, data)
    expected, drawn = classify(props, data)
    expected = {k: v for k, v in expected.items() if v}

    # A fixed camera: without one, render frames the scene's bounds, which the test changes.
    cameras = os.path.join(os.path.dirname(os.path.abspath(source)), "cameras.json")
    view = ["--cameras=" + cameras] if os.path.exists(cameras) else []
    rendered = run([vis4gs, "render", scene, "--output=" + os.path.join(work, "special.png"),
                    "--resolution=320,240", "--sh-degree=0"] + view)
    got = printed_counts("\n".join(l for l in rendered.splitlines() if "special values" in l))
    analyzed = run([vis4gs, "analyze", scene, "--scores=shape",
                    "--output=" + os.path.join(work, "analyze")])
    got_a = printed_counts("\n".join(l for l in analyzed.splitlines() if "note:" in l))
    ok = True
    if got != expected:
        print("FAILED: render printed %s, numpy counts %s" % (got, expected))
        ok = False
    expected_a = {k: v for k, v in expected.items() if "SH" not in k}
    if got_a != expected_a:
        print("FAILED: analyze printed %s, numpy counts %s" % (got_a, expected_a))
        ok = False
    # Leaving out what is skipped changes no pixel.
    kept = os.path.join(work, "kept.ply")
    write_ply(kept, props, data[drawn])
    run([vis4gs, "render", kept, "--output=" + os.path.join(work, "kept.png"),
         "--resolution=320,240", "--sh-degree=0"] + view)
    with open(os.path.join(work, "special.png"), "rb") as a, \
            open(os.path.join(work, "kept.png"), "rb") as b:
        same = a.read() == b.read()
    if not same:
        print("FAILED: the render with the skipped Gaussians differs from the render without")
        ok = False
    print("counts: %s" % expected)
    if not ok:
        sys.exit(1)
    print("special values checked: %d Gaussians, %d drawn" % (len(data), int(drawn.sum())))


if __name__ == "__main__":
    main()
