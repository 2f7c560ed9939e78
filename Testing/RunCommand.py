"""Runs one command line of a test and checks what it claims: its exit status, the files it
says it wrote (removed first, so an old file cannot pass), the files it must not leave behind,
and optionally text in its output. Text alone is never enough: an error message can print the
same words, so the exit status is always checked. CTest's PASS_REGULAR_EXPRESSION ignores the
exit status; no test uses it (vis4gs_add_checked_test in CMake/Vis4GSTesting.cmake runs this).

Usage: RunCommand.py [--status=N] [--output=REGEX]... [--file=PATH]... [--png=PATH:W,H]...
                     [--absent=PATH]... -- COMMAND [ARGS...]

  --status=N       the exit status COMMAND must return (default 0; vis4gs returns 1 for a
                   failure it explains and 2 for a bad command line)
  --output=REGEX   stdout and stderr together must match REGEX (re.search, DOTALL)
  --file=PATH      COMMAND writes PATH: a non-empty file after the run
  --png=PATH:W,H   COMMAND writes the PNG PATH: it decodes (VTK's PNG reader), is W x H and is
                   not one flat colour
  --absent=PATH    PATH must not exist after the run (a failed command leaves no output)
Prints "FAILED: ..." and exits 1 when a check fails.
"""
import os
import re
import shutil
import subprocess
import sys


def fail(message, output=None):
    if output is not None:
        print(output)
    print("FAILED: " + message)
    sys.exit(1)


def check_png(path, width, height):
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    reader = vtkPNGReader()
    if not reader.CanReadFile(path):
        fail(f"{path} is not a PNG file")
    reader.SetFileName(path)
    reader.Update()
    dims = reader.GetOutput().GetDimensions()
    if (dims[0], dims[1]) != (width, height):
        fail(f"{path} is {dims[0]} x {dims[1]}, not {width} x {height}")
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    if pixels.size == 0 or np.all(pixels == pixels[0]):
        fail(f"{path} is one flat colour: nothing was drawn")


def main(argv):
    if "--" not in argv:
        fail("usage: RunCommand.py [checks] -- COMMAND [ARGS...]")
    split = argv.index("--")
    options, command = argv[:split], argv[split + 1:]
    status, patterns, files, pngs, absent = 0, [], [], [], []
    for option in options:
        key, _, value = option.partition("=")
        if key == "--status":
            status = int(value)
        elif key == "--output":
            patterns.append(value)
        elif key == "--file":
            files.append(value)
        elif key == "--png":
            path, _, size = value.rpartition(":")
            w, h = (int(v) for v in size.split(","))
            pngs.append((path, w, h))
        elif key == "--absent":
            absent.append(value)
        else:
            fail(f"unknown option {option}")
    for path in files + [p for p, _, _ in pngs] + absent:
        if os.path.isdir(path):
            shutil.rmtree(path)
        elif os.path.exists(path):
            os.remove(path)
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         errors="replace")
    output = run.stdout
    if run.returncode != status:
        fail(f"{os.path.basename(command[0])} exited with status {run.returncode}, expected "
             f"{status}", output)
    print(output, end="")
    for pattern in patterns:
        if not re.search(pattern, output, re.S):
            fail(f"the output does not match {pattern!r}")
    for path in files:
        if not os.path.isfile(path) or os.path.getsize(path) == 0:
            fail(f"{path} was not written (or is empty)")
    for path, w, h in pngs:
        if not os.path.isfile(path):
            fail(f"{path} was not written")
        check_png(path, w, h)
    for path in absent:
        if os.path.exists(path):
            fail(f"{path} exists after the run")
    print(f"exit status {status} as expected; {len(files) + len(pngs)} files checked")


if __name__ == "__main__":
    main(sys.argv[1:])
