"""The Python layer (vis4gs.open, Scene) gives the application's answers bit for bit.

  TestScriptingLayer.py demo VIS4GS LOG DEMO_OUTPUT
      the embedded demo log against `vis4gs demo`'s outputs (scores.csv, scores.ply,
      root-cause.txt) and against the plain VTK pipeline (reader ports -> filters)
  TestScriptingLayer.py folder VIS4GS
      a PLY + COLMAP cameras + images folder (shared data) against `vis4gs analyze` and
      `vis4gs render` run here on the same inputs

Every comparison is exact: float arrays compared as their bit patterns, files byte for byte,
rendered PNGs pixel for pixel."""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkIOImage import vtkPNGReader

import vis4gs

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "Testing", "Python"))
failures = []
vtkObject.GlobalWarningDisplayOff()  # the filter's warnings are checked through scene.warnings


def check(cond, what):
    if not cond:
        failures.append(what)


def same_bits(a, b):
    """Equal shapes and equal values, NaN included (the bit patterns of float64)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a.astype(np.float64).view(np.uint64),
                              b.astype(np.float64).view(np.uint64))
    return np.array_equal(a, b)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def png_pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    return np.asarray(dsa.WrapDataObject(image).PointData[0]).reshape(h, w, -1)


def plain_scores(scene_output, cameras_output, configure):
    """The obvious VTK pipeline: a reader port (or data) into vtkGaussianArtifactScoreFilter."""
    f = vis4gs.vtkGaussianArtifactScoreFilter()
    f.SetInputConnection(scene_output)
    f.SetCamerasConnection(cameras_output)
    configure(f)
    f.Update()
    pd = f.GetOutput().GetPointData()
    return {short: np.asarray(dsa.vtkDataArrayToVTKArray(pd.GetArray(array))).copy()
            for short, array in vis4gs.SCORES.items() if pd.GetArray(array) is not None}


def demo(vis4gs_exe, log, demo_output):
    scene = vis4gs.open(log)
    check(scene.iteration == scene.iterations[-1], f"default iteration is the last: {scene}")
    scores = scene.scores(["coverage", "blur", "needle", "shape"])

    # The plain pipeline: reader ports 0 and 1 into the score filter, nothing else set.
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(log)
    plain = plain_scores(reader.GetOutputPort(0), reader.GetOutputPort(1), lambda f: None)
    check(list(plain) == list(vis4gs.DEFAULT_SCORES),
          f"the filter's defaults {list(plain)} are the registry's {vis4gs.DEFAULT_SCORES}")
    for short in scores:
        check(same_bits(scores[short], plain[short]),
              f"demo {short}: the layer differs from the plain VTK pipeline")

    # A score only the registry names (issue 33): listed, computed as the plain pipeline does,
    # and read by a rule under its rule name.
    check({"render-cost", "cost-per-contribution"} <= set(vis4gs.SCORES),
          f"the render-cost scores are in vis4gs.SCORES: {list(vis4gs.SCORES)}")
    costly = vis4gs.open(log)
    cost = costly.scores(["render-cost", "cost-per-contribution"])
    plain_cost = plain_scores(reader.GetOutputPort(0), reader.GetOutputPort(1),
                              lambda f: f.SetScores("render-cost,cost-per-contribution"))
    for short in cost:
        check(same_bits(cost[short], plain_cost[short]),
              f"demo {short}: the layer differs from the plain VTK pipeline")
    ratio = cost["cost-per-contribution"]
    shown = np.isfinite(ratio)
    check(shown.any() and (ratio[shown] >= 1).all() and (cost["render-cost"] >= 0).all(),
          "render cost >= 0, cost per contribution >= 1 where finite")
    check(np.array_equal(np.isnan(ratio), cost["render-cost"] == 0),
          "cost per contribution is NaN exactly where nothing was evaluated")
    worst = vis4gs.open(log).select_rule("cost_per_contribution top 1%")
    k = int(np.ceil(0.01 * (~np.isnan(ratio)).sum()))
    check(int(worst.mask.sum()) >= k and np.all(ratio[worst.mask] >= np.sort(
        ratio[~np.isnan(ratio)])[-k]), "select_rule('cost_per_contribution top 1%') computes "
          f"the score and selects its top 1 % ({int(worst.mask.sum())} Gaussians)")
    check(all(np.isfinite(scores[s]).all() for s in ("blur", "needle")),
          "demo blur/needle are computed from the log's images (finite)")

    # The application's batch outputs: scores.csv byte for byte, scores.ply as float32.
    with tempfile.TemporaryDirectory() as tmp:
        csv = scene.to_csv(os.path.join(tmp, "scores.csv"))
        check(read_bytes(csv) == read_bytes(os.path.join(demo_output, "scores.csv")),
              "demo: the layer's scores.csv differs from vis4gs demo's")
        app = vis4gs.open(os.path.join(demo_output, "scores.ply"))
        for short in scores:
            array = vis4gs.SCORES[short]
            check(same_bits(app[array], scores[short].astype(np.float32)),
                  f"demo {array}: differs from vis4gs demo's scores.ply")

        # Only the scores asked for are computed.
        alone = vis4gs.open(log)
        coverage = alone.scores(["coverage"])
        check(list(coverage) == ["coverage"] and "BlurScore" not in alone.arrays,
              f"scores(['coverage']) computes coverage only: {alone.arrays}")
        check(same_bits(coverage["coverage"], scores["coverage"]), "coverage alone = with others")

        # The root-cause trace of vis4gs demo, step for step.
        with open(os.path.join(demo_output, "root-cause.txt")) as f:
            expected = f.read().split("\n")
        floater = int(re.match(r"Root-cause trace of Gaussian (\d+)", expected[0]).group(1))
        rows = [line.split() for line in expected[2:] if line.strip()]
        trace = alone.lineage(floater)
        got = [[str(s.gaussian_id), str(s.born), s.kind, "alive" if s.died is None else str(s.died)]
               + (["(in", "no", "snapshot)"] if s.snapshot is None
                  else [f"{s.value:.3f}", "at", str(s.snapshot)]) for s in trace]
        check(got == rows, f"lineage({floater}) differs from root-cause.txt:\n{got}\n{rows}")
        check(set(alone.ancestors([floater])) == {s.gaussian_id for s in trace[1:]},
              "ancestors() are the trace's Gaussians above the floater")
        tree_filter = vis4gs.vtkGaussianGenealogyTreeFilter()
        tree_filter.SetInputConnection(reader.GetOutputPort(3))
        tree_filter.Update()
        check(alone.tree.GetNumberOfVertices() == tree_filter.GetOutput().GetNumberOfVertices(),
              "the layer's tree is the reader -> tree filter's")

        # Another iteration: the snapshot nearest to it.
        early = scene.at(scene.iterations[1] + 1)
        reader.SetIteration(scene.iterations[1])
        reader.Update(0)
        check(early.iteration == scene.iterations[1] and same_bits(
            early.ids, dsa.WrapDataObject(reader.GetOutputDataObject(0)).PointData["GaussianId"]),
            f"at({scene.iterations[1] + 1}) is the snapshot of {scene.iterations[1]}")

        # Selection by mask and by ids, and the PLY export of a selection.
        low = scene.select(mask=scores["coverage"] < 0.1)
        n_low = int(np.count_nonzero(scores["coverage"] < 0.1))
        check(len(low) == n_low and n_low > 0, f"select(mask) keeps {len(low)} of {n_low}")
        check(same_bits(low["BlurScore"], scores["blur"][scores["coverage"] < 0.1]),
              "a selection keeps each Gaussian's scores")
        by_ids = scene.select(ids=low.ids[::2])
        check(same_bits(by_ids.ids, low.ids[::2]) and same_bits(by_ids.positions,
                                                               low.positions[::2]),
              "select(ids) keeps those Gaussians, in the scene's order")
        saved = vis4gs.open(low.save(os.path.join(tmp, "low.ply")), id_property="id")
        check(same_bits(saved.positions, low.positions) and same_bits(saved.ids, low.ids),
              "the saved selection reads back with its positions and GaussianIds")
        check(same_bits(saved["NeedleScore"], low["NeedleScore"]),
              "the saved selection holds its scores")

        # Bad requests: an error naming the file and the problem, never an empty result.
        for call, words in ((lambda: vis4gs.open(os.path.join(tmp, "nope.h5")), "nope.h5"),
                            (lambda: scene.scores(["sharpness"]), "unknown score sharpness"),
                            (lambda: saved.scores(["coverage"]), "need cameras"),
                            (lambda: scene.render(camera=999), "no camera 999"),
                            (lambda: scene.lineage(10 ** 9, score=None), "not in the genealogy")):
            try:
                call()
                check(False, f"no error for a request that should say '{words}'")
            except vis4gs.Vis4GSError as e:
                check(words in str(e), f"the error '{e}' says '{words}'")

        # Rendering a snapshot's own camera without a display: the rasteriser's image.
        pixels = scene.render(os.path.join(tmp, "view.png"), camera=0, size=(64, 48))
        png = png_pixels(os.path.join(tmp, "view.png"))
        check(png.shape == (48, 64, 3) and pixels.shape == (48, 64, 3), f"render size {png.shape}")
        # png_pixels gives VTK's rows (bottom first), render() the image's (top first).
        check(np.abs(png[::-1] / 255.0 - np.clip(pixels, 0, 1)).max() <= 0.5 / 255 + 1e-9,
              "the PNG is the rendered image rounded to 8 bits")
        check(png.max() > 0, "the rendered view is not black")
    return f"demo log: {len(scene)} Gaussians; 4 scores = plain pipeline = vis4gs demo's " \
           f"scores.csv/ply; lineage of {floater} = root-cause.txt ({len(trace)} steps)"


def folder(vis4gs_exe):
    from vis4gs_test_data import shared_data_dir
    data = shared_data_dir()
    ply = os.path.join(data, "inria_ply_tiny_kacytran", "point_cloud", "iteration_7000",
                       "point_cloud.ply")
    colmap = os.path.join(data, "colmap_statue_bartoszek")
    for path in (ply, colmap):
        if not os.path.exists(path):
            print(f"{path} is absent: skipped")
            sys.exit(77)
    options = dict(view_stride=8, loss_resolution=4)
    scene = vis4gs.open(ply, cameras=colmap)
    scores = scene.scores(["coverage", "blur", "needle", "shape"], **options)
    check(not any("cannot be computed" in w for w in scene.warnings),
          f"every score computed: {scene.warnings}")

    # The same images named through images= (matched to the cameras by name).
    named = vis4gs.open(ply, cameras=colmap, images=os.path.join(colmap, "images"))
    by_name = named.scores(["blur", "needle"], **options)
    check(same_bits(by_name["blur"], scores["blur"]) and same_bits(by_name["needle"],
                                                                   scores["needle"]),
          "images= gives the scores of the cameras' own image paths")
    check(same_bits(named.select(ids=[5, 3, 1]).ids, [1, 3, 5]), "select(ids) in scene order")

    plys = vis4gs.vtkGaussianSceneReader()
    plys.SetFileName(ply)
    cams = vis4gs.vtkGaussianCameraReader()
    cams.SetFileName(colmap)
    plain = plain_scores(plys.GetOutputPort(), cams.GetOutputPort(),
                         lambda f: (f.SetViewStride(8), f.SetLossResolution(4)))
    for short in scores:
        check(same_bits(scores[short], plain[short]),
              f"folder {short}: the layer differs from the plain VTK pipeline")

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "analyze")
        subprocess.run([vis4gs_exe, "analyze", ply, f"--cameras={colmap}", "--view-stride=8",
                        "--loss-resolution=4", "--overlay-views=0", "--top=1",
                        f"--output={out}"], check=True, stdout=subprocess.DEVNULL)
        check(read_bytes(scene.to_csv(os.path.join(tmp, "scores.csv")))
              == read_bytes(os.path.join(out, "scores.csv")),
              "folder: the layer's scores.csv differs from vis4gs analyze's")

        # One camera rendered by the layer and by `vis4gs render`: the same PNG pixels.
        subprocess.run([vis4gs_exe, "render", ply, f"--cameras={colmap}", "--camera=DSC_5290",
                        "--resolution=100,66", f"--output={tmp}/app.png"], check=True,
                       stdout=subprocess.DEVNULL)
        scene.render(f"{tmp}/layer.png", camera="DSC_5290", size=(100, 66))
        app, layer = png_pixels(f"{tmp}/app.png"), png_pixels(f"{tmp}/layer.png")
        check(app.shape == layer.shape and np.array_equal(app, layer),
              "folder: the layer's render differs from vis4gs render's")

        # A .splat scene too (antimatter15's format, the same reader).
        splat = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(ply))),
                             "model_1.splat")
        subprocess.run([vis4gs_exe, "render", splat, f"--cameras={colmap}", "--camera=DSC_5290",
                        "--resolution=100,66", f"--output={tmp}/app-splat.png"], check=True,
                       stdout=subprocess.DEVNULL)
        vis4gs.open(splat, cameras=colmap).render(f"{tmp}/layer-splat.png", camera="DSC_5290",
                                                  size=(100, 66))
        check(np.array_equal(png_pixels(f"{tmp}/app-splat.png"),
                             png_pixels(f"{tmp}/layer-splat.png")),
              "folder: the layer's render of the .splat differs from vis4gs render's")
    return f"PLY + COLMAP folder: {len(scene)} Gaussians; 4 scores = plain pipeline = vis4gs " \
           f"analyze's scores.csv; render (.ply, .splat) = vis4gs render's PNG"


if __name__ == "__main__":
    message = demo(*sys.argv[2:5]) if sys.argv[1] == "demo" else folder(sys.argv[2])
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(message)
