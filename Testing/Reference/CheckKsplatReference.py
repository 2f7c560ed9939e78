""".ksplat reference check (issue 19): our .ksplat reader against the format's own writer and
an independent reader, both installed at test time from npm:

  GaussianSplats3D (@mkkellogg/gaussian-splats-3d, install-gaussian-splats-3d.sh) converts a
  source PLY to .ksplat at compression levels 0, 1 and 2 with its own PLY parser and
  SplatBuffer generator (make-ksplat.mjs); then
  (a) our reading (vis4gsSceneConvert .ksplat -> PLY) vs @playcanvas/splat-transform's reading
      of the same file, value by value;
  (b) our reading vs the source PLY within the precision each level stores (float32; float16
      and 16-bit bucket offsets; bytes for SH), colour and opacity within the writer's
      floor() to a byte, SH degree capped at 2 as GaussianSplats3D's parser does.

Usage: CheckKsplatReference.py CONVERT WORKDIR [SOURCE.ply ...]
With no SOURCE a degree-2 scene is generated. Exit 0 pass, 1 fail, 77 skipped (no node/npm).
"""
import os
import struct
import subprocess
import sys

import numpy as np

import CheckSpzReference as common
from CheckSpzReference import check, read_ply, rest_names, run, sigmoid, write_ply

HERE = os.path.dirname(os.path.abspath(__file__))
C0 = 0.28209479177387814


def install(script, *args):
    r = subprocess.run(["bash", os.path.join(HERE, script), *args], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout + r.stderr)
        sys.exit(r.returncode)
    return r.stdout.strip().splitlines()[-1]


def generated_scene(n=3000, seed=19):
    """Degree 2; a dense cube fills buckets of 256, the rest spreads over many 5-unit blocks."""
    rng = np.random.default_rng(seed)
    pos = rng.uniform(-20, 20, (n, 3))
    pos[:700] = rng.uniform(0.2, 1.2, (700, 3))
    c = {k: pos[:, i] for i, k in enumerate("xyz")}
    for i in range(3):
        c["f_dc_%d" % i] = rng.uniform(-2.2, 2.2, n)  # beyond [-1.77, 1.77]: clamped bytes
    for i in range(24):
        c["f_rest_%d" % i] = rng.uniform(-0.8, 0.8, n)
    c["opacity"] = rng.uniform(-8, 8, n)  # alpha bytes 0 are left out by the writer
    for i in range(3):
        c["scale_%d" % i] = rng.uniform(-12, 2, n)  # down to float16 subnormals
    q = rng.normal(size=(n, 4))
    for i in range(4):
        c["rot_%d" % i] = q[:, i]
    return c


def ksplat_sh_range(path):
    with open(path, "rb") as f:
        head = f.read(44)
    lo, hi = struct.unpack_from("<ff", head, 36)
    return (lo or -1.5), (hi or 1.5)


def f16_bound(v):
    """Largest error of GaussianSplats3D's float16 (three.js toHalfFloat truncates the float32
    mantissa): one ulp, 2^(e-10); subnormals below 2^-14: 2^-24."""
    a = np.abs(v)
    e = np.floor(np.log2(np.maximum(a, 2.0 ** -14)))
    return np.maximum(2.0 ** (e - 10), 2.0 ** -24) * (1 + 1e-6) + 1e-7 * a


def compare_readers(ours, theirs, what):
    check(len(ours["x"]) == len(theirs["x"]), "%s: same count (%d)" % (what, len(theirs["x"])))
    keys = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity"] + \
        ["rot_%d" % i for i in range(4)] + rest_names(theirs)
    check(sorted(rest_names(ours)) == sorted(rest_names(theirs)),
          "%s: same SH degree (%d rest values)" % (what, len(rest_names(theirs))))
    worst = {k: np.max(np.abs(ours[k] - theirs[k])) for k in keys}
    bad = {k: v for k, v in worst.items() if not v <= 1e-6 * max(1, np.max(np.abs(theirs[k])))}
    check(not bad, "%s: positions, colours, opacities, rotations, SH identical to float32 "
          "rounding (worst %s)" % (what, bad or max(worst.values())))
    # splat-transform writes log-scale -10 for a zero scale where we keep -inf.
    for i in range(3):
        k = "scale_%d" % i
        zero = np.isneginf(ours[k])
        d = np.max(np.abs(ours[k][~zero] - theirs[k][~zero]))
        check(d <= 1e-6 and np.all(theirs[k][zero] == -10),
              "%s: %s identical (max diff %.3g), %d zero scales" % (what, k, d, zero.sum()))


