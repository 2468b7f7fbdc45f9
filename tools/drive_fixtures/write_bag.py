#!/usr/bin/python3
"""Writes a ROS 1 bag (format 2.0) with Debian's python3-rosbag and python3-sensor-msgs (not
lpir-gseg's code): one sensor_msgs/PointCloud2 per KITTI .bin frame on one topic, chunked, each
chunk compressed with bz2 or lz4 (python3-roslz4) or not at all; rosbag writes the connection
and chunk-info index records when it closes the bag.

Frame i (0-based, in the order given) becomes one message, laid out as pointcloud.mjs lays out
the ROS 2 ones: header seq i, stamp 1600000000 s + i x 100 ms, frame_id --frame-id; height 1,
width = the frame's points, little-endian, is_dense false; fields x y z intensity (float32, from
the .bin), ring (uint16, from FRAME.ring beside FRAME.bin) when that file exists, time (float32,
point k of n at k / n x 0.1 s). point_step 22 with ring, else 20. The message is recorded at its
stamp.

usage: write_bag.py --out FILE.bag --compression bz2|lz4|none [--topic /points]
                    [--frame-id velodyne] [--chunk-threshold BYTES] [--extras]
                    [--recorder-died] FRAME.bin...
A chunk is closed once it holds --chunk-threshold bytes (default rosbag's 768 KiB; 1 gives one
message per chunk). --extras adds the other topics extras.mjs describes, as ROS 1 messages:
/imu/data (sensor_msgs/Imu, 100 Hz, callerid /imu_driver) and /gps/fix (sensor_msgs/NavSatFix,
10 Hz, latched, callerid /gps_driver), each recorded at its stamp.

--recorder-died leaves what a recorder killed while writing its last frame leaves (NAME.bag.active
from `rosbag record`): the first frame in a chunk closed at once, the others in a chunk left open
(rosbag's default threshold), the file flushed and cut halfway through the last frame's record,
the bag never closed: no index, and the open chunk's header still holding the zero sizes rosbag
writes before a chunk's data (the frames only: --extras is not taken with it).
"""
import argparse
import math
import os
import sys

import genpy
import numpy
import rosbag
from sensor_msgs.msg import Imu, NavSatFix, NavSatStatus, PointCloud2, PointField

BASE_SEC = 1600000000
PERIOD_NS = 100000000


