"""A stand-in gsplat training loop logged by vis4gs_logger, for CheckFullDisk.py (issue 32).

  FullDiskTraining.py LOG LOGGER_TESTS WRITER [MOMENT]

WRITER: swmr (the default writer, format version 2) or v1 (swmr=False). MOMENT: when the
disk fills (the file system of LOG, to 0 bytes free, with CheckFullDisk.fill), while the
training runs: "step:K" (before step K's records), "snapshot:K" (inside the snapshot of
iteration K, after its first array is written) or "close" (before close(), which writes the
final snapshot, 52, of a model grown 8 times so that it needs new space). Without MOMENT the disk is left as it is.

The training must end normally whatever happens to its log: exit status 0 and its last
line printed.
"""
import os
import sys
import warnings

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CheckFullDisk import fill  # noqa: E402

LAST_STEP = 52  # not a multiple of the snapshot interval: close() writes the final model


def mount_point(path):
    path = os.path.abspath(path)
    while not os.path.ismount(path):
        path = os.path.dirname(path)
    return path


def fill_inside_snapshot(log, iteration):
    """Fills the disk in the middle of the snapshot of @p iteration: at its second array
    written (format version 2 appends rows to datasets, version 1 creates them)."""
    from vis4gs_logger.writer import TrainingLogWriter

    state = {"armed": False, "writes": 0}

    def counted(method):
        def wrapper(*args, **kwargs):
            result = method(*args, **kwargs)
            if state["armed"]:
                state["writes"] += 1
                if state["writes"] == 2:
                    state["armed"] = False
                    fill(mount_point(log), 0)
            return result
        return wrapper

    h5py.Dataset.__setitem__ = counted(h5py.Dataset.__setitem__)
    h5py.Group.create_dataset = counted(h5py.Group.create_dataset)
    write_snapshot = TrainingLogWriter.write_snapshot

    def armed(self, it, *args, **kwargs):
        state["armed"] = int(it) == iteration
        return write_snapshot(self, it, *args, **kwargs)

    TrainingLogWriter.write_snapshot = armed


def main():
    log, tests, writer = sys.argv[1:4]
    moment = sys.argv[4] if len(sys.argv) > 4 else ""
    sys.path[:0] = [os.path.dirname(tests), tests]
    import torch
    import mock_gsplat_ops
    from test_gsplat import make_splats
    from vis4gs_logger import TrainingLogger, track_gsplat

    warnings.simplefilter("always")
    os.makedirs(os.path.dirname(log), exist_ok=True)
    if moment.startswith("snapshot:"):
        fill_inside_snapshot(log, int(moment.split(":")[1]))
    params, optimizers, state = make_splats(500, 4)
    logger = TrainingLogger(log, snapshot_interval=5, iterations=LAST_STEP,
                            swmr=writer == "swmr")
    track_gsplat(params, logger, modules=[mock_gsplat_ops])
    for step in range(1, LAST_STEP + 1):
        if moment == f"step:{step}":
            fill(mount_point(log), 0)
        logger.log_metrics(step, loss=1.0 / step)
        mask = torch.zeros(len(params["means"]), dtype=torch.bool)
        mask[step % len(mask)] = True
        mock_gsplat_ops.duplicate(params, optimizers, state, mask)
        logger.step(step)
    if moment == "close":
        # The final snapshot must need new space: space the log reserved before and did not
        # use yet is the file's, and a snapshot that fits there is written (as it should be).
        for _ in range(3):
            mock_gsplat_ops.duplicate(params, optimizers, state,
                                      torch.ones(len(params["means"]), dtype=torch.bool))
        fill(mount_point(log), 0)
    logger.close()
    print("the training ended at step", step, "with", len(params["means"]), "Gaussians")


if __name__ == "__main__":
    main()
