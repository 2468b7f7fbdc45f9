"""Labels many scans on a Dask cluster: the fleet version of `lpir-gseg segment`.

    python3 -m lpir_gseg.fleet INPUT... --sensor NAME --out DIR [--recursive] [--topic T]
                               [--drive-chunks K] [--set NAME=VALUE]...
                               [--scheduler tcp://HOST:PORT | --workers N]

INPUTs are files, drives or folders of them, as `segment` lists them (host/drive/inputs.h: a ROS
2 bag folder is one drive; another folder gives its cloud files and drives in name order, with
--recursive its subfolders' too, and each entry passed over is named with the reason). Each file
becomes DIR/<stem>.label (one found in a folder: DIR/<its path below that folder>.label), byte
for byte what `lpir-gseg segment` writes, by the same rule (host/io/output_paths.h: two inputs
of one output are refused, naming both, before anything is written). A recorded drive (.mcap,
.db3, a bag folder, .bag,
.bag.active) is one task: its topic's messages (--topic, else its only PointCloud2 topic) become
DIR/<drive stem>/<sequence, 6 digits>_<header stamp in ns>.label, the files
`lpir-gseg segment DRIVE --out DIR/<drive stem>` writes, with an index.csv beside them. A drive
of more than --drive-chunks K chunks (default 64) whose index says where each chunk lies (an MCAP
with a summary, an indexed ROS 1 bag) is split into tasks of K chunks each (`segment --chunks`),
the same files written and their index.csv rows merged into one, in sequence order. Without
--scheduler a LocalCluster of N worker processes (one thread each) starts on 127.0.0.1. Every
worker process keeps one Segmenter for all its tasks. A file that cannot be read or segmented is
named in the report and every other file is still written; the exit code is then 1 and the last
line counts the failures (2: bad arguments, or the cluster or the segmenters could not be set
up); a damaged drive is a failure naming the damage, its readable messages all written. Inputs
and DIR must be paths every worker sees (docs/fleet.md).
"""
import argparse
import dataclasses
import math
import os
import shutil
import socket
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import lpir_gseg

# The worker side: one segmenter per worker process, made by the first task (or by prepare()).
_lock = threading.Lock()
_segmenter: Optional[lpir_gseg.Segmenter] = None
_segmenter_config: Optional["SegmenterConfig"] = None
_segmenters_made = 0  # how many this process made: 1 for a whole run


@dataclasses.dataclass(frozen=True)
class SegmenterConfig:
    """What a worker needs to make its segmenter. The profile travels as text when it is a file
    on the client, so workers need not see it."""

    sensor: str  # a profile name, or the profile file's name when profile_text is set
    profile_text: Optional[str] = None
    backend: str = "auto"
    device: Optional[str] = None
    max_points: Optional[int] = None
    nuscenes: Optional[bool] = None  # read_cloud's layout switch for .bin files
    params: Tuple[Tuple[str, str], ...] = ()  # Segmenter(params=), as `segment --set` takes them


def _worker_segmenter(config: SegmenterConfig) -> lpir_gseg.Segmenter:
    global _segmenter, _segmenter_config, _segmenters_made
    with _lock:
        if _segmenter is None or _segmenter_config != config:
            sensor = config.sensor
            if config.profile_text is not None:
                folder = tempfile.mkdtemp(prefix="lpir_gseg_fleet_")
                sensor = os.path.join(folder, os.path.basename(config.sensor))
                Path(sensor).write_text(config.profile_text)
            # A worker started with LPIR_GSEG_DEVICE set uses that device (one worker a GPU).
            device = os.environ.get("LPIR_GSEG_DEVICE") or config.device
            # One thread: the cluster's processes share the cores out (docs/fleet.md, Threads or
            # processes); a segmenter of every core in each of them would oversubscribe them.
            _segmenter = lpir_gseg.Segmenter(sensor, backend=config.backend, device=device,
                                             max_points=config.max_points,
                                             params=dict(config.params), threads=1)
            _segmenter_config = config
            _segmenters_made += 1
        return _segmenter


