"""pvbatch tests of the Vis4GS ParaView plugin.

  pvbatch TestVis4GSPlugin.py demo PLUGIN LOG DEMO_OUTPUT SCREENSHOT
      loads the plugin, reads the embedded demo log (its snapshot iterations are the time
      steps), computes the scores at the last one and checks them against `vis4gs demo`'s
      scores.csv (the same numbers in the same format, Gaussian by Gaussian), builds the
      genealogy tree and checks the floater's ancestors (its parents in the tree, and the
      Vis4GS Lineage table) against root-cause.txt, and saves a screenshot of the Gaussians
      colored by their Blur score in ParaView's Point Gaussian representation.
  pvbatch TestVis4GSPlugin.py folder PLUGIN SCORES_CSV PLY CAMERAS
      a 3DGS PLY with a COLMAP folder: the scores (view stride 8, loss resolution 4) against
      the scores.csv of `vis4gs analyze` with the same options.
  pvbatch TestVis4GSPlugin.py scores PLUGIN LOG SCORES_CSV ARRAY...
      the scores named by ARRAY (the filter's Scores list, the score registry's array names) at
      the log's last snapshot against the scores.csv of `vis4gs analyze LOG --scores=...`: a
      score added to the registry reaches the plugin with no edit of its XML.
  pvbatch TestVis4GSPlugin.py cameras PLUGIN CAMERAS_JSON COUNT
      Vis4GS Cameras with its defaults reads every camera of a cameras.json beside an empty
      images/ folder (issue 31 part 5: no image is needed to read or score cameras).
  mpiexec -n K pvbatch TestVis4GSPlugin.py mpi PLUGIN LOG SCORES_CSV K
      the scores of the log's last snapshot on K processes (the filter shares the views over
      them) against one process's scores.csv (`vis4gs demo`): every Gaussian once, View
      Coverage, needle shape and the flags as printed there, Blur and Needle to its 9 digits
      (the order of the sums over views differs, 1e-15 relative)."""
import csv
import re
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, GetActiveViewOrCreate, LoadPlugin, OutputPort, Render,
                             SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def same_as_csv(scores, path, port=0):
    """The filter's arrays (output `port`) printed as the application prints scores.csv, row
    for row; returns the number of rows and the column names."""
    data = servermanager.Fetch(scores, idx=port)
    pd = data.GetPointData()
    ids = vtk_to_numpy(pd.GetArray("GaussianId"))
    with open(path) as f:
        rows = list(csv.reader(f))
    header, app = rows[0], rows[1:]
    check(len(app) == data.GetNumberOfPoints(), f"{data.GetNumberOfPoints()} Gaussians, "
          f"{path} {len(app)}")
    columns = {name: vtk_to_numpy(pd.GetArray(name)) for name in header[1:]}
    differ = 0
    for r, row in enumerate(app[:data.GetNumberOfPoints()]):
        mine = [str(int(ids[r]))] + [
            str(int(columns[name][r])) if name == "NoVisibleView" else "%.9g" % columns[name][r]
            for name in header[1:]]
        differ += mine != row
    check(differ == 0, f"{differ} Gaussians' scores differ from {path}")
    return len(app), header[1:]


mode = sys.argv[1]
LoadPlugin(sys.argv[2], remote=False, ns=globals())
if mode == "folder":
    app_csv, ply, colmap = sys.argv[3:6]
    scene = Vis4GSGaussianScene(FileName=ply)  # noqa: F821 (defined by the plugin)
    cameras = Vis4GSCameras(FileName=colmap)  # noqa: F821
    scores = Vis4GSArtifactScores(Input=scene, Cameras=cameras, ViewStride=8,  # noqa: F821
                                  LossResolution=4)
    count, names = same_as_csv(scores, app_csv)
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(f"ParaView plugin: PLY + COLMAP folder, {count} Gaussians' {', '.join(names)} = "
          "vis4gs analyze's scores.csv")
    sys.exit(0)

