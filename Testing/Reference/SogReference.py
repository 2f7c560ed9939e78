"""SOG v2 against PlayCanvas's splat-transform (issue 19).

splat-transform converts a scene (generated, SH degree 3; or the real INRIA PLY) to SOG, both as
a `.sog` zip and as a folder with meta.json (k-means on its CPU device), and converts the `.sog`
back to PLY (and the folder's meta.json); our reader's decoding of the zip, of the folder and of the meta.json path must
equal splat-transform's value by value (float32 bits: both compute in double and round once).
A reading limited to SH degree 1 must equal the first coefficients.

Usage: SogReference.py <vis4gsSceneConvert> <build dir> <work dir> generated|inria [vis4gs]
"""
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import reference_ply as ref  # noqa: E402
from CompressedPlyReference import source_path  # noqa: E402


def main():
    tool, build, work, mode = sys.argv[1:5]
    vis4gs = sys.argv[5] if len(sys.argv) > 5 else ""
    os.makedirs(work, exist_ok=True)
    cli = ref.splat_transform(build)
    src_path = source_path(mode, work)
    n = len(ref.read_ply(src_path)["vertex"])
    failures = 0

    sog = os.path.join(work, "st.sog")
    ref.convert(cli, src_path, sog, "-g", "cpu")
    folder = os.path.join(work, "st-sog")
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    ref.convert(cli, src_path, os.path.join(folder, "meta.json"), "-g", "cpu")
    theirs_path = os.path.join(work, "st-sog-decoded.ply")
    ref.convert(cli, sog, theirs_path)
    theirs = ref.read_ply(theirs_path)["vertex"]
    # The folder comes from a second k-means run: it is compared with its own decoding.
    theirs_folder_path = os.path.join(work, "st-sog-folder-decoded.ply")
    ref.convert(cli, os.path.join(folder, "meta.json"), theirs_folder_path)
    theirs_folder = ref.read_ply(theirs_folder_path)["vertex"]
    rest = [c for c in theirs.dtype.names if c.startswith("f_rest_")]
    if len(theirs) != n or len(rest) != 45:
        print("FAILED: splat-transform decoded %d Gaussians with %d f_rest (source %d)" %
              (len(theirs), len(rest), n))
        sys.exit(1)

    for label, path in (("zip", sog), ("folder", folder),
                        ("meta.json", os.path.join(folder, "meta.json"))):
        out = os.path.join(work, "ours-%s.ply" % label.replace(".", "-"))
        print(ref.run([tool, path, out]).strip())
        ours = ref.read_ply(out)["vertex"]
        if len(ours) != n:
            print("FAILED: we read %d Gaussians from the %s, splat-transform %d" % (len(ours), label, n))
            sys.exit(1)
        failures += ref.compare_exact("reader (%s) vs splat-transform" % label, ours,
                                      theirs if label == "zip" else theirs_folder,
                                      ref.GAUSSIAN_COLUMNS + rest)

    failures += ref.check_commands(vis4gs, sog, os.path.join(work, "ours-zip.ply"), work, "sog")
    failures += ref.check_commands(vis4gs, folder, os.path.join(work, "ours-folder.ply"), work,
                                   "sog-folder")

    # Only the degree asked for: degree 1 equals the first 3 coefficients per channel.
    out = os.path.join(work, "ours-sh1.ply")
    print(ref.run([tool, sog, out, "--sh=1"]).strip())
    sh1 = ref.read_ply(out)["vertex"]
    mapping = {"f_rest_%d" % (c * 3 + j): "f_rest_%d" % (c * 15 + j) for c in range(3) for j in range(3)}
    if sorted(c for c in sh1.dtype.names if c.startswith("f_rest_")) != sorted(mapping):
        print("FAILED: degree 1 reading has columns %s" % (sh1.dtype.names,))
        failures += 1
    else:
        renamed = {k: theirs[v] for k, v in mapping.items()}
        failures += ref.compare_exact("reader at SH degree 1 vs splat-transform", sh1, renamed, list(mapping))

    if failures:
        print("FAILED: %d checks failed" % failures)
        sys.exit(1)
    print("PASSED SOG (%s, %d Gaussians)" % (mode, n))


if __name__ == "__main__":
    main()