def prepare(config: SegmenterConfig) -> str:
    """Makes this worker's segmenter; returns its backend note (run on every worker first, so a
    bad sensor or backend is one error, not one per file)."""
    return _worker_segmenter(config).backend_note


@dataclasses.dataclass
class FileResult:
    path: str
    error: Optional[str] = None  # the report's line when the file failed
    points: int = 0
    ground: int = 0
    worker: str = ""  # host:pid of the worker process
    segmenters_made: int = 0  # by that process so far
    messages: int = 0  # a drive's: the messages labelled and written
    index_rows: Optional[List[Tuple[int, str]]] = None  # a chunk range's (sequence, index line)
    notes: List[str] = dataclasses.field(default_factory=list)  # a drive's (_Drive.notes)


def _error_text(path: str, error: BaseException) -> str:
    text = str(error) or type(error).__name__
    # The library's file errors name the file already, as the command line prints them.
    return text if path in text else f"{path}: {text}"


def segment_files(jobs: Sequence[Tuple[str, str]], config: SegmenterConfig) -> List[FileResult]:
    """The task: reads, segments and writes each (input, output .label) of `jobs`. On Vulkan the
    files that could be read go through one segment_batch (frames in flight); on the CPU each is
    read, segmented and written in turn (one frame's buffers stay in the cache: a batch would
    cycle through frames_in_flight sets of them and hold every cloud at once). A file's failure
    is its result's error; the others are written."""
    segmenter = _worker_segmenter(config)
    worker = f"{socket.gethostname()}:{os.getpid()}"
    results = [FileResult(path=src, worker=worker) for src, _ in jobs]
    outputs = dict(jobs)

    def read(result: FileResult):
        try:
            return lpir_gseg.read_cloud(result.path, nuscenes=config.nuscenes)
        except Exception as error:  # noqa: BLE001 (every failure is the file's, reported)
            result.error = _error_text(result.path, error)
            return None

    def segment(result: FileResult, points):
        try:
            return segmenter.segment(points)
        except Exception as error:  # noqa: BLE001
            result.error = _error_text(result.path, error)
            return None

    def write(result: FileResult, labels) -> None:
        out = outputs[result.path]
        part = f"{out}.part{os.getpid()}"  # never a half-written .label under its own name
        try:
            os.makedirs(os.path.dirname(out) or ".", exist_ok=True)  # a subfolder (--recursive)
            lpir_gseg.write_labels(part, labels)
            os.replace(part, out)
        except Exception as error:  # noqa: BLE001
            result.error = _error_text(out, error)
            return
        result.points, result.ground = len(labels), int(labels.sum())

    if segmenter.backend == "vulkan" and len(jobs) > 1:
        clouds = [(r, p) for r in results for p in [read(r)] if p is not None]
        try:
            labelled = segmenter.segment_batch([points for _, points in clouds])
        except Exception:  # noqa: BLE001: one of them is bad: each on its own says which
            labelled = [segment(r, points) for r, points in clouds]
        for (result, _), labels in zip(clouds, labelled):
            if labels is not None:
                write(result, labels)
    else:
        for result in results:
            points = read(result)
            labels = None if points is None else segment(result, points)
            if labels is not None:
                write(result, labels)
    for result in results:
        result.segmenters_made = _segmenters_made
    return results


def _write_labels(path: str, labels) -> None:
    """`labels` as the .label file `path`, never half-written under its own name."""
    part = f"{path}.part{os.getpid()}"
    lpir_gseg.write_labels(part, labels)
    os.replace(part, path)


INDEX_HEADER = "sequence,stamp_ns,topic,points,ground_fraction,ms,file\n"


