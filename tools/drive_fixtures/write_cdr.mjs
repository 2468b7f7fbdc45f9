// Writes each KITTI .bin frame as one CDR sensor_msgs/msg/PointCloud2 message file, serialized by
// @foxglove/rosmsg2-serialization (pointcloud.mjs says how a frame becomes a message), for
// write_db3.py to store in a rosbag2 SQLite bag.
//
// usage: node write_cdr.mjs --out-dir DIR [--frame-id velodyne] [--first N]
//                           [--extras-dir EXTRAS] FRAME.bin...
// Frame i becomes DIR/<i, 6 digits>_<stamp in ns>.cdr; --first N: the frames given are frames N,
// N + 1, ... (default 0). With --extras-dir, the other topics of extras.mjs go to EXTRAS/<n>/
// (n = 0, 1, ... in the order the topics first appear): a file `topic` (name, then type, a line
// each), `definition.msg` (its ros2msg text) and the messages as <k, 6 digits>_<stamp in ns>.cdr;
// and EXTRAS/pointcloud2.msg holds the frames' definition.
import { mkdirSync, writeFileSync } from "node:fs";
import { join } from "node:path";

import { extraMessages } from "./extras.mjs";
import { POINTCLOUD2_DEFINITION, cdrWriter, parseArgs, pointCloudMessage,
         stampNs } from "./pointcloud.mjs";

try {
  const { options, positional } =
      parseArgs(process.argv.slice(2), ["out-dir", "frame-id", "first", "extras-dir"]);
  if (!options["out-dir"] || positional.length === 0)
    throw new Error("usage: write_cdr.mjs --out-dir DIR [--frame-id F] [--first N] " +
                    "[--extras-dir E] FRAME.bin...");
  mkdirSync(options["out-dir"], { recursive: true });
  const cdr = cdrWriter();
  const first = Number(options.first ?? 0);
  for (let k = 0; k < positional.length; ++k) {
    const i = first + k;
    const data = cdr.writeMessage(pointCloudMessage(positional[k], i, options["frame-id"] ?? "velodyne"));
    const name = `${String(i).padStart(6, "0")}_${stampNs(i)}.cdr`;
    writeFileSync(join(options["out-dir"], name), data);
  }
  const extras = options["extras-dir"];
  if (extras) {
    mkdirSync(extras, { recursive: true });
    writeFileSync(join(extras, "pointcloud2.msg"), POINTCLOUD2_DEFINITION);
    const topics = new Map();  // topic -> { dir, count }
    for (const m of extraMessages(positional.length)) {
      if (!topics.has(m.topic)) {
        const dir = join(extras, String(topics.size));
        mkdirSync(dir, { recursive: true });
        writeFileSync(join(dir, "topic"), `${m.topic}\n${m.type}\n`);
        writeFileSync(join(dir, "definition.msg"), m.definition);
        topics.set(m.topic, { dir, count: 0 });
      }
      const t = topics.get(m.topic);
      writeFileSync(join(t.dir, `${String(t.count++).padStart(6, "0")}_${m.stampNs}.cdr`), m.data);
    }
  }
} catch (error) {
  console.error(`write_cdr: ${error.message}`);
  process.exit(1);
}
