"""Messages for people (issue 35 part 6, issue 33): every command on bad input.

  CheckMessages.py VIS4GS DEMO_LOG WORKDIR

Runs each command of vis4gs on a missing file, damaged files (bytes that are no log, a PLY cut
short, the demo log with damaged events or a damaged snapshot, as CheckDamagedLog.py makes
them), a bad option and an output it cannot write, and checks standard error (a file here, not
a terminal):
  - no VTK object address (0x and 6+ hex digits), no "ERROR: In " / "Warning: In " header, no
    escape character (vtkLogger's colours), no vtkLogger line ("ERR|", "WARN|");
  - a failing run exits non-zero and says "vis4gs COMMAND: error: " naming the file (or the
    option) it could not use;
  - every line is said once (warnings once each).
`vis4gs view` is run too when a display is there (the suite's one Xvfb).
"""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from Checks import check, finish  # noqa: E402
from CheckDamagedLog import damage  # noqa: E402

FORBIDDEN = [(re.compile(r"0x[0-9a-fA-F]{6,}"), "an object address"),
             (re.compile(r"(ERROR|Warning|Generic Warning): In "), "VTK's 'In file, line' header"),
             (re.compile("\x1b"), "an escape character"),
             (re.compile(r"\b(ERR|WARN)\|"), "a vtkLogger line")]


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: CheckMessages.py VIS4GS DEMO_LOG WORKDIR")
    vis4gs, demo, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    missing_log = os.path.join(work, "missing.h5")
    missing_ply = os.path.join(work, "missing.ply")
    garbage_log = os.path.join(work, "garbage.h5")
    with open(garbage_log, "wb") as f:
        f.write(b"this is no HDF5 file\n" * 10)
    cut_ply = os.path.join(work, "cut.ply")
    with open(cut_ply, "wb") as f:
        f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
                + b"".join(b"property float %s\n" % n for n in
                           (b"x", b"y", b"z", b"opacity", b"scale_0", b"scale_1", b"scale_2",
                            b"rot_0", b"rot_1", b"rot_2", b"rot_3", b"f_dc_0", b"f_dc_1",
                            b"f_dc_2"))
                + b"end_header\n" + b"\0" * 100)
    events_log = os.path.join(work, "damaged-events.h5")
    damage("events", demo, events_log)
    snapshot_log = os.path.join(work, "damaged-snapshot.h5")
    damage("snapshot", demo, snapshot_log)
    nowhere = "/proc/vis4gs-nowhere"  # cannot be created, even by root
    scene = os.path.join(work, "scene.ply")  # a good scene, for render's unwritable output
    if subprocess.run([vis4gs, "convert", demo, scene], stdout=subprocess.DEVNULL).returncode:
        sys.exit("FAILED: vis4gs convert could not make the scene for render")
    out = os.path.join(work, "out")

    # (command, arguments, what the error must name; None: the run may succeed)
    cases = [
        ("analyze", [missing_log], missing_log),
        ("analyze", [garbage_log], garbage_log),
        ("analyze", [cut_ply], cut_ply),
        ("analyze", [events_log, "--output=" + out + "-events", "--overlay-views=0"], None),
        ("analyze", [snapshot_log, "--output=" + out + "-snapshot", "--overlay-views=0"], None),
        ("analyze", [demo, "--output=" + nowhere, "--overlay-views=0"], nowhere),
        ("analyze", [demo, "--frobnicate"], "--frobnicate"),
        ("analyze", [demo, "--threads=x"], "--threads"),
        ("render", [missing_ply], missing_ply),
        ("render", [cut_ply, "--output=" + out + ".png"], cut_ply),
        ("render", [garbage_log, "--output=" + out + ".png"], garbage_log),
        ("render", [scene, "--resolution=32,32", "--output=" + nowhere + "/x.png"], nowhere),
        ("compare", [missing_log, demo], missing_log),
        ("compare", [garbage_log, demo], garbage_log),
        ("compare", [demo, demo, "--iteration-a=1600", "--output=" + nowhere], nowhere),
        ("repair", [missing_log, missing_ply], missing_log),
        ("repair", [demo, cut_ply], cut_ply),
        ("convert", [missing_ply, out + ".ply"], missing_ply),
        ("convert", [cut_ply, out + ".ply"], cut_ply),
        ("convert", [garbage_log, out + ".ply"], garbage_log),
        ("convert", [snapshot_log, out + "-snapshot.ply"], None),
        ("convert", [demo, nowhere + "/x.spz"], nowhere),
        ("convert", [demo, out + ".xyz"], out + ".xyz"),
        ("train", [missing_ply], missing_ply),
        ("train", [cut_ply], cut_ply),
        ("demo", ["--no-gui", "--log=" + missing_log], missing_log),
        ("demo", ["--no-gui", "--log=" + garbage_log], garbage_log),
        ("demo", ["--no-gui", "--output=" + nowhere], nowhere),
    ]
    if os.environ.get("DISPLAY"):
        cases += [("view", [missing_log, "--dump-inputs=" + out + "-view"], missing_log),
                  ("view", [garbage_log, "--dump-inputs=" + out + "-view"], garbage_log),
                  ("view", [cut_ply, "--dump-inputs=" + out + "-view"], cut_ply)]
    for command, args, names in cases:
        p = subprocess.run([vis4gs, command, *args, *([] if "--threads=x" in args else
                                                      ["--threads=2"])],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                           errors="replace", timeout=600)
        what = "vis4gs %s %s" % (command, " ".join(os.path.basename(a) for a in args))
        lines = [line for line in p.stderr.splitlines() if line.strip()]
        bad = [(why, line) for line in lines for pattern, why in FORBIDDEN if pattern.search(line)]
        check(not bad, "%s: nothing of VTK's decorations on stderr%s" % (
            what, "" if not bad else " (%s: %r)" % bad[0]))
        repeated = sorted({line for line in lines if lines.count(line) > 1})
        check(not repeated, "%s: each line said once%s" % (
            what, "" if not repeated else " (repeated: %r)" % repeated[0][:200]))
        if names is None:
            if p.returncode != 0:
                names = args[0]
            else:
                check(True, "%s: succeeds (status 0), its warnings clean" % what)
                continue
        errors = [line for line in lines if line.startswith("vis4gs %s: error: " % command)]
        check(p.returncode != 0, "%s: fails (status %d)" % (what, p.returncode))
        check(any(names in line or os.path.basename(names) in line for line in errors),
              "%s: 'vis4gs %s: error: ' names %s: %r" % (
                  what, command, os.path.basename(names), (errors or lines or ["nothing"])[0][:300]))
        others = [line for line in lines if re.match(r"vis4gs[^:]*: [^:]*error:", line)
                  and not line.startswith("vis4gs %s: error: " % command)]
        check(not others, "%s: every error in the form 'vis4gs %s: error: ...'%s" % (
            what, command, "" if not others else " (%r)" % others[0][:200]))
    finish("every command on bad input: errors in one form, naming the file, no VTK decorations")


if __name__ == "__main__":
    main()
