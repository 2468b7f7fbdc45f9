// Writes each KITTI .bin frame as one CDR sensor_msgs/msg/PointCloud2 message file, serialized by
// @foxglove/rosmsg2-serialization (pointcloud.mjs says how a frame becomes a message), for
// write_db3.py to store in a rosbag2 SQLite bag.
//
// usage: node write_cdr.mjs --out-dir DIR [--frame-id velodyne] FRAME.bin...
// Frame i becomes DIR/<i, 6 digits>_<stamp in ns>.cdr.
import { mkdirSync, writeFileSync } from "node:fs";
import { join } from "node:path";

import { cdrWriter, parseArgs, pointCloudMessage, stampNs } from "./pointcloud.mjs";

try {
  const { options, positional } = parseArgs(process.argv.slice(2), ["out-dir", "frame-id"]);
  if (!options["out-dir"] || positional.length === 0)
    throw new Error("usage: write_cdr.mjs --out-dir DIR [--frame-id F] FRAME.bin...");
  mkdirSync(options["out-dir"], { recursive: true });
  const cdr = cdrWriter();
  for (let i = 0; i < positional.length; ++i) {
    const data = cdr.writeMessage(pointCloudMessage(positional[i], i, options["frame-id"] ?? "velodyne"));
    const name = `${String(i).padStart(6, "0")}_${stampNs(i)}.cdr`;
    writeFileSync(join(options["out-dir"], name), data);
  }
} catch (error) {
  console.error(`write_cdr: ${error.message}`);
  process.exit(1);
}
