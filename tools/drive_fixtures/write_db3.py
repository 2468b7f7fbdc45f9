#!/usr/bin/python3
"""Writes a ROS 2 SQLite bag (.db3) with Python's sqlite3, in rosbag2's schema (version 3, as
Humble's recorder writes it): tables schema, metadata, topics(id, name, type,
serialization_format, offered_qos_profiles) and messages(id, topic_id, timestamp, data), with
the timestamp index. One topic (type sensor_msgs/msg/PointCloud2, format cdr); its messages are
the CDR files write_cdr.mjs made (serialized by @foxglove/rosmsg2-serialization), in name order,
each stored with the stamp its name carries (<seq>_<stamp ns>.cdr) as the timestamp.

With --extras-dir EXTRAS (write_cdr.mjs's): the bag is written in Jazzy's schema instead
(version 9: topics add type_description_hash, and a message_definitions table holds each type's
ros2msg definition, EXTRAS/pointcloud2.msg the frames'), with the topics of EXTRAS/<n>/ after
the frames' (topic ids 2, 3, ...), every message of them stored as its file name says.

usage: write_db3.py --cdr-dir DIR --out FILE.db3 [--topic /points] [--extras-dir EXTRAS]
"""
import argparse
import os
import sqlite3
import sys

SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,
                      metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                      timestamp INTEGER NOT NULL, data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""
JAZZY_SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,
                      metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL,
                    type_description_hash TEXT NOT NULL);
CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL,
                                 encoding TEXT NOT NULL, encoded_message_definition TEXT NOT NULL,
                                 type_description_hash TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                      timestamp INTEGER NOT NULL, data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""
# What Humble's recorder stores for a sensor-data subscription (best effort, keep last 5).
QOS = ("- history: 3\n  depth: 0\n  reliability: 2\n  durability: 2\n"
       "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  liveliness: 1\n  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  avoid_ros_namespace_conventions: false\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cdr-dir", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--topic", default="/points")
    parser.add_argument("--extras-dir")
    args = parser.parse_args()
    names = sorted(n for n in os.listdir(args.cdr_dir) if n.endswith(".cdr"))
    if not names:
        sys.exit(f"write_db3: no .cdr files in {args.cdr_dir}")
    if os.path.exists(args.out):
        os.remove(args.out)
    db = sqlite3.connect(args.out)
    # (topic, type, definition file, folder of <k>_<stamp>.cdr files)
    topics = [(args.topic, "sensor_msgs/msg/PointCloud2",
               os.path.join(args.extras_dir, "pointcloud2.msg") if args.extras_dir else None,
               args.cdr_dir)]
    if args.extras_dir:
        db.executescript(JAZZY_SCHEMA)
        db.execute("INSERT INTO schema VALUES (9, 'jazzy')")
        for sub in sorted((d for d in os.listdir(args.extras_dir) if d.isdigit()), key=int):
            folder = os.path.join(args.extras_dir, sub)
            with open(os.path.join(folder, "topic")) as f:
                name, type_ = f.read().split()
            topics.append((name, type_, os.path.join(folder, "definition.msg"), folder))
    else:
        db.executescript(SCHEMA)
        db.execute("INSERT INTO schema VALUES (3, 'humble')")
    rows = []  # (stamp, topic id, file)
    for topic_id, (name, type_, definition, folder) in enumerate(topics, start=1):
        if args.extras_dir:
            db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', ?, '')",
                       (topic_id, name, type_, QOS))
            with open(definition) as f:
                db.execute("INSERT INTO message_definitions (topic_type, encoding, "
                           "encoded_message_definition, type_description_hash) "
                           "VALUES (?, 'ros2msg', ?, '')", (type_, f.read()))
        else:
            db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', ?)",
                       (topic_id, name, type_, QOS))
        for file in sorted(n for n in os.listdir(folder) if n.endswith(".cdr")):
            rows.append((int(file[:-len(".cdr")].split("_")[1]), topic_id,
                         os.path.join(folder, file)))
    rows.sort(key=lambda r: (r[0], r[1]))  # by stamp; the frame first at equal stamps
    for stamp, topic_id, path in rows:
        with open(path, "rb") as f:
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                       (topic_id, stamp, f.read()))
    db.commit()
    db.close()
    print(f"write_db3: {len(rows)} messages on {len(topics)} topic(s) -> {args.out}")


if __name__ == "__main__":
    main()
