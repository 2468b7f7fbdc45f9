#!/usr/bin/python3
"""Writes the metadata.yaml of a ROS 2 bag folder, as rosbag2 writes it beside the bag's files:
one topic (sensor_msgs/msg/PointCloud2, cdr), the files in order with their message counts, the
stamps write_mcap.mjs and write_cdr.mjs give frame i (1600000000 s + i x 100 ms, i counted over
the files).

  --style rosbag2: the text rosbag2's recorder writes through yaml-cpp (Jazzy, version 9: block
                   sequences indented under their key, the QoS profile as a nested list), filled
                   in here line by line;
  --style pyyaml:  the bag information as PyYAML's safe_dump writes it (Humble's version 5 with
                   the QoS profile as one string, keys sorted, sequences not indented, long
                   strings folded over lines), as rosbag2_py's tests and Python tools write it.

usage: write_metadata.py --out DIR/metadata.yaml --storage mcap|sqlite3 --style rosbag2|pyyaml
                         [--topic /points] FILE:COUNT...
"""
import argparse

import yaml

BASE_NS = 1600000000 * 1000000000
PERIOD_NS = 100000000
TYPE = "sensor_msgs/msg/PointCloud2"
# What Humble's recorder stores for a sensor-data subscription (as write_db3.py does).
QOS = ("- history: 3\n  depth: 0\n  reliability: 2\n  durability: 2\n"
       "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  liveliness: 1\n  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
       "  avoid_ros_namespace_conventions: false\n")


def rosbag2_text(storage, topic, files):
    """Jazzy's metadata.yaml for `files` [(name, first frame, count)]."""
    total = sum(count for _, _, count in files)
    start, end = BASE_NS, BASE_NS + (total - 1) * PERIOD_NS
    lines = [
        "rosbag2_bagfile_information:",
        "  version: 9",
        f"  storage_identifier: {storage}",
        "  duration:",
        f"    nanoseconds: {end - start}",
        "  starting_time:",
        f"    nanoseconds_since_epoch: {start}",
        f"  message_count: {total}",
        "  topics_with_message_count:",
        "    - topic_metadata:",
        f"        name: {topic}",
        f"        type: {TYPE}",
        "        serialization_format: cdr",
        "        offered_qos_profiles:",
        "          - history: keep_last",
        "            depth: 5",
        "            reliability: best_effort",
        "            durability: volatile",
        "            deadline:",
        "              sec: 9223372036",
        "              nsec: 854775807",
        "            lifespan:",
        "              sec: 9223372036",
        "              nsec: 854775807",
        "            liveliness: automatic",
        "            liveliness_lease_duration:",
        "              sec: 9223372036",
        "              nsec: 854775807",
        "            avoid_ros_namespace_conventions: false",
        "        type_description_hash: RIHS01_" + "0" * 64,
        f"      message_count: {total}",
        '  compression_format: ""',
        '  compression_mode: ""',
        "  relative_file_paths:",
    ]
    lines += [f"    - {name}" for name, _, _ in files]
    lines.append("  files:")
    for name, first, count in files:
        lines += [
            f"    - path: {name}",
            "      starting_time:",
            f"        nanoseconds_since_epoch: {BASE_NS + first * PERIOD_NS}",
            "      duration:",
            f"        nanoseconds: {(count - 1) * PERIOD_NS}",
            f"      message_count: {count}",
        ]
    lines += ["  custom_data: ~", "  ros_distro: jazzy", ""]
    return "\n".join(lines)


def pyyaml_text(storage, topic, files):
    """Humble's bag information for `files`, dumped by PyYAML."""
    total = sum(count for _, _, count in files)
    info = {
        "version": 5,
        "storage_identifier": storage,
        "duration": {"nanoseconds": (total - 1) * PERIOD_NS},
        "starting_time": {"nanoseconds_since_epoch": BASE_NS},
        "message_count": total,
        "topics_with_message_count": [{
            "topic_metadata": {"name": topic, "type": TYPE, "serialization_format": "cdr",
                               "offered_qos_profiles": QOS},
            "message_count": total,
        }],
        "compression_format": "",
        "compression_mode": "",
        "relative_file_paths": [name for name, _, _ in files],
        "files": [{"path": name,
                   "starting_time": {"nanoseconds_since_epoch": BASE_NS + first * PERIOD_NS},
                   "duration": {"nanoseconds": (count - 1) * PERIOD_NS},
                   "message_count": count} for name, first, count in files],
    }
    return yaml.safe_dump({"rosbag2_bagfile_information": info})


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--storage", required=True, choices=("mcap", "sqlite3"))
    parser.add_argument("--style", required=True, choices=("rosbag2", "pyyaml"))
    parser.add_argument("--topic", default="/points")
    parser.add_argument("files", nargs="+", metavar="FILE:COUNT")
    args = parser.parse_args()
    files, first = [], 0
    for spec in args.files:
        name, count = spec.rsplit(":", 1)
        files.append((name, first, int(count)))
        first += int(count)
    text = (rosbag2_text if args.style == "rosbag2" else pyyaml_text)(args.storage, args.topic,
                                                                      files)
    with open(args.out, "w") as f:
        f.write(text)
    print(f"write_metadata: {len(files)} files, {first} messages ({args.style}) -> {args.out}")


if __name__ == "__main__":
    main()
