// sensor_msgs/msg/PointCloud2 messages from KITTI .bin frames, serialized to CDR by
// @foxglove/rosmsg2-serialization (not by lpir-gseg's code), for the independent MCAP and .db3
// writers (write_mcap.mjs, write_cdr.mjs).
//
// Frame i (0-based, in the order given) becomes one message:
//   header.stamp = 1600000000 s + i x 100 ms, header.frame_id = --frame-id (default "velodyne");
//   height 1, width = the frame's points, little-endian, is_dense false;
//   layout "velodyne" (the default): fields x y z intensity (float32, from the .bin), then ring
//   (uint16, from FRAME.ring beside FRAME.bin: one little-endian uint16 per point) when that file
//   exists, then time (float32, point k of n at k / n x 0.1 s, as a 10 Hz sensor's sweep).
//   point_step 22 with ring, else 20.
//   layout "livox" (livox_ros_driver2's PointCloud2, packed, point_step 26): x y z intensity
//   (float32, from the .bin, offsets 0-12), tag (uint8, 16: 0x10, the Livox manual's "return 1",
//   every other group normal), line (uint8, 17: point k's k mod 4, the laser numbering of a
//   four-laser head, so that a reader taking it for a ring would move the points' rows),
//   timestamp (float64, 18, unaligned: the point's time in ns since the epoch, the stamp plus
//   k / n x 100 ms).
import { readFileSync, existsSync } from "node:fs";

import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";

// The ros2msg text ROS 2's recorder stores in an MCAP schema: the message, then each dependency
// after a line of '=' and "MSG: <type>".
const SEPARATOR = "=".repeat(80);
export const POINTCLOUD2_DEFINITION = [
  "std_msgs/Header header",
  "uint32 height",
  "uint32 width",
  "PointField[] fields",
  "bool is_bigendian",
  "uint32 point_step",
  "uint32 row_step",
  "uint8[] data",
  "bool is_dense",
  SEPARATOR,
  "MSG: std_msgs/Header",
  "builtin_interfaces/Time stamp",
  "string frame_id",
  SEPARATOR,
  "MSG: builtin_interfaces/Time",
  "int32 sec",
  "uint32 nanosec",
  SEPARATOR,
  "MSG: sensor_msgs/PointField",
  "uint8 INT8    = 1",
  "uint8 UINT8   = 2",
  "uint8 INT16   = 3",
  "uint8 UINT16  = 4",
  "uint8 INT32   = 5",
  "uint8 UINT32  = 6",
  "uint8 FLOAT32 = 7",
  "uint8 FLOAT64 = 8",
  "string name",
  "uint32 offset",
  "uint8  datatype",
  "uint32 count",
  "",
].join("\n");

export const POINTCLOUD2_TYPE = "sensor_msgs/msg/PointCloud2";
const FLOAT32 = 7;
const FLOAT64 = 8;
const UINT8 = 2;
const UINT16 = 4;
const LIVOX_TAG = 0x10;
const BASE_SEC = 1600000000;
const PERIOD_NS = 100000000n;

// Nanoseconds since the epoch of frame i's stamp.
export function stampNs(i) {
  return BigInt(BASE_SEC) * 1000000000n + BigInt(i) * PERIOD_NS;
}

// The x y z intensity fields of both layouts: the .bin's 16 bytes a point, copied at offset 0.
const XYZI_FIELDS = [
  { name: "x", offset: 0, datatype: FLOAT32, count: 1 },
  { name: "y", offset: 4, datatype: FLOAT32, count: 1 },
  { name: "z", offset: 8, datatype: FLOAT32, count: 1 },
  { name: "intensity", offset: 12, datatype: FLOAT32, count: 1 },
];

// The fields, point_step and data of frame `bin` (n points) in livox_ros_driver2's layout,
// stamped `stamp` ns.
function livoxRecords(bin, n, stamp) {
  const step = 26;
  const fields = [
    ...XYZI_FIELDS,
    { name: "tag", offset: 16, datatype: UINT8, count: 1 },
    { name: "line", offset: 17, datatype: UINT8, count: 1 },
    { name: "timestamp", offset: 18, datatype: FLOAT64, count: 1 },
  ];
  const data = new Uint8Array(n * step);
  const view = new DataView(data.buffer);
  for (let k = 0; k < n; ++k) {
    bin.copy(data, k * step, k * 16, k * 16 + 16);
    view.setUint8(k * step + 16, LIVOX_TAG);
    view.setUint8(k * step + 17, k % 4);
    view.setFloat64(k * step + 18, Number(stamp) + (k / n) * Number(PERIOD_NS), true);
  }
  return { fields, step, data };
}

// The message object of frame `index` read from `binPath`, in `layout` ("velodyne" or "livox").
export function pointCloudMessage(binPath, index, frameId, layout = "velodyne") {
  const bin = readFileSync(binPath);
  if (bin.length % 16 !== 0) throw new Error(`${binPath}: not a KITTI .bin (size ${bin.length})`);
  const n = bin.length / 16;
  const stamp = stampNs(index);
  const header = {
    stamp: { sec: Number(stamp / 1000000000n), nanosec: Number(stamp % 1000000000n) },
    frame_id: frameId,
  };
  let records;
  if (layout === "livox") records = livoxRecords(bin, n, stamp);
  else if (layout === "velodyne") records = velodyneRecords(binPath, bin, n);
  else throw new Error(`layout must be velodyne or livox, not ${layout}`);
  return {
    header,
    height: 1,
    width: n,
    fields: records.fields,
    is_bigendian: false,
    point_step: records.step,
    row_step: n * records.step,
    data: records.data,
    is_dense: false,
  };
}

// The fields, point_step and data of frame `bin` (n points, read from `binPath`) in the velodyne
// layout: the ring from FRAME.ring when that file exists.
function velodyneRecords(binPath, bin, n) {
  const ringPath = binPath.replace(/\.bin$/, ".ring");
  const ring = existsSync(ringPath) ? readFileSync(ringPath) : null;
  if (ring && ring.length !== 2 * n)
    throw new Error(`${ringPath}: ${ring.length} bytes, expected ${2 * n} (one uint16 per point)`);
  const fields = [...XYZI_FIELDS];
  let step = 16;
  if (ring) {
    fields.push({ name: "ring", offset: step, datatype: UINT16, count: 1 });
    step += 2;
  }
  const timeOffset = step;
  fields.push({ name: "time", offset: timeOffset, datatype: FLOAT32, count: 1 });
  step += 4;
  const data = new Uint8Array(n * step);
  const view = new DataView(data.buffer);
  for (let k = 0; k < n; ++k) {
    bin.copy(data, k * step, k * 16, k * 16 + 16);  // x y z intensity as the .bin holds them
    if (ring) view.setUint16(k * step + 16, ring.readUInt16LE(2 * k), true);
    view.setFloat32(k * step + timeOffset, (k / n) * 0.1, true);
  }
  return { fields, step, data };
}

// A serializer of PointCloud2 objects to CDR (little-endian, with the encapsulation header).
export function cdrWriter() {
  return new MessageWriter(parse(POINTCLOUD2_DEFINITION, { ros2: true }));
}

// Command-line options --name value; the rest are positional.
export function parseArgs(argv, known) {
  const options = {};
  const positional = [];
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i].startsWith("--")) {
      const key = argv[i].slice(2);
      if (!known.includes(key)) throw new Error(`unknown option --${key}`);
      if (i + 1 >= argv.length) throw new Error(`--${key} needs a value`);
      options[key] = argv[++i];
    } else {
      positional.push(argv[i]);
    }
  }
  return { options, positional };
}