if mode == "cameras":
    # A cameras.json beside an empty images/ folder, with the reader's defaults: every camera
    # is read (without an image), since the scores and rendering do not need one.
    cameras_json, count = sys.argv[3], int(sys.argv[4])
    table = servermanager.Fetch(Vis4GSCameras(FileName=cameras_json))  # noqa: F821
    rows = table.GetNumberOfRows()
    check(rows == count, f"{rows} cameras read from {cameras_json}, expected {count}")
    images = table.GetColumnByName("Image")
    check(images is not None and all(images.GetValue(r) == "" for r in range(rows)),
          "the cameras have no image")
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(f"ParaView plugin: {rows} cameras of {cameras_json} beside an empty images/ folder")
    sys.exit(0)

if mode == "mpi":
    from paraview.modules.vtkRemotingCore import vtkProcessModule
    log, app_csv, processes = sys.argv[3], sys.argv[4], int(sys.argv[5])
    ranks = vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
    check(ranks == processes, f"{ranks} processes, expected {processes}")
    reader = Vis4GSTrainingLog(FileName=log)  # noqa: F821 (defined by the plugin)
    reader.UpdatePipelineInformation()
    # SharePreparation (off by default) on: the path under test shares the preparation.
    scores = Vis4GSArtifactScores(Input=OutputPort(reader, 0),  # noqa: F821
                                  Cameras=OutputPort(reader, 1), SharePreparation=1)
    scores.UpdatePipeline(time=list(reader.TimestepValues)[-1])
    data = servermanager.Fetch(scores)
    pd = data.GetPointData()
    with open(app_csv) as f:
        rows = list(csv.reader(f))
    header, app = rows[0], rows[1:]
    check(len(app) == data.GetNumberOfPoints(),
          f"{data.GetNumberOfPoints()} Gaussians gathered from {ranks} processes, {len(app)} in "
          f"{app_csv}")
    ids = vtk_to_numpy(pd.GetArray("GaussianId"))
    differ = {}
    for c, name in enumerate(header[1:], start=1):
        array = pd.GetArray(name)
        check(array is not None, f"no {name} array")
        if array is None:
            continue
        mine = vtk_to_numpy(array)
        for r, row in enumerate(app[:data.GetNumberOfPoints()]):
            if str(int(ids[r])) != row[0]:
                differ[name] = differ.get(name, 0) + 1
            elif name in ("BlurScore", "NeedleScore"):
                theirs = float(row[c])
                if not (abs(mine[r] - theirs) <= 1e-8 * abs(theirs) or (mine[r] != mine[r]
                                                                           and theirs != theirs)):
                    differ[name] = differ.get(name, 0) + 1
            elif (str(int(mine[r])) if name == "NoVisibleView" else "%.9g" % mine[r]) != row[c]:
                differ[name] = differ.get(name, 0) + 1
    check(not differ, f"Gaussians whose scores differ from {app_csv}: {differ}")
    # The processes (all on this machine) prepared the projection once between them, in
    # shared memory (Vis4GSNodeSharedMemory), and the scores above are still one process's.
    scores.UpdatePropertyInformation()
    shared = scores.GetPropertyValue("PreparationProcesses")
    check(shared == ranks, f"preparation shared by {shared} processes, expected {ranks}")
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    # No sys.exit here: pvbatch under mpiexec ends its other processes when the script ends.
    print(f"ParaView plugin on {ranks} processes: {len(app)} Gaussians' {', '.join(header[1:])} "
          f"= one process's scores.csv, the preparation shared by {shared} processes")

if mode == "scores":
    log, app_csv, arrays = sys.argv[3], sys.argv[4], sys.argv[5:]
    reader = Vis4GSTrainingLog(FileName=log)  # noqa: F821 (defined by the plugin)
    reader.UpdatePipelineInformation()
    scores = Vis4GSArtifactScores(Input=OutputPort(reader, 0),  # noqa: F821
                                  Cameras=OutputPort(reader, 1))
    # The list comes from the filter at run time (the score registry), not from the XML.
    scores.UpdatePropertyInformation()
    available = list(scores.Scores.Available)
    check(set(arrays) <= set(available), f"the Scores list {available} lacks {arrays}")
    scores.Scores = arrays
    scores.UpdatePipeline(time=list(reader.TimestepValues)[-1])
    count, names = same_as_csv(scores, app_csv)
    check(names[:len(arrays)] == arrays, f"scores.csv has {names}, asked for {arrays}")
    pd = servermanager.Fetch(scores).GetPointData()
    others = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())
              if pd.GetArrayName(i) in ("ViewCoverage", "BlurScore", "NeedleScore")]
    check(not others, f"scores not asked for were computed: {others}")
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(f"ParaView plugin: {count} Gaussians' {', '.join(names)} = vis4gs analyze's scores.csv")
    sys.exit(0)

