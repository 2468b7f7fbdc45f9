// Writes each KITTI .bin frame as one CDR sensor_msgs/msg/PointCloud2 message file, serialized by
// @foxglove/rosmsg2-serialization (pointcloud.mjs says how a frame becomes a message), for
// write_db3.py to store in a rosbag2 SQLite bag.
//
// usage: node write_cdr.mjs --out-dir DIR [--frame-id velodyne] [--first N] FRAME.bin...
// Frame i becomes DIR/<i, 6 digits>_<stamp in ns>.cdr; --first N: the frames given are frames N,
// N + 1, ... (default 0).
import { mkdirSync, writeFileSync } from "node:fs";
import { join } from "node:path";

import { cdrWriter, parseArgs, pointCloudMessage, stampNs } from "./pointcloud.mjs";

try {
  const { options, positional } =
      parseArgs(process.argv.slice(2), ["out-dir", "frame-id", "first"]);
  if (!options["out-dir"] || positional.length === 0)
    throw new Error("usage: write_cdr.mjs --out-dir DIR [--frame-id F] [--first N] FRAME.bin...");
  mkdirSync(options["out-dir"], { recursive: true });
  const cdr = cdrWriter();
  const first = Number(options.first ?? 0);
  for (let k = 0; k < positional.length; ++k) {
    const i = first + k;
    const data = cdr.writeMessage(pointCloudMessage(positional[k], i, options["frame-id"] ?? "velodyne"));
    const name = `${String(i).padStart(6, "0")}_${stampNs(i)}.cdr`;
    writeFileSync(join(options["out-dir"], name), data);
  }
} catch (error) {
  console.error(`write_cdr: ${error.message}`);
  process.exit(1);
}
