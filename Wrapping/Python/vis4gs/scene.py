"""A Python way into Vis4GS, thin over the VTK classes.

    import vis4gs
    scene = vis4gs.open("Data/Demo/vis4gs-demo.h5", iteration=600)
    scores = scene.scores(["coverage", "blur", "needle"])   # numpy arrays by short name
    for step in scene.lineage(25704): print(step)            # back to its root
    scene.select(mask=scores["coverage"] < 0.1).save("floaters.ply")
    scene.render("view.png", camera=0)
    floaters = scene.select_rule("views<=3 and opacity>=0.1")   # guided clean-up (issue 20)
    effect = scene.measure_removal(ids=floaters.ids)            # per view, before / after
    scene.at(1600).select_rule(floaters.rule)                   # the rule on another snapshot
    diff = scene.at(400).compare(scene, move=0.01)              # born, died, moved, ... ids

A Scene opened from a file is a vtkGaussianSession (the file's reader, chosen by content, its
cameras, the score, genealogy and removal-effect filters, in one wrapped VTK algorithm that
the `vis4gs` program uses too); the other calls connect vtkGaussianGenealogyLineage,
vtkGaussianRasterizer, vtkGaussianPLYWriter, vtkGaussianRuleSelectionFilter,
vtkGaussianStateComparisonFilter and vtkGaussianFineTuneFilter the way the program does, so the
arrays are the program's, bit for bit.
The VTK objects stay reachable (`scene.polydata`, `scene.cameras`, `scene.tree`) for anything
this layer does not cover.
"""
import collections
import math
import os
import re

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_ID_TYPE, VTK_STRING, vtkIdTypeArray, vtkObject
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData, vtkTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from .vis4gsFiltersDiagnostics import vtkGaussianArtifactScoreFilter, vtkGaussianScoreRegistry
from .vis4gsFiltersGenealogy import vtkGaussianGenealogyLineage, vtkGaussianGenealogyTreeFilter
from .vis4gsFiltersRaster import vtkGaussianRasterizer
from .vis4gsFiltersSelection import (vtkGaussianFineTuneFilter,
                                     vtkGaussianRemovalEffectFilter,
                                     vtkGaussianRuleSelectionFilter,
                                     vtkGaussianStateComparisonFilter)
from .vis4gsFiltersSession import vtkGaussianSession
from .vis4gsIOScene import vtkGaussianPLYWriter

# The scores of the registry (Core/Diagnostics/ScoreRegistry.h, vtkGaussianScoreRegistry):
# short names (as `vis4gs analyze --scores` spells them) and their arrays, in the order the
# program writes them; the default set; what each needs.
_REGISTRY = vtkGaussianScoreRegistry
SCORES = collections.OrderedDict((_REGISTRY.GetName(i), _REGISTRY.GetArrayName(i))
                                 for i in range(_REGISTRY.GetNumberOfScores()))
DEFAULT_SCORES = tuple(_REGISTRY.GetDefaultScores().split(","))
_NEEDS_CAMERAS = {_REGISTRY.GetName(i) for i in range(_REGISTRY.GetNumberOfScores())
                  if _REGISTRY.GetNeedsCameras(i)}
# vtkGaussianArtifactScoreFilter's parameters, as keywords of Scene.scores().
_SCORE_PARAMETERS = {"loss_resolution": "LossResolution",
                     "coverage_resolution": "CoverageResolution",
                     "view_stride": "ViewStride", "footprint": "FootprintMode",
                     "float_accumulation": "FloatAccumulation",
                     "occlusion_threshold": "OcclusionThreshold", "lam": "Lambda"}
_BIRTH_KINDS = {0: "root", 1: "clone", 2: "split", 3: "clone-split"}
# How select_rule() combines with a current selection (vtkGaussianRuleSelectionFilter).
_COMBINE = {None: 0, "replace": 0, "add": 1, "subtract": 2, "intersect": 3}
# The rule attributes that are scores (SelectionRule.h: each registered score by its rule
# name), with the score each needs; "views" is View Coverage times the views used. "needle" is
# the shape, computed from the log-scales.
_RULE_SCORES = dict([(_REGISTRY.GetRuleName(i), _REGISTRY.GetName(i))
                     for i in range(_REGISTRY.GetNumberOfScores())] + [("views", "coverage")])
# before-after.csv of `vis4gs analyze --report`: its columns, in its order.
_REMOVAL_CSV = ("view", "split", "affected", "psnr_before", "psnr_after", "ssim_before",
                "ssim_after", "l1_before", "l1_after")
# vtkGaussianStateComparisonFilter's flags (StateComparison.h) and id sets of Comparison.
_CHANGES = collections.OrderedDict([("moved", 1), ("opacity_changed", 2), ("scale_changed", 4),
                                    ("born", 8), ("died", 16)])

Ancestor = collections.namedtuple(
    "Ancestor", "gaussian_id born kind died snapshot value",
    defaults=(None,))
Ancestor.__doc__ = ("One step of a root-cause trace: the Gaussian, its birth iteration and "
                    "kind, its death iteration (None: alive), the snapshot nearest its birth "
                    "that holds it (None: none) and its value there (NaN without one).")


class Vis4GSError(RuntimeError):
    """A file that cannot be read or a request that cannot be answered, naming which."""


def _new_session(path, cameras=None, images=None, id_property=None):
    """A vtkGaussianSession on a file with the options of vis4gs.open()."""
    session = vtkGaussianSession()
    session.SetFileName(os.fspath(path))
    if cameras:
        session.SetCamerasFileName(os.fspath(cameras))
    if images:
        session.SetImageDirectory(os.fspath(images))
    if id_property:
        session.SetIdProperty(id_property)
    return session


