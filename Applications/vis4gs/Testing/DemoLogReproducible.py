"""The embedded demo log is reproducible with the command of Data/Demo/README.md.

Runs that command (vis4gs train) into a temporary folder and compares the new log with the
committed one: every snapshot array, table column, dataset and attribute equal, bit for bit,
except the wall-clock columns (metrics*/elapsed_s). The comparison reads both logs through
vis4gs_logger.logfile, so it holds across the layouts of DESIGN §3 (the committed log is
format version 1; `vis4gs train` writes version 2 since issue 32): the trainer's numbers
must not change, the file's layout may. A change of the trainer's arithmetic makes this fail; then the demo log,
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

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "TrainingLogger"))
from vis4gs_logger.logfile import open_log, read_snapshot, read_table, snapshot_iterations  # noqa: E402

# Read through logfile's functions (either layout); walked as plain datasets otherwise.
_TABLES = ("metrics/test", "metrics", "events", "lineage_breaks")
_LAYOUT = ("snapshots", "committed") + _TABLES


def readme_command(source_dir):
    text = open(os.path.join(source_dir, "Data", "Demo", "README.md")).read()
    block = re.search(r"```sh\n(vis4gs train .*?)```", text, re.S)
    if not block:
        sys.exit("FAILED: Data/Demo/README.md has no ```sh block with the vis4gs train command")
    return shlex.split(block.group(1).replace("\\\n", " "))


def _same(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype.kind in "SOU" or y.dtype.kind in "SOU":  # fixed- vs variable-length strings
        def text(v):
            return [e.decode() if isinstance(e, bytes) else str(e) for e in np.ravel(v)]
        return x.shape == y.shape and text(x) == text(y)
    return x.shape == y.shape and (
        np.array_equal(x, y, equal_nan=True) if x.dtype.kind == "f" else np.array_equal(x, y))


def _flatten(f):
    """{name: array} of every snapshot array, table column and other dataset, and
    {name: attributes} of the objects outside the layout-specific groups."""
    data, attrs = {}, {"/": {k: v for k, v in f.attrs.items() if k != "format_version"}}
    for iteration in snapshot_iterations(f):
        for name, value in read_snapshot(f, iteration).items():
            data[f"snapshots/{iteration:06d}/{name}"] = value
    for table in _TABLES:
        for name, value in read_table(f, table).items():
            if len(value):  # version 2 keeps empty tables that version 1 leaves out
                data[f"{table}/{name}"] = value

    def visit(name, obj):
        if name.split("/")[0] in _LAYOUT:
            return
        attrs[name] = dict(obj.attrs.items())
        if isinstance(obj, h5py.Dataset):
            data[name] = obj[()]

    f.visititems(visit)
    return data, attrs


def compare(expected, actual):
    problems = []
    (da, aa), (db, ab) = _flatten(expected), _flatten(actual)
    for name in sorted(set(aa) | set(ab)):
        if name not in ab or name not in aa:
            problems.append(f"{name}: {'missing in' if name not in ab else 'only in'} the new log")
            continue
        if sorted(aa[name]) != sorted(ab[name]):
            problems.append(f"{name}: attributes {sorted(aa[name])} vs {sorted(ab[name])}")
            continue
        problems += [f"{name}: attribute {k} differs" for k in aa[name]
                     if not _same(aa[name][k], ab[name][k])]
    for name in sorted(set(da) | set(db)):
        if name not in db or name not in da:
            problems.append(f"{name}: {'missing in' if name not in db else 'only in'} the new log")
        elif not name.endswith("elapsed_s") and not _same(da[name], db[name]):
            problems.append(f"{name}: values differ")
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
    with open_log(committed) as a, open_log(new) as b:
        problems = compare(a, b)
    if problems:
        print("\n".join(problems[:20]))
        sys.exit(f"FAILED: {len(problems)} differences between {committed} and {new}")
    print(f"the demo log is reproduced bit for bit (except elapsed_s) by: {' '.join(args[1:])}")


if __name__ == "__main__":
    main()