def segment_drive(drive: str, out: str, topic: Optional[str], config: SegmenterConfig,
                  chunks: Optional[Tuple[int, int]] = None,
                  topic_option: str = "topic=") -> List[FileResult]:
    """The task for a recorded drive: every message of its topic read, segmented and written in
    log order as out/<sequence %06>_<header stamp ns>.label, listed in out/index.csv (sequence,
    stamp_ns, topic, points, ground_fraction, ms, file). `chunks` (first, last): only the
    messages of those chunks (numbered from 1), with the sequence numbers a whole run gives them;
    their index lines are then the result's index_rows, not written. Damaged parts and messages
    that do not decode, and failed writes, are the result's error (each named); every other
    message is written. `topic_option` is how an error asks for the topic ("--topic" from the
    command line)."""
    segmenter = _worker_segmenter(config)
    result = FileResult(path=drive, worker=f"{socket.gethostname()}:{os.getpid()}")
    problems: List[str] = []
    try:
        reader = lpir_gseg._core._Drive(drive)
        chosen = lpir_gseg.drive.cloud_topic(reader, topic, topic_option)
        reader.select(chosen, *(chunks or (0, 0)))
        result.notes = reader.notes()
        os.makedirs(out, exist_ok=True)
    except Exception as error:  # noqa: BLE001 (the drive's failure, reported)
        result.error = _error_text(drive, error)
        result.segmenters_made = _segmenters_made
        return [result]
    rows: List[Tuple[int, str]] = []
    index_part = os.path.join(out, f"index.csv.part{os.getpid()}")
    with open(index_part if chunks is None else os.devnull, "w") as index:
        index.write(INDEX_HEADER)
        for kind, *rest in iter(reader.next, ("end",)):
            if kind != "message":
                problems.append(rest[0])
                continue
            sequence, stamp_ns, points, _ = rest
            name = f"{sequence:06}_{stamp_ns}.label"
            try:
                start = time.perf_counter()
                labels = segmenter.segment(points)
                ms = 1000 * (time.perf_counter() - start)
                _write_labels(os.path.join(out, name), labels)
            except Exception as error:  # noqa: BLE001
                problems.append(_error_text(f"{drive}: {chosen} message {sequence}", error))
                continue
            ground = int(labels.sum())
            fraction = ground / len(labels) if len(labels) else 0.0
            line = f"{sequence},{stamp_ns},{chosen},{len(labels)},{fraction:.6f},{ms:.3f},{name}\n"
            index.write(line)
            rows.append((sequence, line))
            result.messages += 1
            result.points += len(labels)
            result.ground += ground
    if chunks is None:
        os.replace(index_part, os.path.join(out, "index.csv"))
    else:
        result.index_rows = rows
    if problems:
        result.error = _error_text(drive, RuntimeError("; ".join(problems)))
    result.segmenters_made = _segmenters_made
    return [result]


def drive_ranges(drive: str, per_task: int) -> List[Optional[Tuple[int, int]]]:
    """The tasks of a drive: [None] (the whole drive, one task) unless it has more than
    `per_task` chunks and an index that says where they lie, then (first, last) ranges of
    `per_task` chunks each, in order. A drive that cannot be opened is one task (which names
    the problem)."""
    try:
        reader = lpir_gseg._core._Drive(drive, read_threads=1)
        count = reader.chunk_count() if reader.chunks_indexed() else 0
    except Exception:  # noqa: BLE001 (the task reports it)
        return [None]
    if count <= per_task:
        return [None]
    return [(first, min(first + per_task - 1, count)) for first in range(1, count + 1, per_task)]


def write_index(folder: str, rows: List[Tuple[int, str]]) -> None:
    """folder/index.csv from the chunk ranges' rows, in sequence order (as one run writes it)."""
    part = os.path.join(folder, f"index.csv.part{os.getpid()}")
    with open(part, "w") as index:
        index.write(INDEX_HEADER)
        for _, line in sorted(rows, key=lambda row: row[0]):
            index.write(line)
    os.replace(part, os.path.join(folder, "index.csv"))


def list_inputs(inputs: Sequence[str], skipped: Optional[List[Tuple[str, str]]] = None, *,
                recursive: bool = False) -> List[Tuple[str, str, bool]]:
    """(path, folder, is_drive) for each input the paths name, as `segment` lists them
    (host/drive/inputs.h): a ROS 2 bag folder is one drive, another folder gives its cloud files
    and drives in path order, with `recursive` its subfolders' too (the entries it passes over
    appended to `skipped` as (path, why)); folder is the folder given that the input was found
    in, "" for one given itself. A missing file or drive is reported when it is read. ValueError
    for a folder without any input."""
    listed, passed = lpir_gseg._core._list_inputs([str(name) for name in inputs], recursive)
    if skipped is not None:
        skipped.extend(passed)
    return listed


