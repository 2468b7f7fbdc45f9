// Writes a ROS 2 MCAP drive with @mcap/core's McapWriter: one CDR sensor_msgs/msg/PointCloud2 per
// KITTI .bin frame (pointcloud.mjs says how a frame becomes a message) on one topic, chunked,
// each chunk compressed with zstd (@foxglove/wasm-zstd), lz4 (lz4js, LZ4 frame format) or not at
// all, with message indexes and the summary (schema, channel, statistics, chunk indexes).
//
// usage: node write_mcap.mjs --out FILE.mcap --compression zstd|lz4|none [--topic /points]
//                            [--frame-id velodyne] [--chunk-size BYTES] [--first N] FRAME.bin...
// A chunk is closed once it holds more than --chunk-size bytes (default 1 MiB; 1 gives one
// message per chunk). log_time = publish_time = the header stamp. --first N: the frames are
// frames N, N + 1, ... of the drive (their stamps and sequence numbers; default 0), as in the
// second file of a split bag.
import { open } from "node:fs/promises";

import { McapWriter } from "@mcap/core";
import * as zstd from "@foxglove/wasm-zstd";
import lz4 from "lz4js";

import { POINTCLOUD2_DEFINITION, POINTCLOUD2_TYPE, cdrWriter, parseArgs, pointCloudMessage,
         stampNs } from "./pointcloud.mjs";

// An IWritable over a file handle.
class FileWritable {
  constructor(handle) {
    this.handle = handle;
    this.offset = 0n;
  }
  async write(buffer) {
    await this.handle.write(buffer);
    this.offset += BigInt(buffer.byteLength);
  }
  position() {
    return this.offset;
  }
}

async function main() {
  const { options, positional } =
      parseArgs(process.argv.slice(2),
                ["out", "compression", "topic", "frame-id", "chunk-size", "first"]);
  if (!options.out || !options.compression || positional.length === 0)
    throw new Error("usage: write_mcap.mjs --out FILE.mcap --compression zstd|lz4|none " +
                    "[--topic T] [--frame-id F] [--chunk-size BYTES] [--first N] FRAME.bin...");
  let compressChunk;
  if (options.compression === "zstd") {
    await zstd.isLoaded;
    compressChunk = (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) });
  } else if (options.compression === "lz4") {
    compressChunk = (data) => ({ compression: "lz4", compressedData: lz4.compress(data) });
  } else if (options.compression !== "none") {
    throw new Error(`--compression must be zstd, lz4 or none, not ${options.compression}`);
  }
  const topic = options.topic ?? "/points";
  const frameId = options["frame-id"] ?? "velodyne";
  const chunkSize = Number(options["chunk-size"] ?? 1024 * 1024);
  const first = Number(options.first ?? 0);

  const handle = await open(options.out, "w");
  const writer = new McapWriter({ writable: new FileWritable(handle), chunkSize, compressChunk });
  await writer.start({ profile: "ros2", library: "@mcap/core (lpir-gseg drive fixtures)" });
  const schemaId = await writer.registerSchema({
    name: POINTCLOUD2_TYPE,
    encoding: "ros2msg",
    data: new TextEncoder().encode(POINTCLOUD2_DEFINITION),
  });
  const channelId = await writer.registerChannel({
    topic,
    schemaId,
    messageEncoding: "cdr",
    metadata: new Map([["offered_qos_profiles", ""]]),
  });
  const cdr = cdrWriter();
  for (let k = 0; k < positional.length; ++k) {
    const i = first + k;
    const data = cdr.writeMessage(pointCloudMessage(positional[k], i, frameId));
    const stamp = stampNs(i);
    await writer.addMessage({ channelId, sequence: i, logTime: stamp, publishTime: stamp, data });
  }
  await writer.end();
  await handle.close();
  console.log(`write_mcap: ${positional.length} messages on ${topic} (${options.compression}) -> ` +
              options.out);
}

main().catch((error) => {
  console.error(`write_mcap: ${error.message}`);
  process.exit(1);
});