def _error_collector(messages):
    """An ErrorEvent observer appending the message text to `messages`."""
    @calldata_type(VTK_STRING)
    def collect(caller, event, text):
        messages.append(text)
    return collect


def _plain_error(messages):
    """VTK error texts without their "ERROR: In <source>, line <n>" and "<class> (<address>): "
    prefix: the session's messages name the file and the problem already."""
    plain = [re.sub(r"^ERROR: In [^\n]*, line \d+\n[A-Za-z0-9_]+ \(0x[0-9a-fA-F]+\): ", "",
                    m).strip() for m in messages]
    return "; ".join(m for m in plain if m)


def open(path, iteration=None, cameras=None, images=None, id_property=None):  # noqa: A001
    """A Scene from a 3DGS .ply / .splat or a training log (.h5).

    iteration: for a log, the snapshot nearest to it (default: the last one).
    cameras: cameras.json, a COLMAP dataset folder or a transforms*.json; a log's own cameras
    and, for a scene file, cameras.json beside it or two folders up, by default.
    images: a folder of training images matched to the cameras by name (default: the
    cameras' own, or the images stored in the log).
    id_property: for a .ply, the integer property holding the GaussianIds (Scene.save()
    writes them as "id"); default: the row numbers, as `vis4gs analyze` numbers them."""
    if not os.path.exists(path):
        raise Vis4GSError(f"{path}: no such file")
    return Scene(path, iteration, cameras, images, id_property)


class RemovalEffect:
    """What deleting a selection does to the reconstruction (Scene.measure_removal()).

    views: {column: numpy array}, one row per view, the largest PSNR drop first (views without
    an image last, NaN): view (names), camera (index in the camera table), split ("train" /
    "test"), affected (1 where a removed Gaussian took part), psnr_before, psnr_after,
    ssim_before, ssim_after, l1_before, l1_after. effect["psnr_after"] is views["psnr_after"].
    totals: {"train" / "test": {views, affected, psnr_before, ...}}, means over the views of a
    split that have an image. removed, kept: Gaussians; views_rendered, tiles_rendered,
    tiles_of_tiled_views, views_without_image, seconds_before, seconds_after, baseline_reused
    (the "before" of an earlier measurement of the same scene was reused): the work done."""

    def __init__(self, views, totals, counts):
        self.views = views
        self.totals = totals
        self.__dict__.update(counts)

    def __getitem__(self, column):
        return self.views[column]

    def __repr__(self):
        parts = [f"{split} PSNR {t['psnr_before']:.4f} -> {t['psnr_after']:.4f} dB "
                 f"({t['affected']} of {t['views']} views changed)"
                 for split, t in self.totals.items()]
        return f"<vis4gs.RemovalEffect: {self.removed} Gaussians removed; {'; '.join(parts)}>"

    def to_csv(self, path):
        """Writes before-after.csv as `vis4gs analyze --select=RULE --report` does: the "mean"
        rows of the splits first, then the views, in the same number format."""
        lines = [",".join(_REMOVAL_CSV)]
        figures = _REMOVAL_CSV[3:]
        for split, t in self.totals.items():
            lines.append(",".join(["mean", split, str(int(t["affected"]))] +
                                  [_format_double(t[f]) for f in figures]))
        for r in range(len(self.views["view"])):
            lines.append(",".join([str(self.views["view"][r]), str(self.views["split"][r]),
                                   str(int(self.views["affected"][r]))] +
                                  [_format_double(self.views[f][r]) for f in figures]))
        _write_text(path, "\n".join(lines) + "\n")
        return path


class Comparison:
    """Two states compared Gaussian by Gaussian (Scene.compare()), matched by GaussianId.

    ids, change (flags: 1 moved, 2 opacity, 4 scale, 8 born, 16 died), status ("born", "died",
    "unchanged" or e.g. "moved+opacity"), move, opacity, scale: numpy arrays, one row per id of
    either state, by increasing id (move, opacity, scale NaN for born and died Gaussians).
    born, died, moved, opacity_changed, scale_changed, unchanged: the ids of each kind, sorted
    (a Gaussian can be moved and opacity_changed). counts: {kind: number}, matched included."""

    def __init__(self, columns, counts):
        self.ids = columns["GaussianId"]
        self.change = columns["Change"]
        self.status = columns["Status"]
        self.move = columns["Move"]
        self.opacity = columns["OpacityChange"]
        self.scale = columns["ScaleChange"]
        for kind, flag in _CHANGES.items():
            setattr(self, kind, self.ids[(self.change & flag) != 0])
        self.unchanged = self.ids[self.change == 0]
        self.counts = counts

    def __repr__(self):
        return "<vis4gs.Comparison: " + ", ".join(f"{v} {k}" for k, v in self.counts.items()) + ">"

    def to_csv(self, path):
        """Writes differences.csv as `vis4gs compare` does (id, status, dmove, dopacity,
        dscale)."""
        lines = ["id,status,dmove,dopacity,dscale"]
        for r in range(len(self.ids)):
            lines.append(",".join([str(int(self.ids[r])), str(self.status[r]),
                                   _format_double(self.move[r]), _format_double(self.opacity[r]),
                                   _format_double(self.scale[r])]))
        _write_text(path, "\n".join(lines) + "\n")
        return path


