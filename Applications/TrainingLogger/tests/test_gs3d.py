# SPDX-License-Identifier: BSD-3-Clause
"""The original-3DGS hooks against a mock GaussianModel that performs the trainer's tensor
operations. Every Gaussian carries its id in an SH coefficient (copied by clone and split
exactly like every other parameter), which is an independent witness of the genealogy."""

import math

import numpy as np
import pytest
import torch

from logcheck import check_format, dump, read_events, replay_genealogy, require_dump
from vis4gs_logger.logfile import open_log, read_snapshot, snapshot_iterations
from mock_3dgs import GaussianModel
from vis4gs_logger import CLONE, PRUNE, SPLIT, TrainingLogger, track_3dgs

CARRIER = (13, 1)  # _features_rest[:, 13, 1] holds the id (exact in float32 below 2**24)


def set_carrier(g, rows, ids):
    with torch.no_grad():
        g._features_rest[rows, CARRIER[0], CARRIER[1]] = ids.float()


def carrier(g):
    return g._features_rest[:, CARRIER[0], CARRIER[1]].detach().long()


def densify_round(g, rng, extent):
    """Fills the statistics so that clone, split and prune all happen, then densifies."""
    n = g.get_xyz.shape[0]
    with torch.no_grad():
        g.xyz_gradient_accum[:] = torch.from_numpy(rng.uniform(0, 0.0005, (n, 1)).astype(np.float32))
        g.denom[:] = torch.from_numpy(rng.integers(0, 3, (n, 1)).astype(np.float32))
        scales = rng.choice([-6.0, -3.5], size=(n, 1)) + rng.normal(0, 0.1, (n, 3))
        g._scaling[:] = torch.from_numpy(scales.astype(np.float32))
        opac = rng.uniform(0.0, 0.2, (n, 1))
        g._opacity[:] = torch.logit(torch.from_numpy(opac.astype(np.float32)))
    g.densify_and_prune(0.0002, 0.005, extent, 20)


def test_ids_follow_rows_and_events_replay(tmp_path):
    torch.manual_seed(0)
    rng = np.random.default_rng(1)
    g = GaussianModel(3)
    g.create_random(400, seed=2)
    path = str(tmp_path / "gs3d.h5")
    logger = TrainingLogger(path, scene="mock", sh_degree=3, iterations=1000, snapshot_interval=100)
    set_carrier(g, torch.arange(400), torch.arange(400))
    tracker = track_3dgs(g, logger)
    extent = 1.0
    total_events = 0
    for iteration in range(1, 601):
        logger.log_metrics(iteration, loss=0.5 / iteration, l1=0.3 / iteration)
        if iteration % 100 == 50:
            n_before = g.get_xyz.shape[0]
            before = tracker.ids.clone()
            e_before = len(logger.writer._pending_events)
            densify_round(g, rng, extent)
            new_events = logger.writer._pending_events[e_before:]
            # Witness 1: every row's carrier is its own id, or its parent's id for new rows.
            ids = tracker.ids
            assert len(ids) == g.get_xyz.shape[0]
            c = carrier(g)
            born = {}
            for it, kind, parents, children in new_events:
                assert np.all(it == iteration)
                for p, ch in zip(parents, children):
                    if kind[0] in (CLONE, SPLIT):
                        born[int(ch)] = (int(kind[0]), int(p))
            for row in range(len(ids)):
                i = int(ids[row])
                if i in born:
                    assert int(c[row]) == born[i][1], "child does not carry its parent's parameters"
                else:
                    assert int(c[row]) == i
            kinds = np.concatenate([e[1] for e in new_events]) if new_events else np.array([])
            assert (kinds == CLONE).any() and (kinds == SPLIT).any() and (kinds == PRUNE).any()
            # Splits: two children per parent, parent gone, and never recorded as pruned.
            split_parents = [p for ch, (k, p) in born.items() if k == SPLIT]
            counts = {p: split_parents.count(p) for p in split_parents}
            assert set(counts.values()) == {2}
            pruned = set(np.concatenate([e[2] for e in new_events if e[1][0] == PRUNE]).tolist())
            assert not (set(counts) & pruned)
            assert not (set(counts) & set(ids.tolist()))
            # Survivors kept their relative order: ids stay strictly increasing.
            assert torch.all(ids[1:] > ids[:-1])
            # Gone = pruned or split; children may be pruned in the same call (reference §4.5).
            assert (set(before.tolist()) | set(born)) - set(ids.tolist()) == pruned | set(counts)
            set_carrier(g, torch.arange(len(ids)), ids)
            total_events += int(sum(len(e[0]) for e in new_events))
            assert g.get_xyz.shape[0] != n_before or total_events > 0
        logger.step(iteration)
    logger.log_metrics(600, l1=0.1, psnr=30.0, ssim=0.9, lpips=0.2, test=True)
    final_ids = tracker.ids.clone()
    logger.close()

    check_format(path)
    events = read_events(path)
    assert len(events[0]) == total_events > 0
    alive, next_id = replay_genealogy(events, 400)
    assert alive == set(final_ids.tolist())
    assert next_id == tracker.next_id
    with open_log(path) as f:
        assert snapshot_iterations(f) == list(range(0, 601, 100))
        last = read_snapshot(f, 600)
        assert np.array_equal(last["id"][:], final_ids.numpy())
        assert last["sh"].shape[1] == 16
        np.testing.assert_array_equal(last["position"][:], g._xyz.detach().numpy())
        assert f["metrics/iteration"].shape == (600,)
        assert math.isnan(f["metrics/psnr"][0]) and f["metrics/loss"][0] == 0.5
        assert f["metrics/num_gaussians"][0] == 400
        assert f["metrics/test/lpips"][0] == pytest.approx(0.2)
        assert "grad_accum" in last and "denom" in last

    # The same log through the C++ reader (validates events and snapshot ids).
    info = dump(path, "--history=0,1,2,401,450")
    if require_dump():
        assert info["snapshots"] == list(range(0, 601, 100))
        assert info["events"] == total_events
        assert info["repairs"] == []
        assert info["counts"][-1] == len(final_ids)
        hist = info["history"]
        assert all(h["id"] in (0, 1, 2, 401, 450) for h in hist)


