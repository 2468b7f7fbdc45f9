// Writes a ROS 2 MCAP drive with @mcap/core's McapWriter: one CDR sensor_msgs/msg/PointCloud2 per
// KITTI .bin frame (pointcloud.mjs says how a frame becomes a message) on one topic, chunked,
// each chunk compressed with zstd (@foxglove/wasm-zstd), lz4 (lz4js, LZ4 frame format) or not at
// all, with message indexes and the summary (schema, channel, statistics, chunk indexes).
//
// usage: node write_mcap.mjs --out FILE.mcap --compression zstd|lz4|none [--topic /points]
//                            [--frame-id velodyne] [--chunk-size BYTES] [--first N]
//                            [--extras 1] [--layout velodyne|livox] FRAME.bin...
// A chunk is closed once it holds more than --chunk-size bytes (default 1 MiB; 1 gives one
// message per chunk). log_time = publish_time = the header stamp. --first N: the frames are
// frames N, N + 1, ... of the drive (their stamps and sequence numbers; default 0), as in the
// second file of a split bag. --extras 1 adds the other topics of extras.mjs (/imu/data,
// /gps/fix) in log-time order among the frames, each channel with its own sequence from 0, and
// first a metadata record and an attachment. --layout: the PointCloud2's fields (pointcloud.mjs;
// default velodyne).
import { open } from "node:fs/promises";

import { McapWriter } from "@mcap/core";
import * as zstd from "@foxglove/wasm-zstd";
import lz4 from "lz4js";

import { EXTRA_ATTACHMENT, EXTRA_METADATA, extraMessages } from "./extras.mjs";
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
                ["out", "compression", "topic", "frame-id", "chunk-size", "first", "extras",
                 "layout"]);
  if (!options.out || !options.compression || positional.length === 0)
    throw new Error("usage: write_mcap.mjs --out FILE.mcap --compression zstd|lz4|none " +
                    "[--topic T] [--frame-id F] [--chunk-size BYTES] [--first N] [--extras 1] " +
                    "[--layout velodyne|livox] FRAME.bin...");
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
  const layout = options.layout ?? "velodyne";

  const handle = await open(options.out, "w");
  const writer = new McapWriter({ writable: new FileWritable(handle), chunkSize, compressChunk });
  await writer.start({ profile: "ros2", library: "@mcap/core (lpir-gseg drive fixtures)" });
  const qos = new Map([["offered_qos_profiles", ""]]);
  const channel = async (topic, name, definition) => {
    const schemaId = await writer.registerSchema({
      name,
      encoding: "ros2msg",
      data: new TextEncoder().encode(definition),
    });
    return writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: qos });
  };
  const messages = [];  // { channel, stampNs, data }, in log-time order
  const cloudChannel = await channel(topic, POINTCLOUD2_TYPE, POINTCLOUD2_DEFINITION);
  const cdr = cdrWriter();
  for (let k = 0; k < positional.length; ++k) {
    const i = first + k;
    messages.push({ channel: cloudChannel, stampNs: stampNs(i),
                    data: cdr.writeMessage(pointCloudMessage(positional[k], i, frameId, layout)) });
  }
  if (options.extras === "1") {
    await writer.addMetadata(EXTRA_METADATA);
    await writer.addAttachment({ ...EXTRA_ATTACHMENT, logTime: stampNs(0), createTime: stampNs(0) });
    const channels = new Map();
    for (const m of extraMessages(positional.length)) {
      if (!channels.has(m.topic)) channels.set(m.topic, await channel(m.topic, m.type, m.definition));
      messages.push({ channel: channels.get(m.topic), stampNs: m.stampNs, data: m.data });
    }
    messages.sort((a, b) => (a.stampNs < b.stampNs ? -1 : a.stampNs > b.stampNs ? 1 : 0));
  }
  const sequences = new Map([[cloudChannel, first]]);  // the frames' sequence is their number
  for (const m of messages) {
    const sequence = sequences.get(m.channel) ?? 0;
    sequences.set(m.channel, sequence + 1);
    await writer.addMessage({ channelId: m.channel, sequence, logTime: m.stampNs,
                              publishTime: m.stampNs, data: m.data });
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
