#!/usr/bin/python3
"""Reads a ROS 1 bag with Debian's python3-rosbag (not lpir-gseg's code) and checks it, for the
output of `lpir-gseg segment --format bag`. Prints one line per topic: topic, type, message count.

usage: read_bag.py FILE.bag [--input IN.bag] [--expect TOPIC:COUNT]... [--labels DIR]
  --input IN.bag  every topic of IN is in FILE: each connection's header (type, md5sum,
                  message_definition, callerid, latching, ...) as IN's, and the same messages
                  (receipt time, serialized bytes) in the same order.
  --expect T:N    topic T has N messages.
  --labels DIR    the .label files of `lpir-gseg segment` (uint32 per point, in natural name
                  order): the k-th labelled message's labels equal the k-th file's values.
For every topic T that has T/labelled, T/ground and T/nonground beside it, message k of each
(sensor_msgs/PointCloud2, deserialized by rosbag's generated class) against T's message k:
  - each of the three: point_step a multiple of 4, every field's offset and point_step a multiple
    of the field's size, row_step = width x point_step, data exactly row_step x height, T's
    header (seq, stamp, frame_id);
  - T/labelled: T's width and height, T's fields and a uint32 `label` (count 1) whose values are
    0 or 1, every field's bytes of every point equal to T's;
  - T/ground: height 1, the points of T/labelled whose label is 1, in order, every field's bytes
    equal; T/nonground the same for label 0.
Exits 1, naming the message and the problem, on any failure.
"""
import argparse
import os
import re
import struct
import sys

import rosbag

SIZES = {1: 1, 2: 1, 3: 2, 4: 2, 5: 4, 6: 4, 7: 4, 8: 8}  # by PointField datatype
UINT32 = 6
SUFFIXES = ("/labelled", "/ground", "/nonground")
problems = []


def load(path):
    """topic -> {"header": the connection header, "messages": [(time ns, raw bytes, msg)]}."""
    topics = {}
    with rosbag.Bag(path) as bag:
        for conn in bag._get_connections():
            topics.setdefault(conn.topic, {"header": dict(conn.header), "messages": []})
        for topic, raw, t in bag.read_messages(raw=True):
            topics[topic]["messages"].append((t.to_nsec(), raw[1], raw))
    return topics


def decode(raw):
    """The message of rosbag's raw tuple (type, bytes, md5sum, position, class)."""
    msg = raw[4]()
    msg.deserialize(raw[1])
    return msg


