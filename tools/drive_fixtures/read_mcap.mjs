// Reads an MCAP file with @mcap/core (not lpir-gseg's code) and checks it, for the output of
// `lpir-gseg segment --format mcap`: first a McapStreamReader pass over every record (chunk CRCs
// validated) to the footer, then the summary through McapIndexedReader, then every message. The
// file must be indexed (chunked, with chunk indexes in its summary), as lpir-gseg's writer and
// ROS 2's recorder make them: McapIndexedReader reads nothing else.
// Prints one line per channel: topic, schema name, message encoding, message count.
//
// usage: node read_mcap.mjs FILE.mcap [--expect TOPIC:COUNT]... [--labels DIR]
// Every CDR sensor_msgs/msg/PointCloud2 message is decoded with @foxglove/rosmsg2-serialization
// from its channel's schema. For a topic T/ground beside T: its k-th message must carry a uint8
// `label` field, width x height points, exactly the bytes that point count needs, labels 0 or 1,
// the same stamp, width and height as T's k-th message and the same x, y, z bytes; and T/ground
// must have as many messages as T. With --labels DIR (the .label files of `lpir-gseg segment`,
// uint32 per point, taken in natural name order), the k-th message's labels must equal the k-th
// file's values. Exits 1, naming the message and the problem, on any failure.
import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import * as zstd from "@foxglove/wasm-zstd";
import lz4 from "@foxglove/wasm-lz4";

const UINT8 = 2;
const problems = [];
const fail = (text) => problems.push(text);

function decompressHandlers() {
  return {
    zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
    lz4: (buffer, size) => lz4(buffer, Number(size)),
  };
}

// The bytes of field `name` of every point of a decoded PointCloud2, concatenated.
function fieldBytes(msg, name, width) {
  const field = msg.fields.find((f) => f.name === name);
  if (!field) return null;
  const out = [];
  for (let row = 0; row < msg.height; ++row)
    for (let col = 0; col < msg.width; ++col) {
      const at = row * msg.row_step + col * msg.point_step + field.offset;
      out.push(Buffer.from(msg.data.buffer, msg.data.byteOffset + at, width).toString("hex"));
    }
  return out.join("");
}