class Progress:
    """The command line's progress bar (apps/cli/progress.h) with frames per second: one line
    redrawn with '\\r' on a terminal, a plain line at every tenth on anything else. It counts
    inputs done (a drive is one) and the frames they gave (a drive's messages)."""

    CELLS = 30

    def __init__(self, total: int, enabled: bool, out=None):
        self.total, self.enabled, self.out = total, enabled, out or sys.stderr
        self.tty = self.enabled and self.out.isatty()
        self.done, self.failed, self.start = 0, 0, time.monotonic()
        self.frames = 0
        self.last_draw, self.shown, self.width = 0.0, 0, 0
        self.name = ""  # of the last input done

    def rate(self) -> float:
        elapsed = time.monotonic() - self.start
        return self.frames / elapsed if elapsed > 0 else 0.0

    def step(self, count: int, failed: int, name: str = "", frames: Optional[int] = None) -> None:
        """`count` inputs done, `failed` of them failed, `frames` segmented (default: count)."""
        self.done += count
        self.failed += failed
        self.frames += count if frames is None else frames
        self.name = name
        if not self.enabled:
            return
        now = time.monotonic()
        if self.tty:
            if self.width == 0 or self.done == self.total or now - self.last_draw >= 0.1:
                self._draw(now)
        elif self.done * 10 // self.total > self.shown * 10 // self.total or self.done == self.total:
            self.shown = self.done
            print(f"progress: {self._text(now)}", file=self.out, flush=True)

    def close(self) -> None:
        if self.tty and self.width:
            self._draw(time.monotonic())
            print(file=self.out, flush=True)

    def _text(self, now: float) -> str:
        elapsed = now - self.start
        digits = len(str(self.total))
        text = (f"{self.done:{digits}}/{self.total} {100 * self.done // max(self.total, 1):3}%"
                f"  {self.rate():.1f} frames/s  {_duration(elapsed)}")
        if self.failed:
            text += f"  {self.failed} failed"
        return text + (f"  {self.name}" if self.name else "")

    def _draw(self, now: float) -> None:
        self.last_draw, self.shown = now, self.done
        filled = min(self.CELLS, self.done * self.CELLS // max(self.total, 1))
        line = "[" + "#" * filled + "." * (self.CELLS - filled) + "] " + self._text(now)
        columns = shutil.get_terminal_size((80, 24)).columns
        line = line[: columns - 1]
        self.out.write("\r" + line + " " * max(0, self.width - len(line)))
        self.out.flush()
        self.width = len(line)


def _duration(seconds: float) -> str:
    s = int(seconds + 0.5)
    return f"{s // 3600}:{s // 60 % 60:02}:{s % 60:02}" if s >= 3600 else f"{s // 60}:{s % 60:02}"


@dataclasses.dataclass
class RunStats:
    files: int  # cloud files
    written: int  # inputs written whole (cloud files, and drives without a problem)
    failures: List[Tuple[str, str]]  # (input, the report's line)
    seconds: float  # from the first task submitted to the last result
    workers: int  # worker processes of the cluster when the run started
    segmenters: Dict[str, int]  # worker process (host:pid) -> segmenters it made
    drives: int = 0
    frames: int = 0  # clouds segmented and written: cloud files and drives' messages
    skipped: List[Tuple[str, str]] = dataclasses.field(default_factory=list)  # (entry, why)

    @property
    def frames_per_second(self) -> float:
        return self.frames / self.seconds if self.seconds > 0 else math.inf

    def inputs(self) -> str:
        """"13 files", "30 files and 2 drives", "1 drive"."""
        parts = [f"{n} {word}{'s' if n != 1 else ''}"
                 for n, word in ((self.files, "file"), (self.drives, "drive")) if n]
        return " and ".join(parts) or "0 files"


def run(inputs: Sequence[str], sensor: str, out: str, *, scheduler: Optional[str] = None,
        workers: int = 1, backend: str = "auto", device: Optional[str] = None,
        max_points: Optional[int] = None, nuscenes: Optional[bool] = None,
        chunk: Optional[int] = None, progress: bool = True, log=None,
        topic: Optional[str] = None, drive_chunks: int = 64,
        params: Optional[Dict[str, object]] = None, topic_option: str = "topic=",
        recursive: bool = False) -> RunStats:
    """Labels every input (list_inputs; with `recursive` the folders' subfolders too) on the
    cluster at `scheduler`, or on a LocalCluster of `workers` processes; writes each cloud file's
    labels and each drive's folder where `lpir-gseg segment` would (host/io/output_paths.h:
    out/<the input's path below the folder given>.label, out/<drive stem>/ for a drive;
    segment_drive, its `topic`, None: its only PointCloud2 topic), one task per drive. `chunk`
    cloud files make one task (None: about four tasks a worker, at most 32 files each, so that a
    task's scheduling costs little beside its frames even at some 15 ms a frame on the CPU). An
    indexed drive of more than `drive_chunks` chunks becomes tasks of that many chunks each
    (drive_ranges), whose index rows are merged into one index.csv. `params`: Segmenter(params=)
    of every worker. Every folder entry passed over is printed on `log` (stderr by default) with
    the reason, and so are a drive's notes. Returns the counts and times (frames: the files and
    messages segmented); a failed file or damaged drive is in RunStats.failures (and printed on
    `log`), never an exception. `topic_option` is how errors ask for a drive's topic ("--topic"
    from the command line). Raises ValueError for bad arguments (two inputs of one output
    named), RuntimeError when the segmenters cannot be made."""
    log = log or sys.stderr
    if chunk is not None and chunk < 1:
        raise ValueError("chunk must be at least 1")
    if drive_chunks < 1:
        raise ValueError("drive_chunks must be at least 1")
    if scheduler is None and workers < 1:
        raise ValueError("workers must be at least 1")
    skipped: List[Tuple[str, str]] = []
    listed = list_inputs(inputs, skipped, recursive=recursive)
    files = [path for path, _, _ in listed]
    jobs: List[Tuple[str, str]] = []  # cloud files
    drive_jobs: List[Tuple[str, str]] = []  # drives and their folders
    # the command line's rule (host/io/output_paths.h): ValueError naming both inputs when two
    # would write one output, before anything is written
    targets = lpir_gseg._core._output_paths(listed, out, ".label")
    for (path, _, drive), target in zip(listed, targets):
        (drive_jobs if drive else jobs).append((path, target))
    # the profile and the settings, checked once here (a CPU segmenter of one point is cheap):
    # ValueError naming the nearest sensor or setting, OSError for a profile file that does not
    # parse
    lpir_gseg.Segmenter(sensor, backend="cpu", max_points=1, params=params)
    profile_text = Path(sensor).read_text() if os.path.isfile(sensor) else None
    config = SegmenterConfig(sensor=sensor, profile_text=profile_text, backend=backend,
                             device=device, max_points=max_points, nuscenes=nuscenes,
                             params=tuple((name, str(value))
                                          for name, value in (params or {}).items()))
    for path, why in skipped:
        print(f"lpir_gseg.fleet: skipped {path}: {why}", file=log)
    os.makedirs(out, exist_ok=True)

    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is None:
        import logging

        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               host="127.0.0.1", dashboard_address=None,
                               silence_logs=logging.ERROR)
    try:
        with Client(scheduler or cluster) as client:
            if cluster is not None:
                client.wait_for_workers(workers)
            try:
                notes = client.run(prepare, config)
            except Exception as error:  # noqa: BLE001
                raise RuntimeError(f"the workers could not make a segmenter: {error}") from error
            for note in sorted(set(notes.values())):
                if backend == "auto" and not note.startswith("Vulkan on "):
                    print(f"lpir_gseg.fleet: note: {note}", file=log)
            n_workers = len(notes)
            bar = Progress(len(files), progress and len(files) > 1)
            start = time.monotonic()
            bar.start = start
            size = chunk or max(1, min(32, len(jobs) // (4 * max(n_workers, 1))))
            chunks = [jobs[i:i + size] for i in range(0, len(jobs), size)]
            futures = {client.submit(segment_files, part, config, pure=False): part
                       for part in chunks}
            # A split drive's ranges: how many are left, and their results so far.
            ranges_left: Dict[str, int] = {}
            range_results: Dict[str, List[FileResult]] = {}
            for drive, folder in drive_jobs:
                ranges = drive_ranges(drive, drive_chunks)
                if ranges != [None]:
                    ranges_left[drive], range_results[drive] = len(ranges), []
                for chunks in ranges:
                    futures[client.submit(segment_drive, drive, folder, topic, config, chunks,
                                          topic_option, pure=False)] = [(drive, folder)]
            failures: List[Tuple[str, str]] = []
            segmenters: Dict[str, int] = {}
            written = frames = 0
            drive_paths = {drive for drive, _ in drive_jobs}
            noted = set()
            for future in as_completed(futures):
                part = futures[future]
                try:
                    results = future.result()
                except Exception as error:  # noqa: BLE001: the task itself died (its worker)
                    results = [FileResult(path=src, error=_error_text(src, error))
                               for src, _ in part]
                drive = part[0][0]
                if drive in ranges_left:  # one range of a split drive: the drive once all are in
                    range_results[drive].extend(results)
                    ranges_left[drive] -= 1
                    if ranges_left[drive]:
                        continue
                    results = [_merge_ranges(drive, part[0][1], range_results[drive])]
                failed = done_frames = 0
                for result in results:
                    if result.worker:
                        segmenters[result.worker] = max(segmenters.get(result.worker, 0),
                                                        result.segmenters_made)
                    # a drive's frames are its messages; a file's, itself when written
                    done_frames += (result.messages if result.path in drive_paths
                                    else int(result.error is None))
                    for note in result.notes:
                        if note not in noted:
                            noted.add(note)
                            print(f"lpir_gseg.fleet: note: {note}", file=log, flush=True)
                    if result.error is None:
                        written += 1
                        continue
                    failed += 1
                    failures.append((result.path, result.error))
                    if bar.tty and bar.width:
                        log.write("\n")
                        bar.width = 0
                    print(f"lpir_gseg.fleet: error: {result.error}", file=log, flush=True)
                frames += done_frames
                bar.step(len(results), failed, Path(results[-1].path).stem, done_frames)
            seconds = time.monotonic() - start
            bar.close()
    finally:
        if cluster is not None:
            cluster.close()
    order = {path: i for i, path in enumerate(files)}
    failures.sort(key=lambda f: order.get(f[0], len(order)))
    return RunStats(files=len(jobs), written=written, failures=failures, seconds=seconds,
                    workers=n_workers, segmenters=segmenters, drives=len(drive_jobs),
                    frames=frames, skipped=skipped)


def _merge_ranges(drive: str, folder: str, parts: List[FileResult]) -> FileResult:
    """A split drive's one result from its ranges' (index.csv written from their rows)."""
    merged = FileResult(path=drive)
    rows: List[Tuple[int, str]] = []
    errors = []
    for part in parts:
        rows.extend(part.index_rows or [])
        merged.points += part.points
        merged.ground += part.ground
        merged.messages += part.messages
        merged.notes = merged.notes or part.notes
        merged.worker = merged.worker or part.worker
        merged.segmenters_made = max(merged.segmenters_made, part.segmenters_made)
        if part.error is not None:
            errors.append(part.error)
    try:
        os.makedirs(folder, exist_ok=True)
        write_index(folder, rows)
    except OSError as error:
        errors.append(_error_text(os.path.join(folder, "index.csv"), error))
    merged.error = "; ".join(errors) if errors else None
    return merged


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m lpir_gseg.fleet",
        description="Labels every point of every input cloud on a Dask cluster and writes "
                    "OUT/<stem>.label, as `lpir-gseg segment` does.")
    parser.add_argument("inputs", nargs="+", metavar="INPUT",
                        help="cloud files (%s), recorded drives (.mcap, .db3, ROS 2 bag "
                             "folders, .bag, .bag.active) or folders of them" %
                             ", ".join(lpir_gseg.cloud_formats()))
    parser.add_argument("--sensor", required=True,
                        help="sensor profile name (%s) or a profile file" %
                             ", ".join(lpir_gseg.sensors()))
    parser.add_argument("--out", required=True, metavar="DIR",
                        help="where DIR/<stem>.label go (a drive's: DIR/<drive stem>/)")
    parser.add_argument("--topic", help="the drives' PointCloud2 topic (default: each drive's "
                                        "only one)")
    parser.add_argument("-r", "--recursive", action="store_true",
                        help="folders: also the cloud files and drives of their subfolders, at "
                             "the same paths below DIR (as `segment --recursive`)")
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running dask scheduler, e.g. tcp://10.0.0.5:8786")
    where.add_argument("--workers", type=int, metavar="N",
                       help="worker processes of the local cluster (default: the CPU count)")
    parser.add_argument("--backend", default="auto", choices=["auto", "cpu", "vulkan"],
                        help="as `segment --backend` (default auto: a GPU, else the CPU)")
    parser.add_argument("--device", help="Vulkan device: index or part of its name")
    parser.add_argument("--max-points", type=int, metavar="N",
                        help="largest cloud accepted (default: the sensor's)")
    parser.add_argument("--nuscenes", action="store_true", default=None,
                        help=".bin files hold 5 floats per point (x y z intensity ring)")
    parser.add_argument("--chunk", type=int, metavar="K",
                        help="files per task (default: about four tasks a worker, at most 32 "
                             "files each; a GPU worker keeps a task's frames in flight)")
    parser.add_argument("--drive-chunks", type=int, metavar="K", default=64,
                        help="an indexed drive of more than K chunks is split into tasks of K "
                             "chunks each (default 64)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="one setting of the profile, as `segment --set` (repeatable)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    settings = [setting.partition("=") for setting in args.set]
    if any(not name or not eq for name, eq, _ in settings):
        parser.error("--set expects NAME=VALUE (--set sensor_height=1.9)")
    try:
        stats = run(args.inputs, args.sensor, args.out, scheduler=args.scheduler,
                    workers=args.workers or os.cpu_count() or 1, backend=args.backend,
                    device=args.device, max_points=args.max_points, nuscenes=args.nuscenes,
                    chunk=args.chunk, progress=not args.quiet, topic=args.topic,
                    drive_chunks=args.drive_chunks,
                    params={name: value for name, _, value in settings}, topic_option="--topic",
                    recursive=args.recursive)
    except (ValueError, RuntimeError, OSError) as error:
        print(f"lpir_gseg.fleet: error: {error}", file=sys.stderr)
        return 2
    # "30 files and 2 drives, 44 frames in 1.50 s, 29.3 frames/s on 2 workers"
    summary = (f"{stats.inputs()}, {stats.frames} frame{'s' if stats.frames != 1 else ''} in "
               f"{stats.seconds:.2f} s, {stats.frames_per_second:.1f} frames/s on "
               f"{stats.workers} worker{'s' if stats.workers != 1 else ''}")
    if stats.failures:
        for path, _ in stats.failures:
            print(f"lpir_gseg.fleet: failed: {path}", file=sys.stderr)
        inputs = stats.files + stats.drives
        noun = "files" if not stats.drives else "inputs"
        print(f"lpir_gseg.fleet: {len(stats.failures)} of {inputs} {noun} failed ({summary})",
              file=sys.stderr)
        return 1
    print(f"wrote {stats.frames} label file{'s' if stats.frames != 1 else ''} to {args.out} "
          f"({summary})")
    return 0


if __name__ == "__main__":
    # Run as lpir_gseg.fleet, not __main__: the tasks are pickled by reference to this module's
    # functions, which every worker imports by that name.
    from lpir_gseg import fleet

    sys.exit(fleet.main())