def compare_source(src, dec, order, level, sh_range, what):
    """Our decoding vs the source PLY, row order[i] of the source for row i of the file."""
    s = {k: v[order] for k, v in src.items()}
    n = len(order)
    if level == 0:
        pos = max(np.max(np.abs(dec[k] - s[k])) for k in "xyz")
        check(pos == 0, "%s: positions exact (max %.3g)" % (what, pos))
    else:
        step = 5.0 / 2 / 32767  # half the block size over the scale range
        pos = max(np.max(np.abs(dec[k] - s[k]) - 1e-6 * np.abs(s[k])) for k in "xyz")
        check(pos <= step / 2 * 1.0001, "%s: positions within half a bucket step %.3g (max %.3g)"
              % (what, step / 2, pos))
    lin = np.exp(np.stack([s["scale_%d" % i] for i in range(3)]))
    got = np.exp(np.stack([dec["scale_%d" % i] for i in range(3)]))
    bound = 1e-6 * lin + 1e-30 if level == 0 else f16_bound(lin)
    check(np.all(np.abs(got - lin) <= bound),
          "%s: linear scales within %s (max rel %.3g)" % (
              what, "float32" if level == 0 else "float16", np.max(np.abs(got - lin) / lin)))
    q = np.stack([s["rot_%d" % i] for i in range(4)])
    q = q / np.linalg.norm(q, axis=0)
    r = np.stack([dec["rot_%d" % i] for i in range(4)])
    bound = 1e-6 if level == 0 else f16_bound(q)
    check(np.all(np.abs(r - q) <= bound), "%s: rotations w x y z = the normalised source (max %.3g)"
          % (what, np.max(np.abs(r - q))))
    # Colour: byte = floor((0.5 + C0 f) * 255) clamped to 0..255; decoded (byte/255 - 0.5)/C0.
    worst = 0
    for i in range(3):
        byte = np.clip(np.floor((0.5 + C0 * s["f_dc_%d" % i]) * 255), 0, 255)
        expect = (byte / 255 - 0.5) / C0
        worst = max(worst, np.max(np.abs(dec["f_dc_%d" % i] - expect)))
    check(worst <= 2e-6, "%s: DC colour = the writer's byte decoded (max %.3g; a byte step is %.3g)"
          % (what, worst, 1 / 255 / C0))
    alpha = np.clip(np.floor(sigmoid(s["opacity"]) * 255), 0, 255) / 255
    expect = np.log(np.clip(alpha, 1e-6, 1 - 1e-6)) - np.log1p(-np.clip(alpha, 1e-6, 1 - 1e-6))
    d = np.max(np.abs(dec["opacity"] - expect))
    check(d <= 1e-5, "%s: opacity logit of the writer's alpha byte (max %.3g)" % (what, d))
    # SH rest, degree 2 at most: the PLY is channel-major with 8 coefficients a channel.
    per = len(rest_names(dec)) // 3
    src_per = len(rest_names(src)) // 3
    lo, hi = sh_range
    worst = 0
    for c in range(3):
        for j in range(per):
            v = s["f_rest_%d" % (c * src_per + j)]
            got = dec["f_rest_%d" % (c * per + j)]
            if level == 0:
                err = np.abs(got - v) - 1e-7 * np.abs(v)
            elif level == 1:
                err = np.abs(got - v) - f16_bound(v)
            else:
                byte = np.clip(np.floor((np.clip(v, lo, hi) - lo) / (hi - lo) * 255), 0, 255)
                err = np.abs(got - (byte / 255 * (hi - lo) + lo)) - 1e-6
            worst = max(worst, np.max(err))
    check(per == min(src_per, 8) and worst <= 0,
          "%s: %d SH coefficients a channel within the level's storage (excess %.3g)"
          % (what, per, worst))
    print("%s: %d Gaussians, positions max error %.3g" % (what, n, pos))


def main():
    convert, work = sys.argv[1], sys.argv[2]
    sources = sys.argv[3:]
    os.makedirs(work, exist_ok=True)
    reference = os.path.join(work, "..")
    make = install("install-gaussian-splats-3d.sh", os.path.join(reference, "gaussian-splats-3d"))
    # splat-transform 2.7.1, as for SPZ (install-splat-transform.sh <build dir> <version>).
    st = install("install-splat-transform.sh", os.path.join(reference, ".."), "2.7.1")
    if not sources:
        sources = [os.path.join(work, "generated.ply")]
        write_ply(sources[0], generated_scene())
    for source in sources:
        src = read_ply(source)
        name = os.path.splitext(os.path.basename(source))[0]
        src_per = len(rest_names(src)) // 3
        degree = {0: 0, 3: 1, 8: 2}.get(min(src_per, 8), 0)
        kept = np.floor(sigmoid(src["opacity"]) * 255) >= 1
        order = None
        for level in (0, 1, 2):
            what = "%s level %d" % (name, level)
            ks = os.path.join(work, "%s.l%d.ksplat" % (name, level))
            run(["node", make, source, ks, str(level), str(degree)])
            run([convert, ks, ks + ".ours.ply"])
            run(["node", st, "-q", "-w", ks, ks + ".theirs.ply"])
            ours = read_ply(ks + ".ours.ply")
            compare_readers(ours, read_ply(ks + ".theirs.ply"), what)
            check(len(ours["x"]) == kept.sum(), "%s: %d Gaussians with an alpha byte >= 1 kept"
                  % (what, kept.sum()))
            if level == 0:
                # The writer groups records by bucket; level 0 keeps float32 positions, which
                # find each record's source row (the order is the same at every level).
                rows = {}
                for i, key in enumerate(zip(src["x"], src["y"], src["z"])):
                    rows.setdefault(key, []).append(i)
                # Rows at the same position (real scenes have some) fall in the same bucket,
                # which keeps their order.
                shared = sum(len(r) - 1 for r in rows.values())
                order = np.array([rows[k].pop(0) for k in zip(ours["x"], ours["y"], ours["z"])])
                check(len(set(order)) == len(order), "%s: every record matches its own source row "
                      "(%d rows share a position with another)" % (what, shared))
            size = os.path.getsize(ks)
            print("%s: %d bytes (%.1f per Gaussian)" % (what, size, size / max(1, len(ours["x"]))))
            compare_source(src, ours, order, level, ksplat_sh_range(ks), what)
    if common.FAILURES:
        print("FAILED: %d checks" % len(common.FAILURES))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