async function main() {
  const args = process.argv.slice(2);
  let path;
  let labelsDir;
  const expect = [];
  for (let i = 0; i < args.length; ++i) {
    if (args[i] === "--expect") {
      const [topic, count] = (args[++i] ?? "").split(/:(?=[0-9]+$)/);
      expect.push({ topic, count: Number(count) });
    } else if (args[i] === "--labels") {
      labelsDir = args[++i];
    } else {
      path = args[i];
    }
  }
  if (!path) throw new Error("usage: read_mcap.mjs FILE.mcap [--expect TOPIC:COUNT]... [--labels DIR]");
  const labelFiles = labelsDir === undefined ? undefined :
      readdirSync(labelsDir).filter((n) => n.endsWith(".label"))
          .sort((a, b) => a.localeCompare(b, "en", { numeric: true }));
  await zstd.isLoaded;
  await lz4.isLoaded;
  const bytes = readFileSync(path);

  const stream = new McapStreamReader({ decompressHandlers: decompressHandlers(), validateCrcs: true });
  stream.append(bytes);
  let records = 0;
  while (stream.nextRecord()) ++records;
  if (!stream.done()) fail(`${path}: the stream reader stopped before the footer (${records} records)`);

  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers: decompressHandlers() });
  const decoders = new Map();
  const messages = new Map();  // topic -> decoded messages in log order
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    messages.set(channel.topic, []);
    if (schema?.name === "sensor_msgs/msg/PointCloud2" && channel.messageEncoding === "cdr")
      decoders.set(id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
  }
  for await (const message of reader.readMessages({ validateCrcs: true })) {
    const channel = reader.channelsById.get(message.channelId);
    const decoder = decoders.get(message.channelId);
    const list = messages.get(channel.topic);
    try {
      list.push(decoder ? decoder.readMessage(message.data) : null);
    } catch (error) {
      fail(`${path}: ${channel.topic} message ${list.length}: cannot decode: ${error.message}`);
      list.push(null);
    }
  }
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    const count = messages.get(channel.topic).length;
    const stat = reader.statistics?.channelMessageCounts.get(id);
    console.log(`${channel.topic} ${schema?.name ?? "(no schema)"} ${channel.messageEncoding} ${count}`);
    if (stat !== undefined && stat !== BigInt(count))
      fail(`${path}: ${channel.topic}: statistics say ${stat} messages, the file holds ${count}`);
  }
  for (const { topic, count } of expect) {
    const got = messages.get(topic)?.length;
    if (got !== count) fail(`${path}: ${topic}: expected ${count} messages, found ${got ?? "no such topic"}`);
  }

  for (const [topic, labelled] of messages) {
    if (!topic.endsWith("/ground")) continue;
    const input = messages.get(topic.slice(0, -"/ground".length));
    if (!input) {
      fail(`${path}: ${topic} has no input topic beside it`);
      continue;
    }
    if (input.length !== labelled.length)
      fail(`${path}: ${topic}: ${labelled.length} messages, its input has ${input.length}`);
    if (labelFiles && labelFiles.length !== labelled.length)
      fail(`${path}: ${topic}: ${labelled.length} messages, ${labelsDir} has ${labelFiles.length} .label files`);
    for (let k = 0; k < labelled.length; ++k) {
      const where = `${path}: ${topic} message ${k}`;
      const msg = labelled[k], src = input[k];
      if (!msg) continue;
      const label = msg.fields.find((f) => f.name === "label");
      if (!label || label.datatype !== UINT8 || label.count !== 1) {
        fail(`${where}: no uint8 label field`);
        continue;
      }
      const points = msg.width * msg.height;
      if (msg.data.length < msg.row_step * msg.height || msg.row_step < msg.width * msg.point_step ||
          label.offset + 1 > msg.point_step) {
        fail(`${where}: ${msg.data.length} data bytes do not hold ${points} points of ${msg.point_step} bytes`);
        continue;
      }
      const labels = Buffer.from(fieldBytes(msg, "label", 1), "hex");
      if (labels.length !== points) fail(`${where}: ${labels.length} labels for ${points} points`);
      const bad = labels.findIndex((v) => v > 1);
      if (bad >= 0) fail(`${where}: point ${bad} has label ${labels[bad]}, not 0 or 1`);
      if (labelFiles) {
        if (k >= labelFiles.length) {
          fail(`${where}: no .label file for it in ${labelsDir} (${labelFiles.length} there)`);
        } else {
          const file = readFileSync(join(labelsDir, labelFiles[k]));
          const want = new Uint32Array(file.buffer, file.byteOffset, Math.floor(file.length / 4));
          const differ = want.length !== labels.length ? 0 : want.findIndex((v, j) => v !== labels[j]);
          if (want.length !== labels.length)
            fail(`${where}: ${labels.length} labels, ${labelFiles[k]} has ${want.length}`);
          else if (differ >= 0)
            fail(`${where}: point ${differ} labelled ${labels[differ]}, ${labelFiles[k]} says ${want[differ]}`);
        }
      }
      if (!src) continue;
      if (src.width * src.height !== points)
        fail(`${where}: ${points} points, the input message has ${src.width * src.height}`);
      if (src.header.stamp.sec !== msg.header.stamp.sec || src.header.stamp.nanosec !== msg.header.stamp.nanosec)
        fail(`${where}: stamp differs from the input message's`);
      for (const axis of ["x", "y", "z"]) {
        const f = src.fields.find((g) => g.name === axis);
        const size = f && f.datatype === 8 ? 8 : 4;
        if (fieldBytes(src, axis, size) !== fieldBytes(msg, axis, size))
          fail(`${where}: field ${axis} differs from the input message's`);
      }
    }
  }
  if (problems.length) {
    for (const p of problems) console.error(`read_mcap: ${p}`);
    process.exit(1);
  }
  console.log(`read_mcap: ${path}: ${records} records, every check passed`);
}

main().catch((error) => {
  console.error(`read_mcap: ${process.argv[2]}: ${error.message}`);
  process.exit(1);
});
