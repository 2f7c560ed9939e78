# SPDX-License-Identifier: BSD-3-Clause
"""Appending writer of the Vis4GS training log (HDF5, format version 2 in SWMR mode, the
default, or 1; see Documentation/file-formats.md). Depends on numpy and h5py only; torch tensors are
accepted wherever an array is (they are moved to the CPU and converted)."""

import contextlib
import ctypes
import ctypes.util
import errno
import math
import os
import time

import h5py
import numpy as np

__all__ = ["TrainingLogWriter", "to_numpy", "FORMAT", "FORMAT_VERSION", "CLONE", "SPLIT", "PRUNE"]

FORMAT = "vis4gs-training-log"
FORMAT_VERSION = 2
#: the layout of format_version 1 (a group per snapshot), written with swmr=False
FORMAT_VERSION_GROUPS = 1
CLONE, SPLIT, PRUNE = 1, 2, 3
#: /committed columns (format version 2): rows of each table a reader may use
COMMITTED = ("metrics", "metrics/test", "events", "lineage_breaks", "snapshots")
_WHERE_BYTES = 200  # /lineage_breaks/where in version 2: fixed-length UTF-8 (SWMR appends)

_METRIC_COLUMNS = ("loss", "l1", "psnr", "ssim", "lpips", "elapsed_s")
#: file space reserved beyond each write's data for HDF5's metadata (object headers, chunk
#: indices, the superblock at close): the most one write was seen to take is ~30 KiB
#: (test_safety.py, test_every_write_stays_inside_its_reservation)
METADATA_RESERVE = 256 << 10
_BREAK_COLUMNS = (("iteration", "<i4"), ("event_row", "<i8"), ("tracked", "<i8"), ("rows", "<i8"),
                  ("kept", "<i8"), ("first_new_id", "<i8"), ("new_roots", "<i8"))


def to_numpy(array, dtype=None):
    """Converts a numpy array, a torch tensor (any device) or a sequence to numpy."""
    if hasattr(array, "detach") and hasattr(array, "cpu"):
        array = array.detach().cpu().numpy()
    array = np.asarray(array)
    if dtype is not None:
        array = array.astype(dtype, copy=False)
    return array


def _scalar(value):
    """A float from a python number, numpy scalar or one-element tensor; NaN for None."""
    if value is None:
        return math.nan
    if hasattr(value, "item"):
        value = value.item()
    return float(value)


_LIBC = []


def _reserve_blocks(fd, offset, length):
    """Allocates the disk blocks of [offset, offset + length) of the open file fd without
    changing its size (fallocate, FALLOC_FL_KEEP_SIZE): writes there cannot fail for want of
    space. Raises OSError (ENOSPC when the disk has not that much free; EOPNOTSUPP on a file
    system or platform without it)."""
    if not _LIBC:
        libc = ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True)
        call = getattr(libc, "fallocate", None)
        if call is not None:
            call.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int64, ctypes.c_int64]
            call.restype = ctypes.c_int
        _LIBC.append(call)
    call = _LIBC[0]
    if call is None:
        raise OSError(errno.EOPNOTSUPP, os.strerror(errno.EOPNOTSUPP))
    if call(fd, 1, offset, length) != 0:  # 1: FALLOC_FL_KEEP_SIZE
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))