class Scene:
    """The Gaussians of one scene file or one snapshot of a training log, with its cameras."""

    # select_rule(): the rule in canonical form and, over the scene it was applied to, the
    # boolean mask of the Gaussians it selected. scores(): |V|, the training views used.
    rule = None
    mask = None
    views_used = None
    _removal = None

    def __init__(self, path, iteration=None, cameras=None, images=None, id_property=None):
        self.path = path
        self.images = images
        self._cameras_path = cameras
        self._tree = None
        self.warnings = []
        # The file's pipeline is one vtkGaussianSession, as the application and `vis4gs
        # analyze` build it: it tells a log from a scene file by content, reads the snapshot,
        # finds and reads the cameras, and holds the score, genealogy and removal filters.
        self._session = _new_session(path, cameras, images, id_property)
        self._session.SetIteration(-1 if iteration is None else int(iteration))
        self._session.ComputeScoresOff()  # scores() asks for the ones it wants
        self._update(self._session.GaussiansPort)
        self.is_log = bool(self._session.GetIsTrainingLog())
        if self.is_log:
            self._follows_latest = iteration is None  # refresh() moves on to the latest
            log = self._session.GetLogReader()
            self.iterations = [log.GetSnapshotIteration(i)
                               for i in range(log.GetNumberOfSnapshots())]
            self.iteration = self._session.GetLoadedIteration()
        else:
            if iteration is not None:
                raise Vis4GSError(f"{path}: iteration= is for training logs only")
            if self._session.GetGaussiansOutput().GetNumberOfPoints() == 0:
                raise Vis4GSError(f"{path}: no Gaussians could be read")
            self.iterations = []
            self.iteration = None
        self.polydata = vtkPolyData()
        self.polydata.ShallowCopy(self._session.GetGaussiansOutput())
        # Whether self.polydata is the session's Gaussians port (so that its score filter
        # computes the scores); not for a selection or a repaired scene.
        self._from_session = True
        self._cameras = None

    def _update(self, port):
        """Updates a port of the session; its errors (which name the file) as Vis4GSError."""
        messages = []
        tag = self._session.AddObserver("ErrorEvent", _error_collector(messages))
        try:
            ok = self._session.Update(port, None)
        finally:
            self._session.RemoveObserver(tag)
        if not ok or messages:
            raise Vis4GSError(_plain_error(messages) or f"{self.path}: could not be read")

    # ---------------------------------------------------------------- data
    def __len__(self):
        return self.polydata.GetNumberOfPoints()

    def __repr__(self):
        at = f", iteration {self.iteration}" if self.iteration is not None else ""
        return f"<vis4gs.Scene {self.path}{at}: {len(self)} Gaussians>"

    @property
    def arrays(self):
        """Names of the per-Gaussian arrays."""
        pd = self.polydata.GetPointData()
        return [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]

    def __getitem__(self, name):
        """A per-Gaussian array as numpy (a view of the VTK array; copy it to keep it)."""
        if self.polydata.GetPointData().GetAbstractArray(name) is None:
            raise KeyError(f"{name}: no such array (there are {', '.join(self.arrays)})")
        return np.asarray(dsa.WrapDataObject(self.polydata).PointData[name])

    @property
    def ids(self):
        """GaussianId of each Gaussian (stable across a log's snapshots)."""
        return self["GaussianId"]

    @property
    def positions(self):
        return np.asarray(dsa.WrapDataObject(self.polydata).Points)

    @property
    def cameras(self):
        """The camera table (vtkTable, one row per view), or None when there are none."""
        if self._cameras is None:
            self._update(self._session.CamerasPort)
            table = self._session.GetCamerasOutput()
            if table is not None and table.GetNumberOfRows() > 0:
                self._cameras = vtkTable()
                self._cameras.ShallowCopy(table)
        return self._cameras

    @property
    def camera_names(self):
        table = self.cameras
        if table is None:
            return []
        names = table.GetColumnByName("Name")
        return [names.GetValue(r) for r in range(table.GetNumberOfRows())]

    def refresh(self):
        """For a log a trainer is still writing (the Python logger and `vis4gs train` write
        it in SWMR mode): reopens it and returns the snapshot iterations that appeared since
        (the log is never blocked). A Scene opened without iteration= (the latest snapshot)
        moves on to the new latest one; one opened at an iteration stays there. Follow a live
        log with one Scene per process (TrainingLogReader::Refresh)."""
        if not self.is_log:
            raise Vis4GSError(f"{self.path}: not a training log, it has nothing to refresh")
        log = self._session.GetLogReader()
        log.Modified()
        log.UpdateInformation()
        known = set(self.iterations)
        self.iterations = [log.GetSnapshotIteration(i) for i in range(log.GetNumberOfSnapshots())]
        new = [i for i in self.iterations if i not in known]
        if new and getattr(self, "_follows_latest", False):
            self._session.Modified()
            self._update(self._session.GaussiansPort)
            self.iteration = self._session.GetLoadedIteration()
            self.polydata = vtkPolyData()
            self.polydata.ShallowCopy(self._session.GetGaussiansOutput())
            self._tree = None
        self._cameras = None  # the trainer may have logged them since
        return new

    def at(self, iteration):
        """The same log at the snapshot nearest to `iteration`."""
        if not self.is_log:
            raise Vis4GSError(f"{self.path}: not a training log, it has no iterations")
        return Scene(self.path, iteration, self._cameras_path, self.images)

    # ---------------------------------------------------------------- scores
    def scores(self, which=DEFAULT_SCORES, **parameters):
        """Computes only the scores named (SCORES: coverage, blur, needle, shape, render-cost,
        ...; default DEFAULT_SCORES) with
        vtkGaussianArtifactScoreFilter; keywords set its parameters (loss_resolution,
        coverage_resolution, view_stride, footprint 0|1 or "alpha"|"ellipse",
        float_accumulation, occlusion_threshold, lam). The arrays (and NoVisibleView) are added
        to this scene; returns {short name: numpy array} in the order asked. The filter's
        warnings (Gaussians no view sees, scores that could not be computed) are in
        scene.warnings."""
        if isinstance(which, str):
            which = [which]
        unknown = [w for w in which if w not in SCORES]
        if unknown:
            raise Vis4GSError(f"unknown score {', '.join(unknown)} "
                              f"(expected {', '.join(SCORES)})")
        # The scene as opened: the session's own score filter on its Gaussians port. A
        # selection or a repaired scene: a score filter on its Gaussians.
        score_filter = (self._session.GetScoreFilter() if self._from_session
                        else vtkGaussianArtifactScoreFilter())
        if not self._from_session:
            score_filter.SetInputData(self.polydata)
        else:
            # Each call starts from the defaults, as a new filter would.
            defaults = vtkGaussianArtifactScoreFilter()
            for name in _SCORE_PARAMETERS.values():
                getattr(score_filter, "Set" + name)(getattr(defaults, "Get" + name)())
        score_filter.SetScores(",".join(which))
        with_cameras = [w for w in which if w in _NEEDS_CAMERAS]
        if with_cameras:
            if self.cameras is None:
                raise Vis4GSError(f"{self.path}: {', '.join(with_cameras)} need cameras; "
                                  "give cameras=cameras.json or a COLMAP folder")
            if not self._from_session:
                score_filter.SetCamerasData(self.cameras)
        if self.images and not self._from_session:
            score_filter.SetImageDirectory(self.images)
        for key, value in parameters.items():
            if key not in _SCORE_PARAMETERS:
                raise Vis4GSError(f"unknown score parameter {key} "
                                  f"(expected {', '.join(_SCORE_PARAMETERS)})")
            if key == "footprint" and isinstance(value, str):
                if value not in ("alpha", "ellipse"):
                    raise Vis4GSError(f"footprint must be alpha or ellipse, not {value!r}")
                value = {"alpha": 0, "ellipse": 1}[value]
            getattr(score_filter, "Set" + _SCORE_PARAMETERS[key])(value)
        # The filter's warnings come back in scene.warnings (its ScoreWarnings field data);
        # the console need not repeat them.
        shown = vtkObject.GetGlobalWarningDisplay()
        vtkObject.GlobalWarningDisplayOff()
        try:
            if self._from_session:
                self._session.ComputeScoresOn()
                self._update(self._session.GaussiansPort)
            else:
                score_filter.Update()
        finally:
            vtkObject.SetGlobalWarningDisplay(shown)
        out = score_filter.GetOutput()
        notes = out.GetFieldData().GetAbstractArray("ScoreWarnings")
        self.warnings = [] if notes is None else [notes.GetValue(i)
                                                  for i in range(notes.GetNumberOfValues())]
        missing = [SCORES[w] for w in which if out.GetPointData().GetArray(SCORES[w]) is None]
        if missing:
            raise Vis4GSError(f"{self.path}: computing {', '.join(missing)} failed "
                              "(see the messages above)")
        previous = self.polydata.GetPointData()
        self.polydata = vtkPolyData()
        self.polydata.ShallowCopy(out)
        # The same Gaussians: the scores of earlier calls stay beside the new ones.
        for i in range(previous.GetNumberOfArrays()):
            array = previous.GetAbstractArray(i)
            if self.polydata.GetPointData().GetAbstractArray(array.GetName()) is None:
                self.polydata.GetPointData().AddArray(array)
        if with_cameras:
            self.views_used = score_filter.GetNumberOfViewsUsed()
        return collections.OrderedDict((w, self[SCORES[w]]) for w in which)

    # ---------------------------------------------------------------- genealogy
    @property
    def tree(self):
        """The densification tree of a training log (vtkTree, one vertex per Gaussian)."""
        if not self.is_log:
            raise Vis4GSError(f"{self.path}: not a training log, it has no genealogy")
        if self._tree is None:
            self._update(self._session.TreePort)
            tree = self._session.GetOutputDataObject(self._session.TreePort)
            if tree is None or tree.GetNumberOfVertices() == 0:
                raise Vis4GSError(f"{self.path}: no genealogy could be built")
            self._tree = tree.NewInstance()
            self._tree.ShallowCopy(tree)
        return self._tree

    def _query(self, method, ids):
        lineage = vtkGaussianGenealogyLineage()
        lineage.SetTree(self.tree)
        result = vtkIdTypeArray()
        if not getattr(lineage, method)(_id_array(ids), result):
            raise Vis4GSError(f"{self.path}: the genealogy query failed")
        return np.array([result.GetValue(i) for i in range(result.GetNumberOfValues())],
                        dtype=np.int64)

    def ancestors(self, ids):
        """GaussianIds of every ancestor of the given Gaussians."""
        return self._query("GetAncestors", ids)

    def descendants(self, ids):
        """GaussianIds of every descendant of the given Gaussians."""
        return self._query("GetDescendants", ids)

    def lineage(self, gaussian_id, score="coverage", **parameters):
        """Root-cause trace of one Gaussian: a list of Ancestor from it up to its root, each
        with `score` at the snapshot nearest its birth (computed on every snapshot of the log,
        with the keyword parameters of scores(); score=None leaves the values out)."""
        lineage = vtkGaussianGenealogyLineage()
        lineage.SetTree(self.tree)
        if score is not None:
            for iteration in self.iterations:
                snapshot = self if iteration == self.iteration else self.at(iteration)
                values = snapshot.scores([score], **parameters)[score]
                lineage.AddSnapshotValues(iteration, _id_array(snapshot.ids),
                                          numpy_to_vtk(values, deep=1))
        trace = vtkTable()
        if not lineage.TraceToRoot(int(gaussian_id), trace):
            raise Vis4GSError(f"{self.path}: Gaussian {gaussian_id} is not in the genealogy")
        col = {trace.GetColumnName(c): trace.GetColumn(c)
               for c in range(trace.GetNumberOfColumns())}
        steps = []
        for r in range(trace.GetNumberOfRows()):
            death = col["DeathIteration"].GetValue(r)
            snapshot = col["SnapshotIteration"].GetValue(r)
            steps.append(Ancestor(col["GaussianId"].GetValue(r), col["BirthIteration"].GetValue(r),
                                  _BIRTH_KINDS[col["BirthKind"].GetValue(r)],
                                  None if death < 0 else death,
                                  None if snapshot < 0 else snapshot,
                                  float(col["Value"].GetValue(r))))
        return steps

    # ---------------------------------------------------------------- selection
    def select(self, ids=None, mask=None):
        """A new Scene holding the Gaussians whose GaussianId is in `ids`, or where the boolean
        `mask` (one value per Gaussian) is true; every array comes along."""
        if (ids is None) == (mask is None):
            raise Vis4GSError("select() takes ids= or mask=, one of them")
        if mask is not None:
            mask = np.asarray(mask, dtype=bool)
            if mask.shape != (len(self),):
                raise Vis4GSError(f"mask has {mask.shape} values, the scene {len(self)} Gaussians")
            rows = np.flatnonzero(mask)
        else:
            rows = np.flatnonzero(np.isin(self.ids, np.asarray(ids, dtype=np.int64)))
        subset = Scene.__new__(Scene)
        subset.__dict__.update(self.__dict__)
        subset.polydata = _take(self.polydata, rows)
        subset._from_session = False
        return subset

    # ---------------------------------------------------------------- clean-up (issue 20)
    def select_rule(self, rule, combine=None, current=None):
        """A new Scene holding the Gaussians a rule selects (vtkGaussianRuleSelectionFilter;
        the language of `vis4gs analyze --select=RULE`, user guide "Guided clean-up"), e.g.
        "views<=3 and opacity>=0.5", "blur top 5%", "needle>=0.8", "isolated r=0.1".

        The scores the rule reads (coverage, views, blur, needle_score, render_cost, ...) are
        computed with the
        defaults of scores() when this scene lacks them. combine "add", "subtract" or
        "intersect" combines the rule's selection with `current`: a previous selection (a
        Scene), GaussianIds, or a boolean mask over this scene (a brush, a histogram range).
        The result keeps the rule in canonical form (.rule: apply it to another snapshot with
        scene.at(iteration).select_rule(sel.rule), or to another log) and the selection as a
        boolean mask over this scene (.mask)."""
        if combine not in _COMBINE:
            raise Vis4GSError(f"combine must be add, subtract or intersect, not {combine!r}")
        if (combine is None) != (current is None):
            raise Vis4GSError("combine= and current= go together")
        words = set(re.findall(r"[a-z_]+", str(rule).lower()))
        needed = [score for word, score in _RULE_SCORES.items() if word in words]
        missing = [s for s in SCORES if s in needed and
                   self.polydata.GetPointData().GetArray(SCORES[s]) is None]
        if "views" in words and self.views_used is None and "coverage" not in missing:
            missing.append("coverage")
        if missing:
            self.scores(missing)
        rule_filter = vtkGaussianRuleSelectionFilter()
        rule_filter.SetInputData(self.polydata)
        rule_filter.SetRule(str(rule))
        rule_filter.SetNumberOfViews(self.views_used or 0)
        rule_filter.SetCombineMode(_COMBINE[combine])
        if current is not None:
            rule_filter.SetCurrentIds(_id_array(self._ids_of(current, "current")))
        shown = vtkObject.GetGlobalWarningDisplay()
        vtkObject.GlobalWarningDisplayOff()
        try:
            rule_filter.Update()
        finally:
            vtkObject.SetGlobalWarningDisplay(shown)
        if rule_filter.GetLastRuleError():
            raise Vis4GSError(f"{self.path}: {rule_filter.GetLastRuleError()}")
        out = rule_filter.GetOutput()
        if out is None or out.GetPointData().GetArray("RuleSelected") is None:
            raise Vis4GSError(f"{self.path}: the rule {rule!r} could not be applied")
        mask = np.asarray(dsa.WrapDataObject(out).PointData["RuleSelected"]).astype(bool)
        subset = self.select(mask=mask)
        subset.rule = rule_filter.GetCanonicalRule()
        subset.mask = mask
        return subset

    def _ids_of(self, selection, what):
        """GaussianIds of a Scene, a boolean mask over this scene, or ids."""
        if isinstance(selection, Scene):
            return np.asarray(selection.ids, dtype=np.int64)
        values = np.asarray(selection)
        if values.dtype == bool:
            if values.shape != (len(self),):
                raise Vis4GSError(f"{what}: the mask has {values.shape} values, the scene "
                                  f"{len(self)} Gaussians")
            return np.asarray(self.ids, dtype=np.int64)[values]
        return values.astype(np.int64).reshape(-1)

    def measure_removal(self, mask=None, ids=None, train=True, test=True,
                        background=(0.0, 0.0, 0.0), sh_degree=-1, reuse_tiles=True, threads=0):
        """Before and after deleting the Gaussians where `mask` is true (one value per Gaussian)
        or whose GaussianId is in `ids` (e.g. a select_rule() result's .ids): every training
        (train=) and test (test=) view with an image rendered with and without them and
        measured against its image (vtkGaussianRemovalEffectFilter, the measurement of
        `vis4gs analyze --select=RULE --report`, whose before-after.csv RemovalEffect.to_csv()
        writes again). Images: the log's, the cameras', or images= of vis4gs.open().
        Returns a RemovalEffect (numpy columns per view, the worst PSNR change first, and the
        totals per split). The "before" is measured once per scene and settings: measuring
        another selection renders only the views (and tiles) it changes."""
        if (ids is None) == (mask is None):
            raise Vis4GSError("measure_removal() takes ids= or mask=, one of them")
        if self.cameras is None:
            raise Vis4GSError(f"{self.path}: measuring a removal needs cameras")
        if mask is not None:
            mask = np.asarray(mask, dtype=bool)
        removed = self._ids_of(mask if mask is not None else ids, "mask")
        # One filter per scene: it keeps the "before", so that measuring another selection of
        # the same scene renders only the "after" of the views that selection touches. The scene
        # as opened measures through its session (its removal ports, fed by the selection).
        through_session = self._from_session and len(removed) > 0
        if through_session:
            effect_filter = self._session.GetRemovalEffectFilter()
        else:
            if self._removal is None:
                self._removal = vtkGaussianRemovalEffectFilter()
            effect_filter = self._removal
            effect_filter.SetInputData(self.polydata)
            effect_filter.SetCamerasData(self.cameras)
            effect_filter.SetRemovedIds(_id_array(removed))
            if self.images:
                effect_filter.SetImageDirectory(self.images)
        effect_filter.SetTrainViews(bool(train))
        effect_filter.SetTestViews(bool(test))
        effect_filter.SetBackground(*background)
        effect_filter.SetSHDegree(sh_degree)
        effect_filter.SetReuseTiles(bool(reuse_tiles))
        effect_filter.SetThreads(int(threads))
        if through_session:
            self._session.SetSelectedIds(_id_array(removed))
            self._update(self._session.RemovalViewsPort)
            views = self._session.GetOutputDataObject(self._session.RemovalViewsPort)
            self._update(self._session.RemovalTotalsPort)
            totals = self._session.GetOutputDataObject(self._session.RemovalTotalsPort)
        else:
            effect_filter.Update()
            views, totals = effect_filter.GetOutput(0), effect_filter.GetOutput(1)
        if totals is None or totals.GetNumberOfRows() != 2:
            raise Vis4GSError(f"{self.path}: measuring the removal failed "
                              "(see the messages above)")
        columns = _table_columns(views)
        total_columns = _table_columns(totals)
        by_split = collections.OrderedDict()
        for r, split in enumerate(total_columns["split"]):
            by_split[str(split)] = {name: values[r] for name, values in total_columns.items()
                                    if name != "split"}
        counts = {"removed": effect_filter.GetNumberRemoved(),
                  "kept": effect_filter.GetNumberKept(),
                  "views_rendered": effect_filter.GetNumberOfViewsRendered(),
                  "tiles_rendered": effect_filter.GetNumberOfTilesRendered(),
                  "tiles_of_tiled_views": effect_filter.GetNumberOfTilesOfTiledViews(),
                  "views_without_image": effect_filter.GetNumberOfViewsWithoutImage(),
                  "seconds_before": effect_filter.GetSecondsBefore(),
                  "seconds_after": effect_filter.GetSecondsAfter(),
                  "baseline_reused": bool(effect_filter.GetBaselineReused())}
        return RemovalEffect(columns, by_split, counts)

    def compare(self, other, move=0.0, opacity=0.0, scale=0.0):
        """This state (A) against `other` (B: a Scene or a path vis4gs.open() reads), Gaussian by
        Gaussian (vtkGaussianStateComparisonFilter, what `vis4gs compare` writes to
        differences.csv): matched by GaussianId, born (only in B), died (only in A), moved more
        than `move` (scene units), activated opacity changed more than `opacity`, a log-scale
        changed more than `scale`; the thresholds are strict, so 0 reports any change.
        Returns a Comparison (numpy columns and the id set of each kind)."""
        if not isinstance(other, Scene):
            other = open(other)
        if min(move, opacity, scale) < 0:
            raise Vis4GSError("move, opacity and scale must be >= 0")
        compare = vtkGaussianStateComparisonFilter()
        compare.SetInputData(0, self.polydata)
        compare.SetInputData(1, other.polydata)
        compare.SetMoveThreshold(float(move))
        compare.SetOpacityThreshold(float(opacity))
        compare.SetScaleThreshold(float(scale))
        compare.Update()
        table = compare.GetOutput()
        if table is None or table.GetColumnByName("Change") is None:
            raise Vis4GSError(f"{self.path}, {other.path}: the comparison failed "
                              "(see the messages above)")
        counts = collections.OrderedDict([
            ("matched", compare.GetNumberMatched()), ("born", compare.GetNumberBorn()),
            ("died", compare.GetNumberDied()), ("moved", compare.GetNumberMoved()),
            ("opacity_changed", compare.GetNumberOpacityChanged()),
            ("scale_changed", compare.GetNumberScaleChanged()),
            ("unchanged", compare.GetNumberUnchanged())])
        return Comparison(_table_columns(table), counts)
    def repair(self, mask=None, ids=None, iterations=50, free_positions=False, densify=False,
               seed=0, output=None, threads=0, warmup=10, iteration=None):
        """Deletes the Gaussians where the boolean `mask` is true (or whose GaussianId is in
        `ids`) and fine-tunes the rest for `iterations` with the built-in CPU trainer
        (vtkGaussianFineTuneFilter, Core/Selection/FineTune.h: what `vis4gs repair` does), the
        positions fixed unless `free_positions`, densification off unless `densify`, the
        learning rates warmed up over the first `warmup` iterations (`--warmup`; 0: none).
        `iteration` is the source iteration the repaired run continues (`--iteration` of a
        scene file: the trainer's schedules see it, the log records the deletion there);
        default the scene's iteration, 0 for a scene file; a log's snapshot has its own.
        Needs the cameras and their images (a training log has both). With `output`, the
        repaired run's training log is written there (the deletion as prune events at the
        source iteration). Returns a Scene of the repaired Gaussians whose `figures` is
        repair.csv's table as a dict {column: numpy array: of str for view and split, of float
        for psnr/ssim/l1 of source, deleted, repaired}: one "mean" row per split, then one row
        per view."""
        if (ids is None) == (mask is None):
            raise Vis4GSError("repair() takes ids= or mask=, one of them")
        if iteration is None:
            iteration = 0 if self.iteration is None else self.iteration
        elif self.is_log and int(iteration) != self.iteration:
            raise Vis4GSError(f"{self.path}: repair(iteration={iteration}) of the snapshot of "
                              f"iteration {self.iteration}: open that snapshot instead "
                              "(vis4gs.open(path, iteration=N))")
        if int(iteration) < 0 or int(warmup) < 0:
            raise Vis4GSError("repair(): iteration= and warmup= must be >= 0")
        if mask is not None:
            ids = self.select(mask=mask).ids
        cameras = self.cameras
        if cameras is None:
            raise Vis4GSError(f"{self.path}: repair() needs cameras with images")
        fine_tune = vtkGaussianFineTuneFilter()
        fine_tune.SetInputData(0, self.polydata)
        fine_tune.SetCamerasData(cameras)
        fine_tune.SetRemovedIds(_id_array(np.asarray(ids, dtype=np.int64)))
        fine_tune.SetSourceIteration(int(iteration))
        fine_tune.SetIterations(int(iterations))
        fine_tune.SetWarmupIterations(int(warmup))
        fine_tune.SetFreePositions(bool(free_positions))
        fine_tune.SetDensify(bool(densify))
        fine_tune.SetSeed(int(seed))
        fine_tune.SetNumberOfThreads(int(threads))
        if output:
            fine_tune.SetOutputLogFileName(os.fspath(output))
        fine_tune.Update()
        if fine_tune.GetOutputDataObject(1).GetNumberOfColumns() == 0:
            raise Vis4GSError(f"{self.path}: repair failed (see the messages above)")
        repaired = Scene.__new__(Scene)
        repaired.__dict__.update(self.__dict__)
        repaired.polydata = vtkPolyData()
        repaired.polydata.ShallowCopy(fine_tune.GetOutputDataObject(0))
        repaired.iteration = fine_tune.GetLastIteration()
        repaired._tree = None
        # Only `output` holds the repaired run's snapshots; at() opens that log.
        repaired.path = os.fspath(output) if output else self.path
        repaired.is_log = bool(output) and repaired.is_log
        repaired.iterations = [int(iteration), repaired.iteration] if repaired.is_log else []
        repaired._from_session = False
        if repaired.is_log:
            repaired._session = _new_session(repaired.path)
        repaired.figures = dict(_table_columns(fine_tune.GetOutputDataObject(1)))
        return repaired

    # ---------------------------------------------------------------- export
    def save(self, path, ascii=False):
        """Writes a 3DGS PLY (vtkGaussianPLYWriter: the model, the GaussianIds as the integer
        property "id", every other array, scores included, as extra properties)."""
        writer = vtkGaussianPLYWriter()
        writer.SetInputData(self.polydata)
        writer.SetFileName(path)
        writer.WriteIdsOn()
        if ascii:
            writer.SetFileFormatToASCII()
        if not writer.Write():
            raise Vis4GSError(f"{path}: could not be written")
        return path

    def to_csv(self, path, columns=None):
        """Writes GaussianId and the given one-component arrays (default: the scores and
        NoVisibleView, as `vis4gs analyze` writes scores.csv, in the same number format)."""
        pd = self.polydata.GetPointData()
        if columns is None:
            columns = [a for a in SCORES.values() if pd.GetArray(a) is not None]
            if pd.GetArray("NoVisibleView") is not None:
                columns.append("NoVisibleView")
        data = [self[c] for c in columns]
        for name, values in zip(columns, data):
            if values.ndim != 1:
                raise Vis4GSError(f"{name}: only one-component arrays go to a CSV column")
        formats = [_format_int if np.issubdtype(v.dtype, np.integer) else _format_double
                   for v in data]
        temporary = path + ".part"
        with builtins_open(temporary, "w") as f:
            f.write(",".join(["GaussianId"] + list(columns)) + "\n")
            for row, gid in enumerate(self.ids):
                f.write(",".join([str(int(gid))] + [fmt(v[row]) for fmt, v in zip(formats, data)])
                        + "\n")
        os.replace(temporary, path)
        return path

    # ---------------------------------------------------------------- rendering
    def render(self, path=None, camera=0, size=None, background=(0.0, 0.0, 0.0), sh_degree=-1,
               precision="float"):
        """Renders one camera (index or name) with the exact CPU rasteriser
        (vtkGaussianRasterizer, off-screen, no display needed), optionally at size=(W, H).
        Returns the image as an [H, W, 3] float array (top row first); with `path`, writes it
        as an 8-bit PNG the way `vis4gs render` does."""
        if self.cameras is None:
            raise Vis4GSError(f"{self.path}: rendering needs cameras")
        raster = vtkGaussianRasterizer()
        raster.SetInputData(self.polydata)
        raster.SetCamerasData(self.cameras)
        if isinstance(camera, str):
            if camera not in self.camera_names:
                raise Vis4GSError(f"{self.path}: no camera named {camera}")
            raster.SetCameraName(camera)
        else:
            if not 0 <= camera < self.cameras.GetNumberOfRows():
                raise Vis4GSError(f"{self.path}: no camera {camera} "
                                  f"(there are {self.cameras.GetNumberOfRows()})")
            raster.SetCameraIndex(camera)
        if size is not None:
            raster.SetWidth(int(size[0]))
            raster.SetHeight(int(size[1]))
        raster.SetBackground(*background)
        raster.SetSHDegree(sh_degree)
        raster.SetPrecision({"float": raster.FLOAT, "double": raster.DOUBLE}[precision])
        raster.Update()
        image = raster.GetOutput()
        rgb = image.GetPointData().GetArray("RGB") if image else None
        if rgb is None:
            raise Vis4GSError(f"{self.path}: rendering failed (see the messages above)")
        width, height, _ = image.GetDimensions()
        pixels = np.asarray(dsa.vtkDataArrayToVTKArray(rgb)).reshape(height, width, 3)[::-1]
        if path is not None:
            _write_png(path, pixels)
        return pixels