def test_mismatched_trainer_warns_instead_of_lying(tmp_path):
    g = GaussianModel(1)
    g.create_random(50, seed=3)
    logger = TrainingLogger(str(tmp_path / "w.h5"), snapshot_interval=0)
    tracker = track_3dgs(g, logger, snapshot_initial=False)
    g.percent_dense = 0.01
    grads = torch.full((50, 1), 1.0)
    with torch.no_grad():
        g._scaling[:] = -6.0
    # A modified trainer that clones half of what the reference rule selects.
    original = tracker._originals["densification_postfix"]

    def halve(new_xyz, *rest):
        return original(new_xyz[:25], *[r[:25] for r in rest])

    tracker._originals["densification_postfix"] = halve
    with pytest.warns(RuntimeWarning, match="recording them without parents"):
        g.densify_and_clone(grads, 0.0002, 1.0)
    assert len(tracker.ids) == 75 and tracker.next_id == 75
    assert len(logger.writer._pending_events) == 0
    logger.close()


def test_3dgs_cameras(tmp_path):
    class Cam:
        def __init__(self, name, w, h, fovx, fovy, w2c):
            self.image_name, self.image_width, self.image_height = name, w, h
            self.FoVx, self.FoVy = fovx, fovy
            self.world_view_transform = torch.tensor(w2c, dtype=torch.float32).T  # column-major
            self.original_image = torch.rand(3, h, w)

    w2c = np.eye(4)
    w2c[:3, 3] = [0.5, -1.0, 2.0]
    w2c[0, 1], w2c[1, 0] = 0.25, -0.25
    cams = [Cam("a", 40, 30, 2 * math.atan(20 / 35.0), 2 * math.atan(15 / 36.0), w2c),
            Cam("b", 40, 30, 1.0, 0.8, np.eye(4))]
    logger = TrainingLogger(str(tmp_path / "c.h5"), snapshot_interval=0)
    logger.log_3dgs_cameras(cams[:1], cams[1:], embed_images=True)
    logger.close()
    with open_log(str(tmp_path / "c.h5")) as f:
        c = f["cameras"]
        assert [n.decode() if isinstance(n, bytes) else n for n in c["name"][:]] == ["a", "b"]
        assert list(c["split"][:]) == [0, 1]
        assert c["fx"][0] == pytest.approx(35.0, rel=1e-12)
        assert c["fy"][0] == pytest.approx(36.0, rel=1e-12)
        assert c["cx"][0] == 20.0 and c["cy"][0] == 15.0
        np.testing.assert_allclose(c["world_to_camera"][0], w2c, atol=1e-7)
        assert f["images/a"].shape == (30, 40, 3) and f["images/a"].dtype == np.uint8
        img = c["image"][0]
        assert (img.decode() if isinstance(img, bytes) else img) == "/images/a"
