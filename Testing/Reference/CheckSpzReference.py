"""SPZ reference check (issue 19): our SPZ reader and writer against @playcanvas/splat-transform
(installed at test time by install-splat-transform.sh; it reads and writes SPZ through Niantic's
own library compiled to WebAssembly).

  (a) source PLY -> splat-transform -> .spz (v3 and v4); our reader vs splat-transform's own
      .spz -> .ply, value by value; our reading also against the source within the
      quantisation of Niantic's writer (which checks the axis convention on its own);
  (b) a version 2 file built byte by byte here (splat-transform cannot write v2): our reader vs
      splat-transform and vs a float64 decode of the published layout;
  (c) our SPZ v4 writer's output read back by splat-transform, compared with the source within
      the documented quantisation, and with the errors our writer reports.

Usage: CheckSpzReference.py CONVERT INSTALL_SCRIPT WORKDIR [SOURCE.ply ...]
With no SOURCE a degree-3 scene is generated. Exit 0 pass, 1 fail, 77 skipped (no node/npm).
"""
import gzip
import json
import os
import struct
import subprocess
import sys

import numpy as np

FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILURES.append(what)


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    assert header[1] == "format binary_little_endian 1.0", header[1]
    types = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4", "uint": "<u4"}
    count, fields = 0, []
    for line in header:
        w = line.split()
        if w[:2] == ["element", "vertex"]:
            count = int(w[2])
        elif w[0] == "property":
            fields.append((w[2], types[w[1]]))
    rows = np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)
    return {name: rows[name].astype(np.float64) for name, _ in fields}


def write_ply(path, columns):
    names = list(columns)
    n = len(columns[names[0]])
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % n
    header += "".join("property float %s\n" % k for k in names) + "end_header\n"
    table = np.stack([np.asarray(columns[k], dtype="<f4") for k in names], axis=1)
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(table.tobytes())


def generated_scene(n=2000, seed=19):
    rng = np.random.default_rng(seed)
    c = {}
    for i, k in enumerate("xyz"):
        c[k] = rng.uniform(-20, 20, n)
    for k in ("nx", "ny", "nz"):
        c[k] = np.zeros(n)
    for i in range(3):
        c["f_dc_%d" % i] = rng.uniform(-2, 2, n)
    for i in range(45):
        c["f_rest_%d" % i] = rng.uniform(-0.8, 0.8, n)
    c["opacity"] = rng.uniform(-6, 6, n)
    for i in range(3):
        c["scale_%d" % i] = rng.uniform(-8, 3, n)
    q = rng.normal(size=(n, 4))
    for i in range(4):
        c["rot_%d" % i] = q[:, i]
    return c


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print("command failed: %s\n%s%s" % (" ".join(cmd), r.stdout[-2000:], r.stderr[-2000:]))
        sys.exit(1)
    return r.stdout


def sigmoid(x):
    with np.errstate(over="ignore"):
        return 1 / (1 + np.exp(-x))


def rest_names(cols):
    return sorted((k for k in cols if k.startswith("f_rest_")), key=lambda k: int(k[7:]))


def compare_decoders(ours, theirs, what, rotation_tolerance=2e-6):
    """Our reading vs splat-transform's reading of the same SPZ file."""
    check(len(ours["x"]) == len(theirs["x"]), "%s: same count (%d)" % (what, len(theirs["x"])))
    exact = ["x", "y", "z", "scale_0", "scale_1", "scale_2"] + rest_names(theirs)
    worst = max(np.max(np.abs(ours[k] - theirs[k])) for k in exact)
    check(worst == 0, "%s: positions, log-scales and %d SH rest values identical (max diff %g)"
          % (what, len(rest_names(theirs)), worst))
    # Niantic decodes in float32, we in float64 rounded once: a few ulps.
    dc = max(np.max(np.abs(ours[k] - theirs[k])) for k in ("f_dc_0", "f_dc_1", "f_dc_2"))
    check(dc <= 2e-6, "%s: DC colour within 2e-6 (max diff %.3g)" % (what, dc))
    rot = max(np.max(np.abs(ours["rot_%d" % i] - theirs["rot_%d" % i])) for i in range(4))
    check(rot <= rotation_tolerance, "%s: rotations within %g (max diff %.3g)"
          % (what, rotation_tolerance, rot))
    # Bytes 0 and 255 are +-inf logits to Niantic, (1e-6, 1-1e-6) clamped ones to us.
    opa = np.max(np.abs(sigmoid(ours["opacity"]) - sigmoid(theirs["opacity"])))
    check(opa <= 1.01e-6, "%s: opacity within 1e-6 (max diff %.3g; %d infinite logits in theirs)"
          % (what, opa, int(np.sum(np.isinf(theirs["opacity"])))))


# What the bytes can hold: log-scale (b/16 - 10), DC colour ((b/255 - 0.5)/0.15), SH (b-128)/128.
RANGES = {"scale": (-10, 5.9375), "f_dc": (-0.5 / 0.15, 0.5 / 0.15), "f_rest": (-1, 127 / 128)}