# The builtin, which vis4gs.open shadows in this module.
builtins_open = __builtins__["open"] if isinstance(__builtins__, dict) else __builtins__.open


def _format_double(value):
    """C++'s `ostream << setprecision(9) << double`, as scores.csv is written."""
    if math.isnan(value):
        return "-nan" if math.copysign(1.0, value) < 0 else "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return "%.9g" % value


def _format_int(value):
    return str(int(value))


def _table_columns(table):
    """The columns of a vtkTable as numpy arrays (strings as an object array)."""
    columns = collections.OrderedDict()
    for c in range(table.GetNumberOfColumns()):
        column = table.GetColumn(c)
        if column.IsA("vtkDataArray"):
            values = np.array(vtk_to_numpy(column))
        else:
            values = np.array([column.GetValue(r) for r in range(column.GetNumberOfValues())],
                              dtype=object)
        columns[table.GetColumnName(c)] = values
    return columns


def _write_text(path, text):
    temporary = path + ".part"
    with builtins_open(temporary, "w") as f:
        f.write(text)
    os.replace(temporary, path)


def _id_array(ids):
    array = numpy_to_vtk(np.ascontiguousarray(np.atleast_1d(ids), dtype=np.int64), deep=1,
                         array_type=VTK_ID_TYPE)
    return array