def cloud_message(bin_path, index, frame_id):
    with open(bin_path, "rb") as f:
        raw = f.read()
    if len(raw) % 16:
        sys.exit(f"write_bag: {bin_path}: not a KITTI .bin (size {len(raw)})")
    n = len(raw) // 16
    ring_path = bin_path[:-len(".bin")] + ".ring"
    ring = None
    if os.path.exists(ring_path):
        with open(ring_path, "rb") as f:
            ring = f.read()
        if len(ring) != 2 * n:
            sys.exit(f"write_bag: {ring_path}: {len(ring)} bytes, expected {2 * n}")
    fields = [PointField(name, 4 * k, PointField.FLOAT32, 1)
              for k, name in enumerate(("x", "y", "z", "intensity"))]
    step = 16
    if ring is not None:
        fields.append(PointField("ring", step, PointField.UINT16, 1))
        step += 2
    fields.append(PointField("time", step, PointField.FLOAT32, 1))
    step += 4
    layout = [("xyzi", "<f4", 4)] + ([("ring", "<u2")] if ring is not None else [])
    records = numpy.zeros(n, dtype=layout + [("time", "<f4")])  # packed: point_step bytes apart
    records["xyzi"] = numpy.frombuffer(raw, dtype="<f4").reshape(n, 4)
    if ring is not None:
        records["ring"] = numpy.frombuffer(ring, dtype="<u2")
    records["time"] = numpy.arange(n) / n * 0.1
    stamp_ns = BASE_SEC * 1000000000 + index * PERIOD_NS
    msg = PointCloud2()
    msg.header.seq = index
    msg.header.stamp = genpy.Time(stamp_ns // 1000000000, stamp_ns % 1000000000)
    msg.header.frame_id = frame_id
    msg.height, msg.width = 1, n
    msg.fields = fields
    msg.is_bigendian = False
    msg.point_step, msg.row_step = step, n * step
    msg.data = records.tobytes()
    msg.is_dense = False
    return msg


def stamp(ns):
    return genpy.Time(ns // 1000000000, ns % 1000000000)


def extra_messages(frames):
    """(topic, message, connection header) of extras.mjs's topics, in stamp order."""
    diagonal = [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    out = []
    for k in range(10 * frames):
        msg = Imu()
        msg.header.seq = k
        msg.header.stamp = stamp(BASE_SEC * 1000000000 + k * 10000000)
        msg.header.frame_id = "imu_link"
        msg.orientation.z, msg.orientation.w = math.sin(k / 200), math.cos(k / 200)
        msg.orientation_covariance = diagonal
        msg.angular_velocity.z = 0.01 * k
        msg.angular_velocity_covariance = diagonal
        msg.linear_acceleration.x, msg.linear_acceleration.z = 0.1, 9.81
        msg.linear_acceleration_covariance = diagonal
        out.append(("/imu/data", msg, {"callerid": "/imu_driver"}))
    for i in range(frames):
        msg = NavSatFix()
        msg.header.seq = i
        msg.header.stamp = stamp(BASE_SEC * 1000000000 + i * PERIOD_NS + 5000000)
        msg.header.frame_id = "gps"
        msg.status.status, msg.status.service = NavSatStatus.STATUS_FIX, NavSatStatus.SERVICE_GPS
        msg.latitude, msg.longitude, msg.altitude = 48.1 + i * 1e-6, 11.5, 520.25
        msg.position_covariance = diagonal
        msg.position_covariance_type = NavSatFix.COVARIANCE_TYPE_DIAGONAL_KNOWN
        out.append(("/gps/fix", msg, {"callerid": "/gps_driver", "latching": "1"}))
    return sorted(out, key=lambda e: e[1].header.stamp)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--compression", required=True, choices=("bz2", "lz4", "none"))
    parser.add_argument("--topic", default="/points")
    parser.add_argument("--frame-id", default="velodyne")
    parser.add_argument("--chunk-threshold", type=int, default=768 * 1024)
    parser.add_argument("--extras", action="store_true")
    parser.add_argument("--recorder-died", action="store_true")
    parser.add_argument("frames", nargs="+")
    args = parser.parse_args()
    compression = {"bz2": rosbag.Compression.BZ2, "lz4": rosbag.Compression.LZ4,
                   "none": rosbag.Compression.NONE}[args.compression]
    if args.recorder_died:
        die_writing(args, compression)
    with rosbag.Bag(args.out, "w", compression=compression,
                    chunk_threshold=args.chunk_threshold) as bag:
        entries = [(args.topic, cloud_message(path, i, args.frame_id), None)
                   for i, path in enumerate(args.frames)]
        if args.extras:  # by stamp; a frame first at an equal stamp
            entries = sorted(entries + extra_messages(len(args.frames)),
                             key=lambda e: e[1].header.stamp)
        for topic, msg, header in entries:
            if header is None:
                bag.write(topic, msg, t=msg.header.stamp)
            else:  # rosbag takes the whole connection header when one is given
                header = dict(header, topic=topic, type=msg._type, md5sum=msg._md5sum,
                              message_definition=msg._full_text)
                bag.write(topic, msg, t=msg.header.stamp, connection_header=header)
    print(f"write_bag: {len(args.frames)} messages on {args.topic} ({args.compression}) -> "
          f"{args.out}")


def die_writing(args, compression):
    """--recorder-died: writes as rosbag does, then leaves the way a killed process does."""
    if len(args.frames) < 2:
        sys.exit("write_bag: --recorder-died needs two frames or more")
    if args.extras:
        sys.exit("write_bag: --recorder-died writes the frames only, not --extras")
    bag = rosbag.Bag(args.out, "w", compression=compression, chunk_threshold=1)
    for i, path in enumerate(args.frames):
        if i == 1:
            bag.chunk_threshold = 768 * 1024  # the rest stays in one open chunk
        msg = cloud_message(path, i, args.frame_id)
        before = bag._file.tell()  # the file rosbag writes (no public name for it)
        bag.write(args.topic, msg, t=msg.header.stamp)
    bag._file.flush()
    after = bag._file.tell()
    os.truncate(args.out, before + (after - before) // 2)  # killed halfway through the last one
    print(f"write_bag: {len(args.frames)} messages on {args.topic} ({args.compression}), the "
          f"last cut at byte {before + (after - before) // 2} of its record's {before}..{after}, "
          f"never closed -> {args.out}", flush=True)
    os._exit(0)  # as a killed recorder: nothing of rosbag's closing runs


if __name__ == "__main__":
    main()
