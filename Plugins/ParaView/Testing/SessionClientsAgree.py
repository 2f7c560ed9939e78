"""One pipeline, four clients (issue 33): the application's document (`vis4gs view LOG
--dump-inputs`), `vis4gs analyze` (its scores.csv), the Python layer (vis4gs.vtkGaussianSession
under /usr/bin/python3 with the main build's package) and pvbatch (the plugin's "Vis4GS
Session") all read LOG through vtkGaussianSession; they must give the same Gaussians in the same
order and the same default score arrays (coverage, blur, needle, shape and NoVisibleView), value
for value (scores.csv as analyze prints them, "%.9g"). Independently of all four, the ids are
those of the log's last snapshot read with h5py, and every score varies (an empty or constant
array would make the comparison vacuous).

Usage: SessionClientsAgree.py VIS4GS PLUGIN PVPYTHONPATH LOG OUTPUT_DIR
(run with PYTHONPATH holding the main build's vis4gs package; pvbatch gets PVPYTHONPATH)"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

import vis4gs

program, plugin, pvpythonpath, log, output = sys.argv[1:6]
SCORES = ["ViewCoverage", "BlurScore", "NeedleScore", "NeedleShape", "NoVisibleView"]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def run(*command, env=None):
    p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=env, timeout=900)
    if p.returncode != 0:
        print("FAILED: %s exited with %d:\n%s" % (" ".join(command), p.returncode, p.stdout))
        sys.exit(1)


def arrays_of(polydata):
    pd = polydata.GetPointData()
    return {name: vtk_to_numpy(pd.GetArray(name)).copy()
            for name in ["GaussianId"] + SCORES if pd.GetArray(name) is not None}


shutil.rmtree(output, ignore_errors=True)
os.makedirs(output)

# Independent: the ids of the log's last snapshot (read first: h5py cannot open a file that this
# process's session holds open with other locking flags).
with h5py.File(log, "r") as h5:
    last = sorted(h5["snapshots"].keys())[-1]
    ids = h5["snapshots"][last]["id"][()]

# 1. The application's document: what the window gives its views.
run(program, "view", log, "--dump-inputs=" + os.path.join(output, "app"), "--threads=2")
reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(output, "app", "scene.vtp"))
reader.Update()
clients = {"the application": arrays_of(reader.GetOutput())}

# 2. vis4gs analyze (its default scores are the session's default ones).
run(program, "analyze", log, "--output=" + os.path.join(output, "analyze"), "--overlay-views=0",
    "--top=1", "--threads=2")
with open(os.path.join(output, "analyze", "scores.csv")) as f:
    rows = [line.rstrip("\n").split(",") for line in f if line.strip()]
header, csv_rows = rows[0], rows[1:]

# 3. Python: the session of the vis4gs package.
session = vis4gs.vtkGaussianSession()
session.SetFileName(log)
session.Update(session.GaussiansPort)
clients["Python"] = arrays_of(session.GetGaussiansOutput())

# 4. pvbatch: the plugin's Vis4GS Session, its Gaussians port saved as numpy arrays.
script = os.path.join(output, "pvbatch_session.py")
with open(script, "w") as f:
    f.write(
        "import sys\n"
        "import numpy as np\n"
        "from paraview import servermanager\n"
        "from paraview.simple import LoadPlugin\n"
        "from vtkmodules.util.numpy_support import vtk_to_numpy\n"
        "LoadPlugin(sys.argv[1], remote=False, ns=globals())\n"
        "session = Vis4GSSession(FileName=sys.argv[2])  # noqa: F821\n"
        "pd = servermanager.Fetch(session, idx=0).GetPointData()\n"
        "np.savez(sys.argv[3], **{pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i))\n"
        "                         for i in range(pd.GetNumberOfArrays())\n"
        "                         if pd.GetArray(i) is not None})\n")
env = dict(os.environ, PYTHONPATH=pvpythonpath)
npz = os.path.join(output, "pvbatch.npz")
run("/usr/bin/pvbatch", script, plugin, log, npz, env=env)
with np.load(npz) as saved:
    clients["pvbatch"] = {name: saved[name] for name in ["GaussianId"] + SCORES if name in saved}

for who, arrays in clients.items():
    missing = [n for n in ["GaussianId"] + SCORES if n not in arrays]
    check(not missing, f"{who} lacks {missing}")
    if missing:
        continue
    check(np.array_equal(arrays["GaussianId"].astype(np.int64), ids.astype(np.int64)),
          f"{who}: the Gaussians are not the last snapshot's {len(ids)} ({last}, h5py)")
    for name in SCORES:
        check(len(np.unique(arrays[name])) > 1, f"{who}: {name} is constant")
        reference = clients["the application"].get(name)
        check(reference is not None and np.array_equal(
            arrays[name].astype(np.float64), reference.astype(np.float64), equal_nan=True),
            f"{who}: {name} differs from the application's")

# analyze's scores.csv printed from the application's arrays, row for row.
app = clients["the application"]
check(header[0] == "GaussianId" and all(n in header for n in SCORES),
      f"scores.csv has the columns {header}")
check(len(csv_rows) == len(ids), f"scores.csv has {len(csv_rows)} rows, the log {len(ids)}")
if not failures:
    columns = [header.index(n) for n in SCORES]
    differ = 0
    for r, row in enumerate(csv_rows):
        mine = [str(int(app["GaussianId"][r]))] + [
            str(int(app[n][r])) if n == "NoVisibleView" else "%.9g" % app[n][r] for n in SCORES]
        differ += mine != [row[0]] + [row[c] for c in columns]
    check(differ == 0, f"{differ} rows of analyze's scores.csv differ from the application's")

if failures:
    print("FAILED:", *failures, sep="\n  ")
    sys.exit(1)
print(f"one session, four clients: {len(ids)} Gaussians' {', '.join(SCORES)} equal in the "
      f"application, vis4gs analyze, Python and pvbatch")