if mode == "demo":
    log, demo_output, screenshot = sys.argv[3:6]
    reader = Vis4GSTrainingLog(FileName=log)  # noqa: F821 (defined by the plugin)
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    check(len(times) > 1 and times == sorted(times), f"snapshot iterations as time steps: {times}")

    scores = Vis4GSArtifactScores(Input=OutputPort(reader, 0),  # noqa: F821
                                  Cameras=OutputPort(reader, 1))
    scores.UpdatePipeline(time=times[-1])
    count, names = same_as_csv(scores, f"{demo_output}/scores.csv")

    tree_filter = Vis4GSGenealogyTree(Input=OutputPort(reader, 3))  # noqa: F821
    tree = servermanager.Fetch(tree_filter)
    with open(f"{demo_output}/root-cause.txt") as f:
        lines = f.read().split("\n")
    floater = int(re.match(r"Root-cause trace of Gaussian (\d+)", lines[0]).group(1))
    expected = [int(line.split()[0]) for line in lines[2:] if line.strip()]
    pedigree = tree.GetVertexData().GetPedigreeIds()
    vertex = {pedigree.GetValue(v): v for v in range(tree.GetNumberOfVertices())}
    chain, v = [], vertex.get(floater)
    while v is not None and v != tree.GetRoot():
        chain.append(pedigree.GetValue(v))
        v = tree.GetParent(v)
    check(chain == expected,
          f"the floater's ancestry {chain} differs from root-cause.txt {expected}")
    lineage = Vis4GSLineage(Input=tree_filter, GaussianId=floater)  # noqa: F821
    trace = servermanager.Fetch(lineage)
    traced = [trace.GetValueByName(r, "GaussianId").ToInt()
              for r in range(trace.GetNumberOfRows())]
    check(traced == expected,
          f"Vis4GS Lineage of {floater} gives {traced}, root-cause.txt {expected}")

    # The session (the pipeline the application, vis4gs analyze and the Python layer use): its
    # Gaussians port equals the demo's scores.csv too, its tree port the genealogy filter's tree.
    session = Vis4GSSession(FileName=log)  # noqa: F821
    session_count, _ = same_as_csv(session, f"{demo_output}/scores.csv", port=0)
    check(session_count == count, "the session's Gaussians are the demo's")
    session_tree = servermanager.Fetch(session, idx=3)
    check(session_tree.GetNumberOfVertices() == tree.GetNumberOfVertices(),
          f"the session's tree has {session_tree.GetNumberOfVertices()} vertices, the genealogy "
          f"filter's {tree.GetNumberOfVertices()}")

    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [640, 480]
    view.ViewTime = times[-1]
    display = Show(scores, view)
    display.SetRepresentationType("Point Gaussian")
    display.GaussianRadius = 0.02
    ColorBy(display, ("POINTS", "BlurScore"))
    display.RescaleTransferFunctionToDataRange(True)
    view.ResetCamera()
    Render(view)
    SaveScreenshot(screenshot, view, ImageResolution=[640, 480])
    png = vtkPNGReader()
    png.SetFileName(screenshot)
    png.Update()
    pixels = vtk_to_numpy(png.GetOutput().GetPointData().GetScalars())
    check(png.GetOutput().GetDimensions()[:2] == (640, 480) and pixels.std() > 1,
          "the screenshot is 640x480 and not blank")

    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(f"ParaView plugin: {len(times)} time steps; {count} Gaussians' {', '.join(names)} "
          f"= vis4gs demo's scores.csv (the scores filter and the session); ancestry and "
          f"Vis4GS Lineage of {floater} = root-cause.txt; "
          f"{screenshot}")
