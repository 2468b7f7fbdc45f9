"""Recorded drives (ROS 2 .mcap and .db3 and bag folders, ROS 1 .bag and .bag.active) read
without ROS: the library's readers (host/drive/) behind read_drive and drive_topics."""
import warnings
from typing import Iterator, List, NamedTuple, Optional, Tuple

from . import _core

is_drive_file = _core.is_drive_file


class DriveTopic(NamedTuple):
    name: str  # "/points"
    type: str  # as the drive names it: "sensor_msgs/msg/PointCloud2", "sensor_msgs/PointCloud2"
    encoding: str  # "cdr", "ros1", ...
    messages: int


def drive_topics(path, *, on_damage: str = "raise") -> List[DriveTopic]:
    """drive_topics(path, *, on_damage="raise")

    Every topic of a recorded drive with its message type, encoding and message count, as
    `lpir-gseg topics` lists them.

    Args:
        path: a drive, as read_drive takes it.
        on_damage: "raise": damage met while listing (a truncated drive read without an index)
            raises OSError naming each damaged part; "warn": a RuntimeWarning per damaged part
            instead, and the topics returned count the messages that could be read.

    Raises:
        OSError: a missing file, an unknown extension, or a file that is no drive of its kind;
            damage (on_damage "raise"). The message names the file.
    """
    if on_damage not in ("raise", "warn"):
        raise ValueError(f"on_damage must be 'raise' or 'warn', not {on_damage!r}")
    drive = _core._Drive(path)
    topics = [DriveTopic(*t) for t in drive.topics()]
    damage = drive.listing_damage()
    if damage and on_damage == "raise":
        raise OSError(f"{drive.path}: {len(damage)} damaged part"
                      f"{'s' if len(damage) != 1 else ''} met while listing its topics: "
                      + "; ".join(damage))
    for problem in damage:
        warnings.warn(problem, RuntimeWarning, stacklevel=2)
    return topics


def _damaged(drive: "_core._Drive") -> str:
    """", damaged (<first damaged part>)" when the listing met damage, else ""."""
    damage = drive.listing_damage()
    if not damage:
        return ""
    more = f", and {len(damage) - 1} more damaged parts" if len(damage) > 1 else ""
    return f" in what could be read: the drive is damaged ({damage[0]}{more})"


def cloud_topic(drive: "_core._Drive", topic: Optional[str], option: str = "topic=") -> str:
    """`topic` when given (OSError naming the drive unless it is a PointCloud2 topic of it, or
    names the damage that may have taken it), else the drive's only PointCloud2 topic (OSError
    listing them when there are several, saying to choose one with `option`; naming the damage
    when there are none on a damaged drive), as `lpir-gseg segment` chooses."""
    if topic is not None:
        try:
            topics = [DriveTopic(*t) for t in drive.topics()]
        except OSError:
            return topic  # counting failed (a damaged drive): select() and the reading report it
        known = {t.name: t.type for t in topics}
        if topic in known and not known[topic].endswith("PointCloud2"):
            raise OSError(f"{drive.path}: topic {topic} holds {known[topic]}, not "
                          "sensor_msgs PointCloud2")
        if topic not in known and _damaged(drive):
            raise OSError(f"{drive.path}: no topic {topic}{_damaged(drive)}")
        return topic  # an absent topic: select() raises, listing those there are
    topics = [DriveTopic(*t) for t in drive.topics()]
    clouds = [t.name for t in topics if t.type.endswith("PointCloud2")]
    if not clouds:
        names = ", ".join(t.name for t in topics) or "none"
        raise OSError(f"{drive.path}: no sensor_msgs PointCloud2 topic"
                      f"{_damaged(drive) or ''}; the drive has {names}")
    if len(clouds) > 1:
        raise OSError(f"{drive.path}: {len(clouds)} PointCloud2 topics ({', '.join(clouds)}): "
                      f"choose one with {option}")
    return clouds[0]


def read_drive(path, topic: Optional[str] = None, *, ring: bool = False,
               on_damage: str = "raise") -> Iterator[Tuple]:
    """read_drive(path, topic=None, *, ring=False, on_damage="raise")

    The sensor_msgs/PointCloud2 messages of one topic of a recorded drive, in the order logged.

    Args:
        path: a .mcap (ROS 2, any of zstd, lz4 or no compression), .db3 (ROS 2 SQLite), a ROS 2
            bag folder (metadata.yaml and its split .mcap or .db3 files, read in order as one
            drive), a .bag (ROS 1, bz2, lz4 or none) or .bag.active (what a ROS 1 recorder that
            died leaves: read by a scan, its unfinished last chunk up to the end of the file).
        topic: the topic; None takes the drive's only PointCloud2 topic.
        ring: also yield each message's ring field.
        on_damage: "raise": after every message that could be read has been yielded, raise
            OSError naming the file and each damaged part (a truncated chunk, a CRC mismatch, an
            unknown compression, a message whose fields do not hold x, y, z); "warn": a
            RuntimeWarning per damaged part instead, and the iteration simply ends.

    Yields:
        (stamp_ns, points): the message header's stamp in nanoseconds (int) and its points as
        an (N, 4) float32 array (x, y, z, intensity) that owns the decoded cloud and carries the
        message's ring field to Segmenter.segment, as read_cloud's arrays do, so that segmenting
        it gives the labels `lpir-gseg segment DRIVE` writes. With ring=True,
        (stamp_ns, points, ring), ring (N,) int32 or None when the message has no ring field.

    Raises:
        OSError: at the call, for a missing file, an unknown extension, a file that is no drive,
            an absent topic or one that is not PointCloud2; at the end, for damage (on_damage
            "raise"). Each message names the file.
    """
    if on_damage not in ("raise", "warn"):
        raise ValueError(f"on_damage must be 'raise' or 'warn', not {on_damage!r}")
    drive = _core._Drive(path)
    drive.select(cloud_topic(drive, topic))
    return _messages(drive, ring, on_damage)


def _messages(drive: "_core._Drive", with_ring: bool, on_damage: str) -> Iterator[Tuple]:
    problems = []
    for kind, *rest in iter(drive.next, ("end",)):
        if kind == "message":
            _, stamp_ns, points, ring = rest
            yield (stamp_ns, points, ring) if with_ring else (stamp_ns, points)
        else:
            problems.append(rest[0])
            if on_damage == "warn":
                warnings.warn(rest[0], RuntimeWarning, stacklevel=2)
    if problems and on_damage == "raise":
        raise OSError(f"{drive.path}: {len(problems)} damaged part"
                      f"{'s' if len(problems) != 1 else ''}: " + "; ".join(problems))
