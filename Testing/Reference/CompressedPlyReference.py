"""Compressed PLY against PlayCanvas's splat-transform (issue 19).

1. splat-transform converts a scene (generated, SH degree 3; or the real INRIA PLY) to a
   compressed PLY and that file back to PLY; our reader's decoding of the same compressed file
   must equal splat-transform's value by value (float32 bits; both compute in double and round
   once).
2. Our writer's compressed PLY of the scene (in source order) is read back by splat-transform;
   every value must lie within the format's quantisation of the source, derived here from the
   chunk bounds stored in the file (half a step of each packed field), and our writer in Morton
   order must produce the same packed words as splat-transform's writer.

Usage: CompressedPlyReference.py <vis4gsSceneConvert> <build dir> <work dir> generated|inria
       [vis4gs: also checks that `vis4gs render` / `analyze` read the file as our reader does]
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import reference_ply as ref  # noqa: E402

C0 = 0.28209479177387814


def source_path(mode, work):
    if mode == "generated":
        path = os.path.join(work, "generated.ply")
        ref.write_ply(path, ref.generated_scene())
        return path
    from vis4gs_test_data import shared_data_dir
    return os.path.join(shared_data_dir(),
                        "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply")


def within_quantisation(src, back, comp):
    """Checks splat-transform's reading of our compressed file against the source: each value
    within half a quantisation step of its chunk's bounds (source order, chunks of 256)."""
    chunk = comp["chunk"]
    n = len(src)
    ci = np.arange(n) // 256
    failures = 0

    def check(name, err, bound):
        nonlocal failures
        over = int(np.count_nonzero(err > bound))
        print("  %-10s max |error| %.3g (RMS %.3g), %d over the bound" %
              (name, float(err.max()), float(np.sqrt(np.mean(err ** 2))), over))
        failures += over

    for k, (axis, bits) in enumerate(zip("xyz", (11, 10, 11))):
        lo, hi = chunk["min_" + axis][ci].astype(np.float64), chunk["max_" + axis][ci].astype(np.float64)
        step = (hi - lo) / ((1 << bits) - 1)
        check(axis, np.abs(back[axis].astype(np.float64) - src[axis]), 0.5 * step * (1 + 1e-6) + 1e-6)
        s = src["scale_%d" % k].astype(np.float64)
        lo = chunk["min_scale_" + axis][ci].astype(np.float64)
        hi = chunk["max_scale_" + axis][ci].astype(np.float64)
        step = (hi - lo) / ((1 << bits) - 1)
        inside = np.abs(s) <= 20
        check("scale_%d" % k, np.abs(back["scale_%d" % k].astype(np.float64) - s)[inside],
              (0.5 * step * (1 + 1e-6) + 1e-6)[inside])
    for k, c in enumerate("rgb"):
        lo = chunk["min_" + c][ci].astype(np.float64)
        hi = chunk["max_" + c][ci].astype(np.float64)
        err = np.abs(back["f_dc_%d" % k].astype(np.float64) - src["f_dc_%d" % k]) * C0
        check("f_dc_%d" % k, err, 0.5 * (hi - lo) / 255 * (1 + 1e-6) + 1e-6)
    alpha = lambda v: 1 / (1 + np.exp(-v.astype(np.float64)))  # noqa: E731
    check("opacity", np.abs(alpha(back["opacity"]) - alpha(src["opacity"])), 0.5 / 255 + 1e-9)
    q = np.stack([src["rot_%d" % i] for i in range(4)], 1).astype(np.float64)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    b = np.stack([back["rot_%d" % i] for i in range(4)], 1).astype(np.float64)
    angle = np.degrees(2 * np.arccos(np.minimum(1, np.abs(np.sum(q * b, 1)))))
    # Smallest-three: the three stored components are off by at most half a step, sqrt(2)/2046
    # each; the largest one (>= 1/2) restores the norm, off by at most sqrt(3) times as much, so
    # |q - q'| <= 2 sqrt(3) sqrt(2)/2046 and the angle 2|q - q'| <= 2 sqrt(6)/1023 radians.
    check("rotation", angle, np.degrees(2 * np.sqrt(6) / 1023) + 1e-4)
    rest = [c for c in src.dtype.names if c.startswith("f_rest_")]
    if rest:
        clipped = [np.clip(src[c].astype(np.float64), -4, 4) for c in rest]
        err = np.concatenate([np.abs(back[c].astype(np.float64) - v) for c, v in zip(rest, clipped)])
        # Half a bucket (8/256) around its centre; the end buckets read back as -4 and 4.
        ends = np.concatenate([np.abs(v) > 4 - 8 / 256 for v in clipped])
        check("f_rest", err, np.where(ends, 8 / 256, 4 / 256) + 1e-6)
    return failures