def _append_bytes(before, added, chunk, row_bytes, compressed):
    """At most the file space HDF5 allocates when ``added`` rows of ``row_bytes`` are
    appended after ``before`` rows of a dataset chunked by ``chunk`` rows: uncompressed,
    each chunk not written yet is allocated whole; compressed, each chunk the rows touch is
    written again at up to its raw size (deflate adds < 1 % to incompressible data) and may
    move (freed space is never reused: fs_strategy "none")."""
    if added <= 0:
        return 0
    first, last = before // chunk, (before + added - 1) // chunk
    if compressed:
        filled = before + added - first * chunk
        return int(filled * row_bytes * 1.01) + 64 * (last - first + 1)
    first_new = -(-before // chunk)
    return max(0, last + 1 - first_new) * chunk * row_bytes


def _sh_rows(sh, n):
    """sh as [N,K,3]; K is taken from the shape so that an empty model (N = 0, all
    Gaussians pruned) keeps its coefficient count instead of failing to infer it."""
    if sh.ndim == 2:
        sh = sh[:, None, :]
    if sh.ndim != 3 or sh.shape[0] != n or sh.shape[2] != 3:
        raise ValueError(f"sh has shape {sh.shape}; expected [{n},K,3] or [{n},3]")
    return sh


class TrainingLogWriter:
    """Writes one training log while a trainer runs.

    Metrics rows and events are buffered and written at each flush(); a snapshot is
    written and flushed when it is handed over, so a training run killed mid-way leaves
    a log that is complete up to its last snapshot. Between flushes HDF5 is kept from
    writing any metadata (metadata-cache evictions off) and freed file space is never
    reused (file-space strategy "none"), so the file on disk stays the valid log of the
    last flush.

    Parameters: path of the .h5 file (created, truncated); scene name; the trainer's
    maximum SH degree; planned number of iterations; producer string; deflate level of
    the metrics, events, cameras and images (shuffle + gzip; 0 = none); snapshot_deflate:
    deflate level of the per-Gaussian snapshot datasets (default 0, uncompressed, as the
    C++ writer: deflate saves only ~15 % on float32 parameters but makes every property
    history query inflate whole chunks); rows per chunk of the snapshot datasets;
    flush_every_s: also flush buffered rows when this many seconds have passed since the
    last flush (None: only at snapshots and close); snapshot_sh_degree: SH degree kept in the
    snapshots (None: all the trainer has; 0: the DC term only); snapshot_sh_float16: store
    the SH coefficients (colours) as float16 (IEEE half: 3 significant digits, |x| < 65504).

    swmr (default True): format version 2 in HDF5's single-writer/multiple-reader mode, so
    that readers (``vis4gs view LOG --follow``, ``vis4gs analyze``) can read the log while
    the trainer writes it, without blocking it. A SWMR writer cannot create datasets, so the
    tables are created at the start and the snapshots are rows of concatenated datasets
    (created at the first snapshot, from its shapes) indexed by /snapshots/iteration, start
    and count; each flush writes the rows, flushes, then counts them in /committed and
    flushes again, so a reader (or a SIGKILL) never sees a half-written row counted.
    SWMR mode starts at the first metrics row (the training loop) or start_swmr(): the
    setup before it (first snapshot, cameras, images) creates its datasets directly (a kill
    then leaves a file that needs ``h5clear -s``; readers cannot open it yet). Structure
    added after it briefly takes the file out of SWMR mode (a reader kept open across that
    moment must reopen). swmr=False writes format version 1 (a group per snapshot).

    write_to_temporary: write the whole file as ``<path>.tmp`` and rename it onto path at
    close() (as TrainingLogger does by default), so that a failure (a full disk, a read-only
    folder) leaves an earlier log at path as it was; abandon() then removes the temporary.
    With swmr, readers follow the live ``<path>.tmp`` (`vis4gs view path --follow` finds it).

    A full disk: HDF5 1.10 cannot recover from a write that fails for want of space (its
    metadata cache stays half flushed, "slist already enabled?", and closing the file then,
    or at the interpreter's exit, crashes the process). So HDF5 never meets a full disk here:
    before each write (a flush, a snapshot, the cameras, an image) the writer reserves the
    file space the write can take at most (its data's chunks plus METADATA_RESERVE) beyond
    the end of the file (fallocate, FALLOC_FL_KEEP_SIZE: the blocks are the file's, its size
    unchanged). A reservation that fails raises OSError (ENOSPC) naming the file before
    anything is written, and the file, still whole, can be closed and removed (abandon()).
    Where fallocate is not supported the free space of the disk is checked instead (another
    process may then take it before HDF5 writes).
    """

    def __init__(self, path, scene="", sh_degree=3, iterations=30000, producer=None,
                 deflate=1, chunk_rows=4096, flush_every_s=300.0, snapshot_deflate=0,
                 start_iteration=0, snapshot_sh_degree=None, snapshot_sh_float16=False,
                 swmr=True, write_to_temporary=False):
        self.path = os.fspath(path)
        self.deflate = int(deflate)
        self.snapshot_deflate = int(snapshot_deflate)
        if snapshot_sh_degree is not None and not 0 <= int(snapshot_sh_degree) <= 4:
            raise ValueError(f"{self.path}: snapshot_sh_degree must be 0..4 or None, "
                             f"not {snapshot_sh_degree}")
        self.snapshot_sh_degree = None if snapshot_sh_degree is None else int(snapshot_sh_degree)
        self.snapshot_sh_float16 = bool(snapshot_sh_float16)
        #: bytes of the snapshot datasets written so far (as stored, after compression)
        self.snapshot_bytes = 0
        self.chunk_rows = int(chunk_rows)
        self.flush_every_s = flush_every_s
        self.swmr = bool(swmr)
        #: the file being written: path, or "<path>.tmp" until close() renames it
        self.write_path = self.path + ".tmp" if write_to_temporary else self.path
        self._file = None
        #: the end of the space reserved by the last write (see the class)
        self.reserved_end = 0
        self._unflushed = 0  # bytes written since the last flush, perhaps not yet allocated
        self._healthy = True  # False once an HDF5 call failed: its state is not to be trusted
        try:
            # SWMR needs the newest file format (superblock 3); version 1 files stay readable
            # by HDF5 1.8 ("earliest").
            self._file = h5py.File(self.write_path, "w", fs_strategy="none",
                                   libver="latest" if self.swmr else "earliest")
            self._reserve(0)
            self._start(scene, sh_degree, iterations, producer, start_iteration)
        except BaseException:
            self.abandon()
            raise

    def _start(self, scene, sh_degree, iterations, producer, start_iteration):
        from . import __version__

        self._keep_metadata()
        f = self._file
        f.attrs["format"] = FORMAT
        f.attrs["format_version"] = np.int64(FORMAT_VERSION if self.swmr else FORMAT_VERSION_GROUPS)
        f.attrs["producer"] = producer or "vis4gs_logger " + __version__
        f.attrs["scene"] = scene
        f.attrs["sh_degree"] = np.int64(sh_degree)
        f.attrs["iterations"] = np.int64(iterations)
        if start_iteration:
            # A run resumed from a checkpoint: ids restart at 0 for the checkpoint's rows.
            f.attrs["start_iteration"] = np.int64(start_iteration)
        self._metrics = {False: self._create_metrics("metrics"),
                         True: self._create_metrics("metrics/test") if self.swmr else None}
        self._pending_metrics = {False: [], True: []}
        events = f.create_group("events")
        # Each flush deflates the partly filled last chunk of each column again: with the
        # frequent flushes of SWMR mode, 4096-row event chunks (32 KiB) make a flush about 10
        # times cheaper than 65536 (Documentation/performance-history.md).
        event_chunk = 4096 if self.swmr else 65536
        for name, dtype in (("iteration", "<i4"), ("kind", "u1"), ("parent", "<i8"), ("child", "<i8")):
            self._create_table(events, name, dtype, event_chunk)
        self._pending_events = []
        self._event_rows = 0  # rows of /events, written and buffered
        self._pending_breaks = []
        f.create_group("snapshots")
        if self.swmr:
            self._create_breaks()
            f.create_dataset("committed", data=np.zeros(len(COMMITTED), np.int64))
            self._snapshot_count = 0
        self._last_snapshot = -1
        self._last_flush = time.monotonic()
        self._cameras_written = False
        self.flush()

    # -- helpers ----------------------------------------------------------------------
    def _reserve(self, nbytes):
        """Reserves the space a write of at most ``nbytes`` of data takes (with what is
        written but not flushed yet, and METADATA_RESERVE) beyond the end of the file, or
        raises OSError naming the file (see the class)."""
        fd = self._file.id.get_vfd_handle()
        size = os.fstat(fd).st_size
        # HDF5 may have allocated space it has not written yet (end of allocation > size)
        end = max(size, int(self._file.id.get_filesize()))
        want = end - size + int(nbytes) + self._unflushed + METADATA_RESERVE
        try:
            _reserve_blocks(fd, size, want)
        except OSError as error:
            if error.errno not in (errno.EOPNOTSUPP, errno.ENOSYS):
                raise OSError(error.errno, os.strerror(error.errno), self.write_path) from None
            disk = os.statvfs(self.write_path)
            if disk.f_bavail * disk.f_frsize < want:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), self.write_path) from None
        self.reserved_end = size + want

    @contextlib.contextmanager
    def _writing(self, nbytes):
        """Runs the HDF5 calls of one write of at most ``nbytes`` of data inside its
        reservation; an error in them marks the file as not to be trusted (abandon())."""
        self._reserve(nbytes)
        try:
            yield
        except BaseException:
            self._healthy = False
            raise

    def _keep_metadata(self):
        """Between flushes HDF5 writes no metadata: the file stays the log of the last
        flush (for format version 1; SWMR orders its metadata writes itself)."""
        cfg = self._file.id.get_mdc_config()
        cfg.evictions_enabled = False
        cfg.incr_mode = 0  # H5C_incr__off
        cfg.flash_incr_mode = 0  # H5C_flash_incr__off
        cfg.decr_mode = 0  # H5C_decr__off
        self._file.id.set_mdc_config(cfg)

    def start_swmr(self):
        """Enters SWMR mode (swmr=True; once, at the first metrics row if not before): from
        then on readers can open the file while it grows and a kill leaves it readable.
        Before, in the setup (the first snapshot, cameras, images), groups and datasets are
        created directly; after, adding them reopens the file (_structure)."""
        self._check_open()
        if self.swmr and not self._file.swmr_mode:
            self.flush()
            self._file.swmr_mode = True

    @contextlib.contextmanager
    def _structure(self):
        """Lets the body create groups and datasets: a SWMR writer cannot, so the file is
        committed, closed and reopened out of SWMR mode for the moment (readers that try to
        open it then fail and try again), then back in SWMR mode."""
        if not self.swmr or not self._file.swmr_mode:
            yield self._file
            return
        self.flush()
        self._file.close()
        self._file = h5py.File(self.write_path, "r+", libver="latest")
        self._keep_metadata()
        self._metrics = {test: self._file["metrics/test" if test else "metrics"]
                         for test in (False, True)}
        try:
            yield self._file
        finally:
            self._file.flush()
            self._file.swmr_mode = True

    def _create_breaks(self):
        g = self._file.create_group("lineage_breaks")
        for name, dtype in _BREAK_COLUMNS:
            self._create_table(g, name, dtype, 256)
        # Fixed-length strings in version 2: a SWMR writer appends them in place.
        where = h5py.string_dtype("utf-8", _WHERE_BYTES) if self.swmr else h5py.string_dtype("utf-8")
        g.create_dataset("where", shape=(0,), maxshape=(None,), chunks=(256,), dtype=where)
        return g

    def _create_packed(self, arrays, ids_dtype=np.int64):
        """The concatenated snapshot datasets of format version 2, shaped by the first
        snapshot's arrays (later snapshots are fitted to them: see _fit)."""
        g = self._file["snapshots"]
        for name, dtype in (("iteration", "<i4"), ("start", "<i8"), ("count", "<i8"),
                            ("sh_degree", "<i4")):
            g.create_dataset(name, shape=(0,), maxshape=(None,), dtype=dtype, chunks=(1024,))
        c = self.chunk_rows
        level = self.snapshot_deflate
        g.create_dataset("id", shape=(0,), maxshape=(None,), dtype=ids_dtype, chunks=(c,),
                         **self._compression(level))
        for key, value in arrays.items():
            chunks = (c, 1, 3) if key == "sh" else (c,) + value.shape[1:]
            g.create_dataset(key, shape=(0,) + value.shape[1:], maxshape=(None,) + value.shape[1:],
                             dtype=value.dtype, chunks=chunks, **self._compression(level))

    @staticmethod
    def _fit(dataset, value):
        """A later snapshot's array for the packed dataset: SH coefficients cut to what it
        holds (fewer are written alone, the index keeps the degree), a statistic the
        snapshot lacks as NaN (empty here, filled by the caller)."""
        if value is None:
            return np.full((0,) + dataset.shape[1:], np.nan, dataset.dtype)
        if value.ndim == 3:
            value = value[:, : dataset.shape[1]]
        return value.astype(dataset.dtype, copy=False)

    def _snapshot_bytes(self, ids, arrays):
        """At most the file space the snapshot's data takes (see _append_bytes)."""
        n = len(ids)
        compressed = self.snapshot_deflate > 0
        g = self._file["snapshots"]
        if self.swmr:
            before = g["id"].shape[0] if "id" in g else 0
            chunk = self.chunk_rows
        else:
            before, chunk = 0, max(1, min(self.chunk_rows, n))
        row_bytes = [ids.itemsize] + [v.itemsize * int(np.prod(v.shape[1:], dtype=np.int64))
                                      for v in arrays.values()]
        if self.swmr:  # the index (iteration, start, count, sh_degree) and a statistic the
            # snapshot lacks (written as NaN)
            row_bytes += [4 * 3] * 2
        return sum(_append_bytes(before, n, chunk, b, compressed) for b in row_bytes) + 4 * 1024 * 3

    def _write_packed(self, iteration, ids, arrays):
        g = self._file["snapshots"]
        if "id" not in g:
            with self._structure() as f:
                self._create_packed(arrays)
                g = f["snapshots"]
        n = len(ids)
        start = g["id"].shape[0]
        written = 0
        index = ("iteration", "start", "count", "sh_degree")
        degree = 0
        stored_before = self._packed_storage(g)
        for key in ("id",) + tuple(k for k in g if k != "id" and k not in index):
            d = g[key]
            if key == "id":
                value = ids
            else:
                value = self._fit(d, arrays.get(key))
                if len(value) == 0 and n > 0:
                    value = np.full((n,) + d.shape[1:], np.nan, d.dtype)
            d.resize((start + n,) + d.shape[1:])
            if key == "sh":
                degree = int(round(math.sqrt(value.shape[1]))) - 1
                if n > 0:  # the other coefficients' chunks stay unwritten (no disk)
                    d[start:start + n, : value.shape[1]] = value
                written += value.nbytes
                continue
            if n > 0:
                d[start:start + n] = value
            written += n * value.dtype.itemsize * int(np.prod(d.shape[1:], dtype=np.int64))
        for key, value in (("iteration", iteration), ("start", start), ("count", n),
                           ("sh_degree", degree)):
            self._append(g[key], np.array([value], g[key].dtype))
        self._snapshot_count += 1
        if self.snapshot_deflate > 0:
            # Compressed: what the chunks take (chunks shared with the next snapshot are
            # counted when written); uncompressed: the raw bytes, which the whole run's
            # chunks add up to.
            return self._packed_storage(g) - stored_before
        return written

    @staticmethod
    def _packed_storage(g):
        return sum(d.id.get_storage_size() for d in g.values())

    def _compression(self, level=None):
        level = self.deflate if level is None else level
        if level > 0:
            return dict(compression="gzip", compression_opts=level, shuffle=True)
        return {}

    def _create_table(self, group, name, dtype, chunk):
        return group.create_dataset(name, shape=(0,), maxshape=(None,), dtype=dtype,
                                    chunks=(chunk,), **self._compression())

    def _create_metrics(self, path):
        g = self._file.create_group(path)
        self._create_table(g, "iteration", "<i4", 1024)
        self._create_table(g, "num_gaussians", "<i8", 1024)
        for name in _METRIC_COLUMNS:
            self._create_table(g, name, "<f8", 1024)
        return g

    def _dataset(self, group, name, data, chunk, level=None):
        data = np.ascontiguousarray(data)
        chunks = tuple(max(1, min(c, s)) if s > 0 else max(1, c) for c, s in zip(chunk, data.shape))
        return group.create_dataset(name, data=data, maxshape=(None,) + data.shape[1:],
                                    chunks=chunks, **self._compression(level))

    @staticmethod
    def _append(dataset, values):
        n = len(values)
        if n == 0:
            return
        start = dataset.shape[0]
        dataset.resize((start + n,))
        dataset[start:start + n] = values

    def _check_open(self):
        if self._file is None:
            raise RuntimeError(f"{self.path}: the training log is already closed")

    # -- public API -------------------------------------------------------------------
    @property
    def last_snapshot_iteration(self):
        return self._last_snapshot

    @property
    def last_flush(self):
        """time.monotonic() of the last flush."""
        return self._last_flush

    def write_cameras(self, names, widths, heights, fx, fy, cx, cy, world_to_camera,
                      splits=None, images=None, source=None, image_dir=None):
        """Writes /cameras (once). world_to_camera is [V,4,4]; splits 0 train / 1 test;
        images are paths relative to the log, or "/images/<name>" for embedded ones.
        source (the scene's cameras.json or COLMAP folder) and image_dir (its image folder)
        are stored as attributes of /cameras, as given (for the record)."""
        self._check_open()
        if self._cameras_written:
            raise RuntimeError(f"{self.path}: /cameras is already written")
        v = len(names)
        w2c = to_numpy(world_to_camera, np.float64).reshape(v, 4, 4)
        text = sum(len(str(x).encode("utf-8")) + 32 for x in list(names) + list(images or []))
        with self._writing(v * 256 + text), self._structure():
            self._write_cameras(v, names, widths, heights, fx, fy, cx, cy, w2c, splits, images,
                                source, image_dir)
        self._cameras_written = True

    def _write_cameras(self, v, names, widths, heights, fx, fy, cx, cy, w2c, splits, images,
                       source, image_dir):
        g = self._file.create_group("cameras")
        str_type = h5py.string_dtype("utf-8")
        g.create_dataset("name", data=np.array([str(n) for n in names], dtype=object), dtype=str_type)
        g.create_dataset("split", data=to_numpy(splits if splits is not None else np.zeros(v), np.uint8))
        g.create_dataset("width", data=to_numpy(widths, np.int32))
        g.create_dataset("height", data=to_numpy(heights, np.int32))
        for key, values in (("fx", fx), ("fy", fy), ("cx", cx), ("cy", cy)):
            g.create_dataset(key, data=to_numpy(values, np.float64))
        g.create_dataset("world_to_camera", data=w2c)
        images = images if images is not None else [""] * v
        g.create_dataset("image", data=np.array([str(p) for p in images], dtype=object), dtype=str_type)
        for key, value in (("source", source), ("image_dir", image_dir)):
            if value:
                g.attrs[key] = os.fspath(value)

    def write_image(self, name, image):
        """Embeds an image as /images/<name>: [H,W,3] uint8, or float in [0,1] as
        [H,W,3] or [3,H,W] (torch layout)."""
        self._check_open()
        a = to_numpy(image)
        if a.ndim == 3 and a.shape[0] == 3 and a.shape[2] != 3:
            a = np.transpose(a, (1, 2, 0))
        if a.dtype != np.uint8:
            a = np.clip(np.rint(a.astype(np.float64) * 255.0), 0, 255).astype(np.uint8)
        if a.ndim != 3 or a.shape[2] != 3 or "/" in name or not name:
            raise ValueError(f"{self.path}: image {name!r} must be [H,W,3]")
        rows = max(1, min(256, a.shape[0]))
        with self._writing(_append_bytes(0, a.shape[0], rows, a.shape[1] * 3, self.deflate > 0)), \
                self._structure() as f:
            self._dataset(f.require_group("images"), name, a, (256, a.shape[1], 3))

    def append_metrics(self, iteration, num_gaussians=-1, loss=None, l1=None, psnr=None,
                       ssim=None, lpips=None, elapsed_s=None, test=False):
        """Buffers one metrics row (test=True: /metrics/test). Unmeasured values: None."""
        self._check_open()
        if self.swmr and not self._file.swmr_mode:
            self.start_swmr()  # the training loop has started: readers may follow from here
        row = (int(iteration), int(num_gaussians), _scalar(loss), _scalar(l1), _scalar(psnr),
               _scalar(ssim), _scalar(lpips), _scalar(elapsed_s))
        self._pending_metrics[bool(test)].append(row)
        self._maybe_timed_flush()

    def append_events(self, iteration, kind, parents, children=None):
        """Buffers events of one kind: parents[i] -> children[i] (prunes: children None)."""
        self._check_open()
        parents = to_numpy(parents, np.int64).reshape(-1)
        if len(parents) == 0:
            return
        if children is None:
            children = np.full(len(parents), -1, np.int64)
        children = to_numpy(children, np.int64).reshape(-1)
        if len(children) != len(parents):
            raise ValueError("parents and children differ in length")
        n = len(parents)
        self._event_rows += n
        self._pending_events.append((np.full(n, int(iteration), np.int32),
                                     np.full(n, int(kind), np.uint8), parents, children))

    def append_lineage_break(self, iteration, tracked, rows, kept, first_new_id, new_roots,
                             where=""):
        """Buffers one row of /lineage_breaks: at ``iteration``, after the events written so
        far (``event_row`` = their count), the logger tracked ``tracked`` ids for ``rows``
        rows; the first ``kept`` rows kept their ids (the others' ids ended there) and
        ``new_roots`` rows got the new root ids first_new_id, first_new_id + 1, ...
        ``where`` says which operation found it."""
        self._check_open()
        self._pending_breaks.append((int(iteration), self._event_rows, int(tracked), int(rows),
                                     int(kept), int(first_new_id), int(new_roots), str(where)))

    def write_snapshot(self, iteration, ids, position, log_scale, rotation, opacity_logit, sh,
                       grad_accum=None, denom=None, flush=True):
        """Writes /snapshots/<iteration>. Rows are sorted by id if they are not already;
        sh is [N,K,3] (or [N,3] for DC only); ids must be unique."""
        self._check_open()
        iteration = int(iteration)
        if iteration <= self._last_snapshot:
            raise ValueError(f"{self.path}: snapshot {iteration} is not after {self._last_snapshot}")
        ids = to_numpy(ids, np.int64).reshape(-1)
        n = len(ids)
        if self.snapshot_sh_degree is not None:  # the coefficients of the degrees kept
            sh = sh[:, : (self.snapshot_sh_degree + 1) ** 2] if sh.ndim == 3 else sh
        arrays = {
            "position": to_numpy(position, np.float32).reshape(n, 3),
            "log_scale": to_numpy(log_scale, np.float32).reshape(n, 3),
            "rotation": to_numpy(rotation, np.float32).reshape(n, 4),
            "opacity_logit": to_numpy(opacity_logit, np.float32).reshape(n),
            "sh": _sh_rows(to_numpy(sh, np.float32), n),
        }
        if grad_accum is not None:
            arrays["grad_accum"] = to_numpy(grad_accum, np.float32).reshape(n)
        if denom is not None:
            arrays["denom"] = to_numpy(denom, np.float32).reshape(n)
        k = arrays["sh"].shape[1]
        if int(round(math.sqrt(k))) ** 2 != k:
            raise ValueError(f"{self.path}: sh has {k} coefficients, not a square number")
        if n > 1 and not np.all(ids[1:] > ids[:-1]):
            order = np.argsort(ids, kind="stable")
            ids = ids[order]
            if np.any(ids[1:] == ids[:-1]):
                raise ValueError(f"{self.path}: snapshot {iteration} has duplicate ids")
            arrays = {key: value[order] for key, value in arrays.items()}
        if self.snapshot_sh_float16:  # readers convert to float32 (HDF5 does)
            arrays["sh"] = arrays["sh"].astype(np.float16)
        reserve = self._snapshot_bytes(ids, arrays)
        with self._writing(reserve):
            self._unflushed += reserve  # its chunks may be allocated at the flush
            if self.swmr:
                self.snapshot_bytes += self._write_packed(iteration, ids, arrays)
            else:
                self.snapshot_bytes += self._write_groups(iteration, ids, arrays)
        self._last_snapshot = iteration
        if flush:
            self.flush()

    def _write_groups(self, iteration, ids, arrays):
        g = self._file.create_group(f"snapshots/{iteration:06d}")
        g.attrs["iteration"] = np.int64(iteration)
        c = self.chunk_rows
        level = self.snapshot_deflate
        written = [self._dataset(g, "id", ids, (c,), level)]
        for key, value in arrays.items():
            chunk = (c, 1, 3) if key == "sh" else (c,) + value.shape[1:]
            written.append(self._dataset(g, key, value, chunk, level))
        return sum(d.id.get_storage_size() for d in written)

    def flush(self):
        """Writes the buffered rows and flushes: the file is then a valid log."""
        self._check_open()
        with self._writing(self._rows_bytes()):
            self._flush_rows()
        self._unflushed = 0
        self._last_flush = time.monotonic()

    def _rows_bytes(self):
        """At most the file space the buffered rows take (see _append_bytes)."""
        compressed = self.deflate > 0
        total = 0
        for test, rows in self._pending_metrics.items():
            if rows:
                g = self._metrics[test]
                before = g["iteration"].shape[0] if g is not None else 0
                total += sum(_append_bytes(before, len(rows), 1024, b, compressed)
                             for b in [4] + [8] * (1 + len(_METRIC_COLUMNS)))
        pending = sum(len(e[0]) for e in self._pending_events)
        chunk = 4096 if self.swmr else 65536
        total += sum(_append_bytes(self._event_rows - pending, pending, chunk, b, compressed)
                     for b in (4, 1, 8, 8))
        if self._pending_breaks:
            g = self._file.get("lineage_breaks")
            before = g["iteration"].shape[0] if g is not None else 0
            total += sum(_append_bytes(before, len(self._pending_breaks), 256, b, compressed)
                         for b in [8] * len(_BREAK_COLUMNS) + [_WHERE_BYTES])
        return total

    def _flush_rows(self):
        for test in (False, True):
            rows = self._pending_metrics[test]
            if not rows:
                continue
            if self._metrics[test] is None:
                self._metrics[test] = self._create_metrics("metrics/test")
            g = self._metrics[test]
            cols = list(zip(*rows))
            self._append(g["iteration"], np.asarray(cols[0], np.int32))
            self._append(g["num_gaussians"], np.asarray(cols[1], np.int64))
            for j, name in enumerate(_METRIC_COLUMNS):
                self._append(g[name], np.asarray(cols[2 + j], np.float64))
            self._pending_metrics[test] = []
        if self._pending_events:
            events = self._file["events"]
            for j, name in enumerate(("iteration", "kind", "parent", "child")):
                self._append(events[name], np.concatenate([e[j] for e in self._pending_events]))
            self._pending_events = []
        if self._pending_breaks:
            self._flush_breaks()
        self._file.flush()
        if self.swmr:
            # Counted only once flushed: a reader (or a kill) never sees a row counted before
            # its bytes are in the file.
            f = self._file
            f["committed"][:] = np.array(
                [f["metrics/iteration"].shape[0], f["metrics/test/iteration"].shape[0],
                 f["events/iteration"].shape[0], f["lineage_breaks/iteration"].shape[0],
                 self._snapshot_count], np.int64)
            f.flush()

    def _flush_breaks(self):
        g = self._file.get("lineage_breaks")
        if g is None:
            g = self._create_breaks()
        cols = list(zip(*self._pending_breaks))
        for j, (name, dtype) in enumerate(_BREAK_COLUMNS):
            self._append(g[name], np.asarray(cols[j], dtype))
        if self.swmr:
            where = [w.encode("utf-8")[:_WHERE_BYTES].decode("utf-8", "ignore").encode("utf-8")
                     for w in cols[-1]]
            self._append(g["where"], np.array(where, dtype=g["where"].dtype))
        else:
            self._append(g["where"], np.array(cols[-1], dtype=object))
        self._pending_breaks = []

    def _maybe_timed_flush(self):
        if self.flush_every_s is not None and time.monotonic() - self._last_flush > self.flush_every_s:
            self.flush()

    def close(self):
        """Flushes and closes the file; with write_to_temporary renames it onto path. On an
        error (a full disk) the file is abandoned (see abandon()) and the error raised."""
        if self._file is None:
            return
        try:
            self.flush()
            try:
                self._file.close()  # inside the flush's reservation
            except BaseException:
                self._healthy = False
                raise
            self._file = None
            # The reserved blocks past the end go back to the disk (a truncation to the same
            # size frees them: tmpfs, ext4).
            os.truncate(self.write_path, os.path.getsize(self.write_path))
            if self.write_path != self.path:
                os.replace(self.write_path, self.path)
        except BaseException:
            self.abandon()
            raise

    def abandon(self):
        """Stops writing after a failure: closes the file, ignoring further errors (HDF5
        reports each on stderr once more), and removes the temporary of write_to_temporary,
        so that no partial log is left and an earlier log at path stays as it was. Without
        write_to_temporary the file at path is left as the failure left it."""
        f, self._file = self._file, None
        if f is not None and not self._healthy:
            # HDF5 flushes a file when it closes it, and after a failed write that flush
            # fails again and can crash the process (seen with h5py 3.7 / HDF5 1.10: "Slist
            # already enabled?", then a segmentation fault at exit). The reservations keep
            # a full disk from getting here (see the class); for any other failed write the
            # descriptor is pointed at /dev/null first, so that the closing writes go nowhere.
            # A file whose writes all succeeded (a reservation failed) closes as it is.
            try:
                fd = f.id.get_vfd_handle()
                null = os.open(os.devnull, os.O_RDWR)
                os.dup2(null, fd)
                os.close(null)
            except Exception:  # noqa: BLE001 - a driver without a descriptor: close as it is
                pass
        if f is not None:
            try:
                f.close()
            except Exception:  # noqa: BLE001 - the file is given up, its state does not matter
                pass
        if self.write_path != self.path:
            try:
                os.remove(self.write_path)
            except OSError:
                pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
