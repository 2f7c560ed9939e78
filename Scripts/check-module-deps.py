#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Checks that each Vis4GS VTK module declares exactly what its own sources include.

A dependency listed under DEPENDS or PRIVATE_DEPENDS of a vtk.module is "unused" when no
header or source of the module (its folder, not Testing/) includes a header of that module;
a VTK or Vis4GS module whose header is included but that is not listed is "undeclared" (it
builds today only because another dependency drags it in). Which VTK module a header belongs
to is read from VTK's own hierarchy files (libvtk9.1: .../vtk/hierarchy/VTK/*-hierarchy.txt,
one line per class: "name ... ; header.h ; vtkModule"). Headers VTK does not list there
(third-party wrappers such as vtk_glew.h) are mapped below by hand.

Usage: check-module-deps.py [SOURCE_DIR]; exit status 0 when every module is exact.
"""
import glob
import os
import re
import sys

HIERARCHY = "/usr/lib/x86_64-linux-gnu/vtk/hierarchy/VTK"
# Headers of VTK modules that the hierarchy files do not list (no class in them).
EXTRA_HEADERS = {"vtk_glew.h": "VTK::glew", "vtk_hdf5.h": "VTK::hdf5"}


def vtk_headers():
    files = glob.glob(os.path.join(HIERARCHY, "*-hierarchy.txt"))
    if not files:
        sys.exit(f"FAILED: no VTK hierarchy files in {HIERARCHY} (Debian's libvtk9.1 installs them)")
    headers = dict(EXTRA_HEADERS)
    for path in files:
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                m = re.search(r";\s*(\S+\.h)\s*;\s*vtk(\w+)", line)
                if m:
                    headers.setdefault(m.group(1), "VTK::" + m.group(2))
    return headers


def parse_module(path):
    name, section, deps = None, None, []
    with open(path, encoding="utf-8") as f:
        for raw in f:
            line = raw.strip()
            if not line:
                continue
            if not raw[0].isspace():
                section = line
                continue
            if section == "NAME":
                name = line
            elif section in ("DEPENDS", "PRIVATE_DEPENDS"):
                deps.append(line)
    return name, deps


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    os.chdir(root)
    modules = sorted(
        m for m in glob.glob("**/vtk.module", recursive=True)
        if not m.startswith(("build", "Plugins", "Testing")) and "/Testing/" not in m)
    headers = vtk_headers()
    own = {}
    parsed = {}
    for m in modules:
        name, deps = parse_module(m)
        parsed[m] = (name, deps)
        for h in glob.glob(os.path.join(os.path.dirname(m), "*.h")):
            own[os.path.basename(h)] = name
    failures = []
    for m in modules:
        name, deps = parsed[m]
        folder = os.path.dirname(m)
        used = set()
        sources = [p for ext in ("h", "cxx", "txx", "inc") for p in glob.glob(f"{folder}/*.{ext}")]
        for src in sources:
            with open(src, encoding="utf-8", errors="replace") as f:
                for inc in re.findall(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', f.read(), re.M):
                    base = os.path.basename(inc)
                    module = own.get(base) or headers.get(base)
                    if module and module != name:
                        used.add(module)
        unused = [d for d in deps if d not in used]
        undeclared = sorted(u for u in used if u not in deps)
        if unused:
            failures.append(f"{m}: {name} lists {', '.join(unused)} but includes none of its headers")
        if undeclared:
            failures.append(f"{m}: {name} includes headers of {', '.join(undeclared)} without listing it")
    if failures:
        print("FAILED: module dependencies must match the includes:")
        for line in failures:
            print("  " + line)
        return 1
    print(f"module dependencies: the {len(modules)} modules list exactly what they include")
    return 0


if __name__ == "__main__":
    sys.exit(main())