def quantisation_errors(src, back, fractional_bits, clip=True, sh1_bits=5, rest_bits=4):
    """Largest differences between a source and its SPZ reading, per attribute, and bounds.
    With clip, source values beyond what the bytes can hold are first clamped to the range
    (the bounds are then half a step); without, the errors include the clamping."""
    def s(k):
        for prefix, (lo, hi) in RANGES.items():
            if clip and k.startswith(prefix):
                return np.clip(src[k], lo, hi)
        return src[k]
    e, bound = {}, {}
    e["position"] = max(np.max(np.abs(back[k] - src[k])) for k in "xyz")
    # Half a fixed-point step, plus float32 rounding of the coordinates.
    extent = max(np.max(np.abs(src[k])) for k in "xyz")
    bound["position"] = 2.0 ** -(fractional_bits + 1) + extent * 1.2e-7
    e["log_scale"] = max(np.max(np.abs(back["scale_%d" % i] - s("scale_%d" % i))) for i in range(3))
    bound["log_scale"] = 1 / 32 + 1e-6
    e["opacity"] = np.max(np.abs(sigmoid(back["opacity"]) - sigmoid(src["opacity"])))
    bound["opacity"] = 0.5 / 255 + 1.01e-6
    e["color"] = max(np.max(np.abs(back["f_dc_%d" % i] - s("f_dc_%d" % i))) for i in range(3))
    bound["color"] = 0.5 / (255 * 0.15) + 1e-6
    names = rest_names(src)
    per = len(names) // 3
    sh = [np.max(np.abs(back[k] - s(k))) for k in names]
    e["sh"] = max(sh) if sh else 0.0
    if clip and sh:
        sh1 = max(sh[c * per + j] for c in range(3) for j in range(min(3, per)))
        check(sh1 <= (0.5 + 2 ** (7 - sh1_bits)) / 128 + 1e-6,
              "  SH degree 1 within %d-bit buckets (max %.4g)" % (sh1_bits, sh1))
    bound["sh"] = (0.5 + 2 ** (7 - rest_bits)) / 128 + 1e-6
    q = np.stack([src["rot_%d" % i] for i in range(4)], axis=1)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    b = np.stack([back["rot_%d" % i] for i in range(4)], axis=1)
    b *= np.where(np.sum(q * b, axis=1) < 0, -1, 1)[:, None]
    e["rotation"] = np.max(np.abs(b - q))
    # Stored components within h = sqrt(1/2)/511/2; the rebuilt largest one w >= 1/2 within
    # sqrt(1 - w^2) sqrt(3) h / w <= 2.07e-3.
    bound["rotation"] = 2.1e-3
    return e, bound


