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


def _listed(topics: List[DriveTopic]) -> str:
    """"/a (sensor_msgs/msg/PointCloud2, 3 messages), /b (...)", or "none"."""
    return ", ".join(f"{t.name} ({t.type}, {t.messages} messages)" for t in topics) or "none"


def _damaged(drive: "_core._Drive") -> str:
    """" in what could be read: the drive is damaged (<first damaged part>...)" when the listing
    met damage, else ""."""
    damage = drive.listing_damage()
    if not damage:
        return ""
    more = f", and {len(damage) - 1} more damaged parts" if len(damage) > 1 else ""
    return f" in what could be read: the drive is damaged ({damage[0]}{more})"


def cloud_topic(drive: "_core._Drive", topic: Optional[str], option: str = "topic=") -> str:
    """`topic` when given (ValueError naming the drive and listing its topics unless it is a
    PointCloud2 topic of it; OSError naming the damage when the drive is damaged and the topic
    is not in what could be read), else the drive's only PointCloud2 topic (ValueError listing
    them when there are several, saying to choose one with `option`; OSError when there is none:
    the file, not the call, is at fault, its damage named), as `lpir-gseg segment` chooses."""
    if topic is not None:
        try:
            topics = [DriveTopic(*t) for t in drive.topics()]
        except OSError:
            return topic  # counting failed (a damaged drive): select() and the reading report it
        known = {t.name: t.type for t in topics}
        if topic not in known and _damaged(drive):
            raise OSError(f"{drive.path}: no topic {topic}{_damaged(drive)}")
        if topic not in known:
            raise ValueError(f"{drive.path}: no topic {topic}; the drive has {_listed(topics)}")
        if not known[topic].endswith("PointCloud2"):
            raise ValueError(f"{drive.path}: topic {topic} holds {known[topic]}, not "
                             "sensor_msgs PointCloud2")
        return topic
    topics = [DriveTopic(*t) for t in drive.topics()]
    clouds = [t for t in topics if t.type.endswith("PointCloud2")]
    if not clouds:
        raise OSError(f"{drive.path}: no sensor_msgs PointCloud2 topic{_damaged(drive)}; the "
                      f"drive has {_listed(topics)}")
    if len(clouds) > 1:
        raise ValueError(f"{drive.path}: {len(clouds)} PointCloud2 topics ({_listed(clouds)}): "
                         f"choose one with {option}")
    return clouds[0].name


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
        FileNotFoundError: at the call, for a missing file.
        ValueError: at the call, for a topic the drive does not have or one that is not
            PointCloud2, or topic=None on a drive with several PointCloud2 topics (the message
            lists them); also for a bad on_damage.
        OSError: at the call, for an unknown extension, a file that is no drive, a drive without
            any PointCloud2 topic, a damaged drive in whose readable part the topic is not; at
            the end, for damage (on_damage "raise"). Each message names the file.
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