def field_bytes(msg, field, i):
    at = (i // msg.width) * msg.row_step + (i % msg.width) * msg.point_step + field.offset
    return bytes(msg.data[at:at + SIZES[field.datatype] * field.count])


def layout_problem(msg):
    if msg.point_step % 4:
        return f"point_step {msg.point_step} is not a multiple of 4"
    for f in msg.fields:
        size = SIZES.get(f.datatype, 0)
        if not size or f.offset % size or msg.point_step % size:
            return f"field {f.name} (offset {f.offset}, datatype {f.datatype}) is not aligned"
    if msg.row_step != msg.width * msg.point_step or len(msg.data) != msg.row_step * msg.height:
        return f"{len(msg.data)} data bytes for {msg.height} rows of {msg.width} x {msg.point_step}"
    return ""


def compare_with_input(path, output, input_path, inputs):
    for topic, want in inputs.items():
        got = output.get(topic)
        if got is None:
            problems.append(f"{path}: {input_path}'s topic {topic} is missing")
            continue
        for key, value in want["header"].items():
            if got["header"].get(key) != value:
                problems.append(f"{path}: {topic}: connection header field {key} differs from "
                                "the input's")
        if len(got["messages"]) != len(want["messages"]):
            problems.append(f"{path}: {topic}: {len(got['messages'])} messages, the input has "
                            f"{len(want['messages'])}")
            continue
        for k, (w, g) in enumerate(zip(want["messages"], got["messages"])):
            if w[0] != g[0] or w[1] != g[1]:
                problems.append(f"{path}: {topic} message {k} differs from the input's (time or "
                                "bytes)")


def check_clouds(path, topic, output, label_files, labels_dir):
    entries = [output[topic]] + [output[topic + s] for s in SUFFIXES]
    count = len(entries[0]["messages"])
    for suffix, e in zip(SUFFIXES, entries[1:]):
        if len(e["messages"]) != count:
            problems.append(f"{path}: {topic}{suffix}: {len(e['messages'])} messages, {topic} "
                            f"has {count}")
    if label_files is not None and len(label_files) != len(entries[1]["messages"]):
        problems.append(f"{path}: {topic}/labelled: {len(entries[1]['messages'])} messages, "
                        f"{labels_dir} has {len(label_files)} .label files")
    for k in range(min(len(e["messages"]) for e in entries)):
        src, labelled, ground, nonground = (decode(e["messages"][k][2]) for e in entries)
        where = f"{path}: {topic} message {k}"
        for name, msg in (("labelled", labelled), ("ground", ground), ("nonground", nonground)):
            problem = layout_problem(msg)
            if problem:
                problems.append(f"{where}: {name}: {problem}")
            if (msg.header.seq, msg.header.stamp, msg.header.frame_id) != (
                    src.header.seq, src.header.stamp, src.header.frame_id):
                problems.append(f"{where}: {name}: header differs from the input message's")
        label = next((f for f in labelled.fields if f.name == "label"), None)
        if label is None or label.datatype != UINT32 or label.count != 1:
            problems.append(f"{where}: labelled: no uint32 label field")
            continue
        points = src.width * src.height
        if (labelled.width, labelled.height) != (src.width, src.height):
            problems.append(f"{where}: labelled is {labelled.width} x {labelled.height}, the "
                            f"input {src.width} x {src.height}")
        if ground.height != 1 or nonground.height != 1 or ground.width + nonground.width != points:
            problems.append(f"{where}: ground {ground.width} + nonground {nonground.width} "
                            f"points, the input has {points}")
        order = ">I" if labelled.is_bigendian else "<I"
        labels = [struct.unpack(order, field_bytes(labelled, label, i))[0] for i in range(points)]
        bad = [i for i, v in enumerate(labels) if v > 1]
        if bad:
            problems.append(f"{where}: point {bad[0]} has label {labels[bad[0]]}, not 0 or 1")
        parts = (nonground, ground)
        differ = 0
        for f in src.fields:
            lf = next((g for g in labelled.fields if g.name == f.name), None)
            pf = [next((g for g in p.fields if g.name == f.name), None) for p in parts]
            if lf is None or None in pf or (lf.datatype, lf.count) != (f.datatype, f.count):
                problems.append(f"{where}: field {f.name} is not in the three clouds as the "
                                "input has it")
                continue
            nxt = [0, 0]
            for i in range(points):
                value = field_bytes(src, f, i)
                differ += field_bytes(labelled, lf, i) != value
                side = 1 if labels[i] == 1 else 0
                if nxt[side] >= parts[side].width or field_bytes(parts[side], pf[side],
                                                                 nxt[side]) != value:
                    differ += 1
                nxt[side] += 1
        if differ:
            problems.append(f"{where}: {differ} field values differ from the input's or the "
                            "split's")
        if label_files is not None and k < len(label_files):
            with open(os.path.join(labels_dir, label_files[k]), "rb") as f:
                raw = f.read()
            want = list(struct.unpack(f"<{len(raw) // 4}I", raw[:len(raw) // 4 * 4]))
            if want != labels:
                problems.append(f"{where}: labels differ from {label_files[k]}")


def natural(name):
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", name)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bag")
    parser.add_argument("--input")
    parser.add_argument("--expect", action="append", default=[])
    parser.add_argument("--labels")
    args = parser.parse_args()
    label_files = None
    if args.labels is not None:
        label_files = sorted((n for n in os.listdir(args.labels) if n.endswith(".label")),
                             key=natural)
    output = load(args.bag)
    for topic, entry in output.items():
        print(f"{topic} {entry['header'].get('type')} {len(entry['messages'])}")
    if args.input:
        compare_with_input(args.bag, output, args.input, load(args.input))
    for expect in args.expect:
        topic, count = expect.rsplit(":", 1)
        got = len(output[topic]["messages"]) if topic in output else None
        if got != int(count):
            problems.append(f"{args.bag}: {topic}: expected {count} messages, found "
                            f"{got if got is not None else 'no such topic'}")
    checked = 0
    for topic in list(output):
        if all(topic + s in output for s in SUFFIXES):
            check_clouds(args.bag, topic, output, label_files, args.labels)
            checked += 1
    if args.labels is not None and checked == 0:
        problems.append(f"{args.bag}: no topic T with T/labelled, T/ground and T/nonground to "
                        f"compare with {args.labels}")
    if problems:
        for p in problems:
            print(f"read_bag: {p}", file=sys.stderr)
        sys.exit(1)
    print(f"read_bag: {args.bag}: every check passed")


if __name__ == "__main__":
    main()
