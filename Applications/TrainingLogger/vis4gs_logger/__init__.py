# SPDX-License-Identifier: BSD-3-Clause
"""vis4gs_logger: writes the Vis4GS training log (HDF5, format version 2 in SWMR mode, or 1) from external
3DGS trainers: the original graphdeco-inria/gaussian-splatting trainer and gsplat.

Only numpy and h5py are required; torch is used when the trainer passes tensors.

    from vis4gs_logger import TrainingLogger, track_3dgs
    logger = TrainingLogger("run/training_log.h5", scene="garden", sh_degree=3)
    tracker = track_3dgs(gaussians, logger)       # after Scene(...) created the model
    ...
    logger.log_metrics(iteration, loss=loss, l1=Ll1)   # each iteration, before densifying
    logger.step(iteration)                              # end of the iteration: snapshots
    logger.close()

See README.md for the few lines to add to train.py and gsplat's simple_trainer.py.
"""

__version__ = "1.0.0"

from .writer import CLONE, FORMAT, FORMAT_VERSION, PRUNE, SPLIT, TrainingLogWriter, to_numpy  # noqa: E402
from .logger import TrainingLogger  # noqa: E402
from .logfile import open_log, read_snapshot, read_table, snapshot_iterations  # noqa: E402
from .gs3d import GaussianModelTracker, track_3dgs  # noqa: E402
from .gsplat_hooks import GsplatTracker, track_gsplat  # noqa: E402

__all__ = [
    "__version__", "TrainingLogWriter", "TrainingLogger", "GaussianModelTracker", "track_3dgs",
    "GsplatTracker", "track_gsplat", "to_numpy", "FORMAT", "FORMAT_VERSION", "CLONE", "SPLIT",
    "PRUNE", "open_log", "read_snapshot", "read_table", "snapshot_iterations",
]
