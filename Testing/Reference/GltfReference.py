"""glTF KHR_gaussian_splatting against splat-transform 3.7 and the Khronos validator (issue 34).

1. splat-transform writes a scene (generated, SH degree 3 with a score column; or the real
   INRIA PLY) as .glb; our reading of that .glb must equal our reading of the PLY: positions,
   rotations and SH bit for bit (both tools turn the PLY's axes into glTF's by the same exact
   half turn about z, and back), log-scales and opacities within the float32 rounding of
   exp/log and sigmoid/logit that the extension's linear values impose.
2. Our writer's .glb and .gltf of the scene pass the Khronos glTF validator (npm
   gltf-validator): no error, warning or info except the validator's own gap, that it does not
   know KHR_gaussian_splatting (one UNSUPPORTED_EXTENSION info, and one
   MESH_PRIMITIVE_INVALID_ATTRIBUTE per attribute the extension defines, which it reports for
   splat-transform's .glb alike). Read back, they hold the source's positions, SH and scores
   bit for bit and its normalised rotations; a second write reads back bit for bit.
3. With the application built: `vis4gs render` of splat-transform's .glb gives the PNG of its
   decoded PLY, and `vis4gs analyze` runs on it.

Usage: GltfReference.py <vis4gsSceneConvert> <build dir> <work dir> generated|inria [vis4gs]
"""
import json
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import reference_ply as ref  # noqa: E402

# Attribute semantics KHR_gaussian_splatting defines (the validator does not know them).
EXTENSION_ATTRIBUTE = re.compile(
    r"/attributes/KHR_gaussian_splatting:(ROTATION|SCALE|OPACITY|SH_DEGREE_[0-3]_COEF_[0-6])$")

VALIDATE = """
const v = require(process.argv[1]);
const data = new Uint8Array(require('fs').readFileSync(process.argv[2]));
v.validateBytes(data, {uri: process.argv[2], maxIssues: 0})
  .then(r => console.log(JSON.stringify(r.issues)), e => { console.error(String(e)); process.exit(2); });
"""


def source_path(mode, work):
    if mode == "generated":
        cols = ref.generated_scene()
        cols["score"] = np.random.default_rng(34).uniform(0, 1, len(cols["x"]))
        path = os.path.join(work, "generated.ply")
        ref.write_ply(path, cols)
        return path
    from vis4gs_test_data import shared_data_dir
    return os.path.join(shared_data_dir(),
                        "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply")


def validator(build):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "install-gltf-validator.sh")
    r = subprocess.run(["bash", script, build], capture_output=True, text=True)
    if r.returncode != 0:
        sys.stdout.write(r.stderr)
        sys.exit(r.returncode)
    return r.stdout.strip().splitlines()[-1]


def validate(package, path):
    """Counts the validator's findings on @path beyond its not knowing the extension."""
    issues = json.loads(ref.run(["node", "-e", VALIDATE, package, path]))
    unknown_attributes = [m for m in issues["messages"]
                          if m["code"] == "MESH_PRIMITIVE_INVALID_ATTRIBUTE"
                          and EXTENSION_ATTRIBUTE.search(m["pointer"])]
    unsupported = [m for m in issues["messages"] if m["code"] == "UNSUPPORTED_EXTENSION"
                   and "KHR_gaussian_splatting" in m["message"]]
    others = [m for m in issues["messages"] if m not in unknown_attributes and m not in unsupported]
    print("validator on %s: %d errors, %d warnings, %d infos, %d hints; %d of them the unknown "
          "extension's attributes and %d its name" % (os.path.basename(path), issues["numErrors"],
                                                    issues["numWarnings"], issues["numInfos"],
                                                    issues["numHints"], len(unknown_attributes),
                                                    len(unsupported)))
    for m in others:
        print("  FAIL %s (%s) at %s" % (m["code"], m["message"], m["pointer"]))
    return len(others), len(unknown_attributes)


def decoded(tool, scene, out):
    print(ref.run([tool, scene, out]).strip())
    return ref.read_ply(out)["vertex"]


