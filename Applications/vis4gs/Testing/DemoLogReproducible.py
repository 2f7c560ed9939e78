"""The embedded demo log is reproducible with the command of Data/Demo/README.md.

Runs that command (vis4gs train) into a temporary folder and compares the new log with the
committed one: every dataset and attribute equal, bit for bit, except the wall-clock columns
(metrics*/elapsed_s). A change of the trainer's arithmetic makes this fail; then the demo log,
the case study and the view baselines are regenerated together (Data/Demo/README.md).

Usage: DemoLogReproducible.py VIS4GS SOURCE_DIR WORKDIR
"""
import os
import re
import shlex
import subprocess
import sys

import h5py
import numpy as np


def readme_command(source_dir):
    text = open(os.path.join(source_dir, "Data", "Demo", "README.md")).read()
    block = re.search(r"```sh\n(vis4gs train .*?)```", text, re.S)
    if not block:
        sys.exit("FAILED: Data/Demo/README.md has no ```sh block with the vis4gs train command")
    return shlex.split(block.group(1).replace("\\\n", " "))


def compare(expected, actual):
    problems = []

    def attrs(name, a, b):
        ka, kb = sorted(a.attrs.keys()), sorted(b.attrs.keys())
        if ka != kb:
            problems.append(f"{name}: attributes {ka} vs {kb}")
            return
        for k in ka:
            if not np.array_equal(np.asarray(a.attrs[k]), np.asarray(b.attrs[k])):
                problems.append(f"{name}: attribute {k} differs")

    def visit(name, obj):
        if name not in actual:
            problems.append(f"{name}: missing in the new log")
            return
        other = actual[name]
        attrs(name, obj, other)
        if isinstance(obj, h5py.Dataset):
            if name.endswith("elapsed_s"):
                return
            x, y = obj[()], other[()]
            same = x.shape == y.shape and (
                np.array_equal(x, y, equal_nan=True) if x.dtype.kind == "f" else np.array_equal(x, y))
            if not same:
                problems.append(f"{name}: values differ")

    attrs("/", expected, actual)
    expected.visititems(visit)
    extra = []
    actual.visit(lambda n: extra.append(n) if n not in expected else None)
    problems += [f"{n}: only in the new log" for n in extra]
    return problems


def main():
    vis4gs, source_dir, workdir = sys.argv[1:4]
    os.makedirs(workdir, exist_ok=True)
    committed = os.path.join(source_dir, "Data", "Demo", "vis4gs-demo.h5")
    new = os.path.join(workdir, "vis4gs-demo.h5")
    args = readme_command(source_dir)
    args = [vis4gs] + [a for a in args[1:] if not a.startswith("--output=")] + ["--output=" + new]
    # The log does not depend on the thread count (tested in Core/Training): use the cores there are.
    args = [a for a in args if not a.startswith("--threads=")] + ["--threads=0"]
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    run = subprocess.run(args, cwd=source_dir, env=env, capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout + run.stderr)
        sys.exit(f"FAILED: {' '.join(args)} exited with {run.returncode}")
    with h5py.File(committed, "r") as a, h5py.File(new, "r") as b:
        problems = compare(a, b)
    if problems:
        print("\n".join(problems[:20]))
        sys.exit(f"FAILED: {len(problems)} differences between {committed} and {new}")
    print(f"the demo log is reproduced bit for bit (except elapsed_s) by: {' '.join(args[1:])}")


if __name__ == "__main__":
    main()
