"""`vis4gs convert` for every pair of the formats it writes (issue 34).

A generated scene (SH degree 3, a `score` column) is written in each format A by the command,
then every A is converted to every format B. Each result is decoded to an exact float32 PLY by
the command itself and compared, Gaussian by Gaussian (matched by nearest mean where the
target reorders: the compressed PLY's Morton order), with A's decoding:
  - the count is kept and the SH degree is A's (0 for .splat);
  - positions, log-scales and alphas lie within B's quantisation (exact for PLY, 1 float32
    rounding of exp/sigmoid for glTF, the fixed-point step for SPZ, the chunk step for the
    compressed PLY, the byte for .splat);
  - the error the command reports for B (SPZ, glTF, compressed PLY) is the error measured here;
  - the score survives bit for bit wherever A and B can hold it (PLY, glTF), and the command
    says so where B cannot.
Then --sh-degree, --no-extras and bad arguments.

Usage: CheckConvert.py <vis4gs> <work dir>
"""
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "Testing", "Reference"))
import reference_ply as ref  # noqa: E402
from Checks import check, finish  # noqa: E402

FORMATS = ["ply", "compressed.ply", "spz", "glb", "gltf", "splat"]
KEEPS_EXTRAS = {"ply", "glb", "gltf"}


def convert(vis4gs, src, dst, *options, status=0):
    r = subprocess.run([vis4gs, "convert", src, dst, *options], capture_output=True, text=True)
    if r.returncode != status:
        check(False, "vis4gs convert %s %s exits %d (got %d: %s%s)" % (
            os.path.basename(src), os.path.basename(dst), status, r.returncode, r.stdout, r.stderr))
    return r.stdout + r.stderr


def scene(n=400, seed=34):
    rng = np.random.default_rng(seed)
    c = {k: rng.uniform(-5, 5, n) for k in "xyz"}
    for i in range(3):
        c["f_dc_%d" % i] = rng.normal(0, 0.8, n)
    for i in range(45):
        c["f_rest_%d" % i] = rng.normal(0, 0.2, n)
    c["opacity"] = rng.normal(0, 2, n)
    for i in range(3):
        c["scale_%d" % i] = rng.normal(-3, 0.7, n)
    q = rng.normal(0, 1, (n, 4))
    for i in range(4):
        c["rot_%d" % i] = q[:, i]
    c["score"] = rng.uniform(0, 1, n)
    return c


def decode(vis4gs, path, work):
    out = os.path.join(work, os.path.basename(path).replace(".", "_") + "-decoded.ply")
    convert(vis4gs, path, out)
    return ref.read_ply(out)["vertex"]


def f64(rows, names):
    return np.stack([rows[n].astype(np.float64) for n in names], 1)


def alpha(v):
    with np.errstate(over="ignore"):
        return 1 / (1 + np.exp(-v))


def reported(line, name):
    m = re.search(re.escape(name) + r" ([0-9.e+-]+|nan|inf)/", line)
    return float(m.group(1)) if m else None


