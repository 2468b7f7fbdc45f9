#!/usr/bin/python3
"""Writes a ROS 2 SQLite bag (.db3) with Python's sqlite3, in rosbag2's schema (version 3, as
Humble's recorder writes it): tables schema, metadata, topics(id, name, type,
serialization_format, offered_qos_profiles) and messages(id, topic_id, timestamp, data), with
the timestamp index. One topic (type sensor_msgs/msg/PointCloud2, format cdr); its messages are
the CDR files write_cdr.mjs made (serialized by @foxglove/rosmsg2-serialization), in name order,
each stored with the stamp its name carries (<seq>_<stamp ns>.cdr) as the timestamp.

usage: write_db3.py --cdr-dir DIR --out FILE.db3 [--topic /points]
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
    args = parser.parse_args()
    names = sorted(n for n in os.listdir(args.cdr_dir) if n.endswith(".cdr"))
    if not names:
        sys.exit(f"write_db3: no .cdr files in {args.cdr_dir}")
    if os.path.exists(args.out):
        os.remove(args.out)
    db = sqlite3.connect(args.out)
    db.executescript(SCHEMA)
    db.execute("INSERT INTO schema VALUES (3, 'humble')")
    db.execute("INSERT INTO topics VALUES (1, ?, 'sensor_msgs/msg/PointCloud2', 'cdr', ?)",
               (args.topic, QOS))
    for name in names:
        stamp = int(name[:-len(".cdr")].split("_")[1])
        with open(os.path.join(args.cdr_dir, name), "rb") as f:
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?, ?)",
                       (stamp, f.read()))
    db.commit()
    db.close()
    print(f"write_db3: {len(names)} messages on {args.topic} -> {args.out}")


if __name__ == "__main__":
    main()