def within(what, ours, theirs, columns, bound, transform=lambda v: v):
    err = max(float(np.max(np.abs(transform(ours[c].astype(np.float64)) -
                                  transform(theirs[c].astype(np.float64))))) for c in columns)
    ok = err <= bound
    print("%s %s: max |difference| %.3g (bound %.3g)" % ("ok  " if ok else "FAIL", what, err, bound))
    return 0 if ok else 1


def main():
    tool, build, work, mode = sys.argv[1:5]
    vis4gs = sys.argv[5] if len(sys.argv) > 5 else ""
    os.makedirs(work, exist_ok=True)
    cli = ref.splat_transform(build)
    package = validator(build)
    src_path = source_path(mode, work)
    src = decoded(tool, src_path, os.path.join(work, "source-decoded.ply"))
    names = src.dtype.names
    rest = [c for c in names if c.startswith("f_rest_")]
    exact = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"] + rest
    failures = 0

    # 1. splat-transform's .glb read by us against our reading of its PLY.
    st_glb = os.path.join(work, "st.glb")
    ref.convert(cli, src_path, st_glb)
    st = decoded(tool, st_glb, os.path.join(work, "st-decoded.ply"))
    if len(st) != len(src):
        print("FAILED: splat-transform's .glb holds %d Gaussians, the PLY %d" % (len(st), len(src)))
        sys.exit(1)
    rotations = ["rot_%d" % i for i in range(4)]
    failures += ref.compare_exact("splat-transform .glb vs PLY, positions, SH and rotations", st, src,
                                  exact + rotations)
    failures += within("log-scales (float32 exp, then log)", st, src,
                       ["scale_%d" % i for i in range(3)], 1.2e-7 * 4)
    sigmoid = lambda v: 1 / (1 + np.exp(-v))  # noqa: E731
    failures += within("opacity (float32 sigmoid)", st, src, ["opacity"], 6e-8, sigmoid)
    errors, unknown = validate(package, st_glb)
    if errors or not unknown:
        print("FAIL: splat-transform's .glb should show only the validator's gap")
        failures += 1
    failures += ref.check_commands(vis4gs, st_glb, os.path.join(work, "st-decoded.ply"), work, "glb")

    # 2. Our writer: validator, then the exact read-back.
    q = np.stack([src[c].astype(np.float64) for c in rotations], 1)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    for ext in ("glb", "gltf"):
        ours_path = os.path.join(work, "ours." + ext)
        print(ref.run([tool, src_path, ours_path]).strip())
        errors, _ = validate(package, ours_path)
        failures += errors
        back = decoded(tool, ours_path, os.path.join(work, "ours-%s-decoded.ply" % ext))
        kept = exact + [c for c in names if c not in ref.GAUSSIAN_COLUMNS and c not in rest]
        failures += ref.compare_exact("our .%s read back: positions, SH and extras %s" % (ext, kept[len(exact):]),
                                      back, src, kept)
        b = np.stack([back[c].astype(np.float64) for c in rotations], 1)
        norm = np.linalg.norm(b, axis=1)
        failures += within("our .%s rotations are unit quaternions" % ext, {"n": norm},
                           {"n": np.ones(len(b))}, ["n"], 1e-6)
        b /= norm[:, None]
        b *= np.sign(np.sum(q * b, 1))[:, None]
        angle = np.degrees(4 * np.arctan2(np.linalg.norm(q - b, axis=1), np.linalg.norm(q + b, axis=1)))
        failures += within("our .%s rotations against the source (degrees)" % ext, {"a": angle},
                           {"a": np.zeros(len(b))}, ["a"], 1e-4)
        again_path = os.path.join(work, "again." + ext)
        print(ref.run([tool, os.path.join(work, "ours-%s-decoded.ply" % ext), again_path]).strip())
        again = decoded(tool, again_path, os.path.join(work, "again-%s-decoded.ply" % ext))
        failures += ref.compare_exact("a second write of .%s, read back" % ext, again, back,
                                      kept + rotations)

    if failures:
        print("FAILED: %d checks failed" % failures)
        sys.exit(1)
    print("PASSED glTF (%s, %d Gaussians)" % (mode, len(src)))


if __name__ == "__main__":
    main()