def main():
    vis4gs, work = sys.argv[1:3]
    os.makedirs(work, exist_ok=True)
    base = os.path.join(work, "base.ply")
    ref.write_ply(base, scene())
    extent = 5.0
    # Position bound of each target: SPZ's 24-bit fixed point picks the most fractional bits
    # that fit (2^-(bits+1), bits = 23 - ceil(log2(extent)) - 1 at most), the compressed PLY
    # half an 11- or 10-bit step of its chunk's bounds.
    pos_bound = {"ply": 0, "glb": 0, "gltf": 0, "splat": 0, "spz": 2.0 ** -20,
                 "compressed.ply": 2 * extent / 1023 / 2}
    scale_bound = {"ply": 0, "glb": 2.4e-7, "gltf": 2.4e-7, "splat": 2.4e-7, "spz": 1 / 32 + 1e-6,
                   "compressed.ply": 0.02}
    alpha_bound = {"ply": 0, "glb": 6e-8, "gltf": 6e-8, "splat": 0.5 / 255 + 1e-4,
                   "spz": 0.5 / 255 + 1e-6, "compressed.ply": 0.5 / 255 + 1e-6}
    decoded = {}
    for a in FORMATS:
        src = os.path.join(work, "source." + a)
        convert(vis4gs, base, src)
        decoded[a] = decode(vis4gs, src, work)
    for a in FORMATS:
        da = decoded[a]
        src = os.path.join(work, "source." + a)
        for b in FORMATS:
            dst = os.path.join(work, "from-%s.%s" % (a.replace(".", "-"), b))
            out = convert(vis4gs, src, dst)
            db = decode(vis4gs, dst, work)
            what = "%s -> %s" % (a, b)
            if not check(len(db) == len(da), "%s keeps the %d Gaussians" % (what, len(da))):
                continue
            pa, pb = f64(da, "xyz"), f64(db, "xyz")
            if b == "compressed.ply":
                # Morton order: match each written Gaussian with its nearest source mean.
                d = ((pb[:, None, :] - pa[None, :, :]) ** 2).sum(-1)
                order = np.argmin(d, 1)
                check(len(set(order.tolist())) == len(da), "%s: a one-to-one match" % what)
                da_m = da[order]
            else:
                da_m = da
            rest_a = [c for c in da.dtype.names if c.startswith("f_rest_")]
            rest_b = [c for c in db.dtype.names if c.startswith("f_rest_")]
            check(len(rest_b) == (0 if b == "splat" else len(rest_a)),
                  "%s: SH degree kept (%d f_rest)" % (what, len(rest_b)))
            pos = float(np.max(np.abs(f64(db, "xyz") - f64(da_m, "xyz"))))
            scales = ["scale_%d" % i for i in range(3)]
            sc = float(np.max(np.abs(f64(db, scales) - f64(da_m, scales))))
            al = float(np.max(np.abs(alpha(db["opacity"].astype(np.float64)) -
                                     alpha(da_m["opacity"].astype(np.float64)))))
            check(pos <= pos_bound[b] and sc <= scale_bound[b] and al <= alpha_bound[b],
                  "%s within the target's quantisation: position %.3g (<= %.3g), log-scale %.3g "
                  "(<= %.3g), alpha %.3g (<= %.3g)" % (what, pos, pos_bound[b], sc, scale_bound[b],
                                                       al, alpha_bound[b]))
            line = ([l for l in out.splitlines() if l.startswith("vis4gs convert: " + dst + ":")]
                    or [""])[0]
            if b in ("spz", "glb", "gltf", "compressed.ply"):
                rp = reported(line, "position")
                ra = reported(line, "opacity (alpha)")
                # Printed with 3 significant digits; the compressed PLY's writer measures alpha
                # from its bytes, we from the float32 logits read back (2e-8 apart at most).
                check(rp is not None and abs(rp - pos) <= 5.01e-3 * pos + 1e-12 and ra is not None
                      and abs(ra - al) <= 5.01e-3 * al + 2e-8,
                      "%s reports the errors measured here (position %s vs %.4g, alpha %s vs %.4g)"
                      % (what, rp, pos, ra, al))
            if a in KEEPS_EXTRAS and b in KEEPS_EXTRAS:
                check("score" in db.dtype.names and np.array_equal(
                    db["score"].astype(np.float32), da["score"].astype(np.float32)),
                    "%s keeps the score bit for bit" % what)
            elif a in KEEPS_EXTRAS:
                check("extra properties (score) have no place" in out,
                      "%s says the score cannot be written" % what)

    # --sh-degree drops bands; --no-extras drops the score; bad arguments fail with a reason.
    convert(vis4gs, base, os.path.join(work, "sh1.glb"), "--sh-degree=1")
    sh1 = decode(vis4gs, os.path.join(work, "sh1.glb"), work)
    rest = [c for c in sh1.dtype.names if c.startswith("f_rest_")]
    full = decoded["ply"]
    # Channel-major f_rest: 3 coefficients per channel at degree 1, 15 at degree 3.
    same = all(np.array_equal(sh1["f_rest_%d" % (3 * ch + k)], full["f_rest_%d" % (15 * ch + k)])
               for ch in range(3) for k in range(3))
    check(len(rest) == 9 and same, "--sh-degree=1 keeps degree 1 exactly (%d f_rest)" % len(rest))
    convert(vis4gs, base, os.path.join(work, "plain.ply"), "--no-extras")
    check("score" not in ref.read_ply(os.path.join(work, "plain.ply"))["vertex"].dtype.names,
          "--no-extras drops the score")
    out = convert(vis4gs, base, os.path.join(work, "scene.xyz"), status=1)
    check("does not say a format" in out, "an unknown target format is refused: " + out.strip())
    out = convert(vis4gs, os.path.join(work, "missing.ply"), os.path.join(work, "x.ply"), status=1)
    check("missing.ply" in out, "a missing input is named: " + out.strip())
    out = convert(vis4gs, base, os.path.join(work, "x.glb"), "--sh-degree=5", status=1)
    check("--sh-degree" in out, "--sh-degree=5 is refused")
    # A training log: its last snapshot by default (--iteration=-1), as --help says.
    log = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "Data",
                       "Demo", "vis4gs-demo.h5")
    import h5py  # noqa: E402 - only this check reads a log
    with h5py.File(log, "r") as f:
        snapshots = sorted(int(k) for k in f["snapshots"])
    for option, expected in (((), snapshots[-1]), (("--iteration=1",), snapshots[0])):
        out = convert(vis4gs, log, os.path.join(work, "log.ply"), *option)
        check("(snapshot %d)" % expected in out, "a log converts its snapshot %d with %s: %s" % (
            expected, " ".join(option) or "no --iteration", out.strip().splitlines()[0]))
    finish("PASSED vis4gs convert: %d pairs of formats" % (len(FORMATS) ** 2))


if __name__ == "__main__":
    main()