def spz_version(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    magic, version = struct.unpack_from("<II", data, 0)
    return version if magic == 0x5053474E else None


def hand_built_v2(path, n=500, seed=2):
    """A version 2 file from the published layout, and its float64 decode in RDF axes."""
    rng = np.random.default_rng(seed)
    fixed = rng.integers(-(1 << 23), 1 << 23, size=(n, 3))
    alpha = rng.integers(1, 255, n)
    color = rng.integers(0, 256, (n, 3))
    scale = rng.integers(0, 256, (n, 3))
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    q *= np.where(q[:, 3:] < 0, -1, 1)  # xyzw with w >= 0, as v2 stores it
    rot = np.clip(np.round(q[:, :3] * 127.5 + 127.5), 0, 255).astype(np.int64)
    sh = rng.integers(0, 256, (n, 8, 3))  # degree 2
    body = struct.pack("<IIIBBBB", 0x5053474E, 2, n, 2, 12, 0, 0)
    body += (fixed & 0xFFFFFF).astype("<u4").view(np.uint8).reshape(n, 3, 4)[:, :, :3].tobytes()
    for a in (alpha, color, scale, rot, sh):
        body += a.astype(np.uint8).tobytes()
    with open(path, "wb") as f:
        f.write(gzip.compress(body))
    flip = np.array([1, -1, -1])
    exp = {}
    for i, k in enumerate("xyz"):
        exp[k] = flip[i] * fixed[:, i] / 4096.0
    for i in range(3):
        exp["f_dc_%d" % i] = (color[:, i] / 255.0 - 0.5) / 0.15
        exp["scale_%d" % i] = scale[:, i] / 16.0 - 10.0
    a = alpha / 255.0
    exp["opacity"] = np.log(a / (1 - a))
    xyz = rot / 127.5 - 1
    exp["rot_0"] = np.sqrt(np.maximum(0, 1 - np.sum(xyz ** 2, axis=1)))
    for i in range(3):
        exp["rot_%d" % (i + 1)] = [1, -1, -1][i] * xyz[:, i]
    # RUB -> RDF parity of the 8 degree-1/2 coefficients (odd in y xor z).
    sign = [-1, -1, 1, -1, 1, 1, -1, 1]
    for c in range(3):
        for j in range(8):
            exp["f_rest_%d" % (c * 8 + j)] = sign[j] * (sh[:, j, c] - 128) / 128.0
    return exp


def main():
    convert, install, work = sys.argv[1], sys.argv[2], sys.argv[3]
    sources = sys.argv[4:]
    os.makedirs(work, exist_ok=True)
    # 2.7.1: SPZ through Niantic's library, RUB in the file (install-splat-transform.sh).
    r = subprocess.run(["bash", install, os.path.join(work, "..", ".."), "2.7.1"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout + r.stderr)
        sys.exit(r.returncode)
    st = ["node", r.stdout.strip().splitlines()[-1]]
    r = subprocess.run([*st, "--version"], capture_output=True, text=True)
    print("reference: splat-transform " + (r.stdout + r.stderr).strip())

    if not sources:
        gen = os.path.join(work, "generated.ply")
        write_ply(gen, generated_scene())
        sources = [gen]
        # (b) a hand-built version 2 file.
        v2 = os.path.join(work, "hand-v2.spz")
        expected = hand_built_v2(v2)
        run([*st, "-q", "-w", v2, os.path.join(work, "hand-v2.theirs.ply")])
        run([convert, v2, os.path.join(work, "hand-v2.ours.ply")])
        ours = read_ply(os.path.join(work, "hand-v2.ours.ply"))
        # v2's w = sqrt(1 - |xyz|^2) loses digits in float32 when w is small; the float64
        # decode below holds ours to 2e-7.
        compare_decoders(ours, read_ply(os.path.join(work, "hand-v2.theirs.ply")), "v2 hand-built",
                         rotation_tolerance=2e-5)
        worst = max(np.max(np.abs(ours[k] - expected[k])) for k in expected)
        check(worst <= 2e-6, "v2 hand-built: ours vs the float64 decode of the layout (max %.3g)" % worst)

    for src_path in sources:
        name = os.path.splitext(os.path.basename(src_path))[0]
        src = read_ply(src_path)
        # (a) splat-transform's SPZ files, v3 (gzip) and v4 (zstd).
        for version in (3, 4):
            spz = os.path.join(work, "%s.st-v%d.spz" % (name, version))
            run([*st, "-q", "-w", "--spz-version", str(version), src_path, spz])
            check(spz_version(spz) == version, "%s: splat-transform wrote SPZ v%d" % (name, version))
            run([*st, "-q", "-w", spz, spz + ".theirs.ply"])
            info = json.loads(run([convert, spz, spz + ".ours.ply"]))
            check(info["read_format"] == "spz v%d" % version, "%s: read as %s" % (name, info["read_format"]))
            ours = read_ply(spz + ".ours.ply")
            compare_decoders(ours, read_ply(spz + ".theirs.ply"), "%s v%d" % (name, version))
            e, bound = quantisation_errors(src, ours, 12)
            for k in e:
                check(e[k] <= bound[k], "%s v%d: our reading vs the source, %s %.4g <= %.4g"
                      % (name, version, k, e[k], bound[k]))
        # (c) our writer, read back by splat-transform.
        spz = os.path.join(work, "%s.ours.spz" % name)
        report = json.loads(run([convert, src_path, spz]))
        check(spz_version(spz) == 4 and report["left_out"] == 0,
              "%s: our writer wrote SPZ v4 with all %d Gaussians" % (name, report["written"]))
        run([*st, "-q", "-w", spz, spz + ".theirs.ply"])
        theirs = read_ply(spz + ".theirs.ply")
        run([convert, spz, spz + ".ours.ply"])
        compare_decoders(read_ply(spz + ".ours.ply"), theirs, "%s, our v4 file" % name)
        e, bound = quantisation_errors(src, theirs, report["fractional_bits"])
        raw, _ = quantisation_errors(src, theirs, report["fractional_bits"], clip=False)
        for k in e:
            check(e[k] <= bound[k], "%s: our v4 file read by splat-transform, %s error %.4g <= %.4g"
                  % (name, k, e[k], bound[k]))
            # The writer's report (clamping included) decodes in float64, Niantic in float32.
            check(abs(report[k]["max"] - raw[k]) <= 1e-5 + 1e-6 * abs(raw[k]),
                  "%s: reported %s max error %.6g matches the reference reading's %.6g"
                  % (name, k, report[k]["max"], raw[k]))
        print("%s: %d Gaussians, SPZ v4 %d bytes, fractional bits %d; errors (max/rms): %s" % (
            name, report["written"], report["file_bytes"], report["fractional_bits"],
            ", ".join("%s %.3g/%.3g" % (k, report[k]["max"], report[k]["rms"])
                      for k in ("position", "log_scale", "rotation", "opacity", "color", "sh"))))
    if FAILURES:
        print("FAILED: %d checks" % len(FAILURES))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