def main():
    tool, build, work, mode = sys.argv[1:5]
    vis4gs = sys.argv[5] if len(sys.argv) > 5 else ""
    os.makedirs(work, exist_ok=True)
    cli = ref.splat_transform(build)
    src_path = source_path(mode, work)
    src = ref.read_ply(src_path)["vertex"]
    rest = [c for c in src.dtype.names if c.startswith("f_rest_")]
    failures = 0

    # 1. splat-transform's compressed file, decoded by splat-transform and by us.
    st_comp = os.path.join(work, "st.compressed.ply")
    ref.convert(cli, src_path, st_comp)
    st_back = os.path.join(work, "st-decoded.ply")
    ref.convert(cli, st_comp, st_back)
    ours_back = os.path.join(work, "ours-decoded.ply")
    print(ref.run([tool, st_comp, ours_back]).strip())
    theirs = ref.read_ply(st_back)["vertex"]
    ours = ref.read_ply(ours_back)["vertex"]
    if len(theirs) != len(ours) or len(ours) != len(src):
        print("FAILED: counts differ: source %d, splat-transform %d, ours %d" %
              (len(src), len(theirs), len(ours)))
        sys.exit(1)
    failures += ref.compare_exact("reader vs splat-transform on its compressed PLY", ours, theirs,
                                  ref.GAUSSIAN_COLUMNS + rest)
    failures += ref.check_commands(vis4gs, st_comp, ours_back, work, "compressed-ply")

    # 2. Our writer, read back by splat-transform, against the source (source order).
    our_comp = os.path.join(work, "ours.compressed.ply")
    print(ref.run([tool, src_path, our_comp, "--compressed", "--source-order"]).strip())
    back_path = os.path.join(work, "ours-by-st.ply")
    ref.convert(cli, our_comp, back_path)
    back = ref.read_ply(back_path)["vertex"]
    print("our compressed PLY read back by splat-transform, against the source:")
    failures += within_quantisation(src, back, ref.read_ply(our_comp))

    # Our writer in Morton order against splat-transform's writer, word by word.
    morton = os.path.join(work, "ours-morton.compressed.ply")
    print(ref.run([tool, src_path, morton, "--compressed"]).strip())
    a, b = ref.read_ply(morton), ref.read_ply(st_comp)
    same = sum(int(np.count_nonzero(a["vertex"][c] == b["vertex"][c])) for c in a["vertex"].dtype.names)
    total = len(a["vertex"]) * len(a["vertex"].dtype.names)
    chunks_same = all(np.array_equal(a["chunk"][c], b["chunk"][c]) for c in a["chunk"].dtype.names)
    sh_same = "sh" not in a or all(np.array_equal(a["sh"][c], b["sh"][c]) for c in a["sh"].dtype.names)
    print("our writer vs splat-transform's writer: %d of %d packed words equal, chunk bounds %s, "
          "sh bytes %s" % (same, total, "equal" if chunks_same else "differ",
                           "equal" if sh_same else "differ"))
    if same != total or not chunks_same or not sh_same:
        failures += 1

    if failures:
        print("FAILED: %d checks failed" % failures)
        sys.exit(1)
    print("PASSED compressed PLY (%s, %d Gaussians)" % (mode, len(src)))


if __name__ == "__main__":
    main()