def _take(polydata, rows):
    """The points `rows` of a Gaussian scene with every point array, as a new vtkPolyData."""
    wrapped = dsa.WrapDataObject(polydata)
    out = vtkPolyData()
    out_wrapped = dsa.WrapDataObject(out)
    out_wrapped.Points = np.ascontiguousarray(np.asarray(wrapped.Points)[rows])
    pd = polydata.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        name = pd.GetArrayName(i)
        values = np.ascontiguousarray(np.asarray(wrapped.PointData[name])[rows])
        array = numpy_to_vtk(values, deep=1, array_type=pd.GetArray(i).GetDataType())
        array.SetName(name)
        out.GetPointData().AddArray(array)
    if pd.GetPedigreeIds() is not None:
        out.GetPointData().SetPedigreeIds(out.GetPointData().GetAbstractArray(
            pd.GetPedigreeIds().GetName()))
    out.GetFieldData().ShallowCopy(polydata.GetFieldData())
    return out


def _write_png(path, pixels):
    """8-bit PNG of a float image, each channel clamped to [0, 1] and rounded half away from
    zero (std::lround), non-finite values black: what `vis4gs render` writes."""
    v = np.where(np.isfinite(pixels), np.clip(pixels, 0.0, 1.0), 0.0) * 255.0
    floor = np.floor(v)
    rounded = np.where(v - floor >= 0.5, floor + 1, floor).astype(np.uint8)
    height, width, _ = rounded.shape
    image = dsa.WrapDataObject(vtkImageData())
    image.VTKObject.SetDimensions(width, height, 1)
    image.PointData.append(np.ascontiguousarray(rounded[::-1]).reshape(-1, 3), "RGB")
    image.VTKObject.GetPointData().SetActiveScalars("RGB")
    temporary = path + ".part.png"
    writer = vtkPNGWriter()
    writer.SetFileName(temporary)
    writer.SetInputData(image.VTKObject)
    writer.Write()
    if writer.GetErrorCode():
        raise Vis4GSError(f"{path}: could not be written")
    os.replace(temporary, path)
