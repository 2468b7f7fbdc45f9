// Reads an MCAP file with @mcap/core (not lpir-gseg's code) and checks it, for the output of
// `lpir-gseg segment --format mcap`: first a McapStreamReader pass over every record (chunk CRCs
// validated) to the footer, then the summary through McapIndexedReader, then every message. The
// file must be indexed (chunked, with chunk indexes in its summary), as lpir-gseg's writer and
// ROS 2's recorder make them: McapIndexedReader reads nothing else.
// Prints one line per channel: topic, schema name, message encoding, message count.
//
// usage: node read_mcap.mjs FILE.mcap [--input IN.mcap] [--expect TOPIC:COUNT]... [--labels DIR]
//   --input IN.mcap  every channel of IN is in FILE: the same topic, schema (name, encoding, data),
//                    message encoding and metadata, and the same messages (sequence, log time,
//                    publish time, bytes) in the same order; and IN's metadata records and
//                    attachments are in FILE, equal.
//   --expect T:N     topic T has N messages.
//   --labels DIR     the .label files of `lpir-gseg segment` (uint32 per point, in natural name
//                    order): the k-th labelled message's labels equal the k-th file's values.
// For every topic T that has T/labelled, T/ground and T/nonground beside it (PointCloud2, decoded
// from the channel's schema: CDR by @foxglove/rosmsg2-serialization, ROS 1 by
// @foxglove/rosmsg-serialization), message k of each, against T's message k:
//   - each of the three: point_step a multiple of 4, every field's offset and point_step a
//     multiple of the field's size, data exactly row_step x height with row_step = width x
//     point_step, the same stamp and frame_id as T's;
//   - T/labelled: T's width and height, T's fields and a uint32 `label` (count 1) whose values
//     are 0 or 1, every field's bytes of every point equal to T's;
//   - T/ground: height 1, the points of T/labelled whose label is 1, in order, every field's bytes
//     equal; T/nonground the same for label 0.
// Exits 1, naming the message and the problem, on any failure.
import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageReader as Ros1Reader } from "@foxglove/rosmsg-serialization";
import { MessageReader as CdrReader } from "@foxglove/rosmsg2-serialization";
import * as zstd from "@foxglove/wasm-zstd";
import lz4 from "@foxglove/wasm-lz4";

const UINT32 = 6;
const SIZES = [0, 1, 1, 2, 2, 4, 4, 4, 8];  // by PointField datatype
const SUFFIXES = ["/labelled", "/ground", "/nonground"];
const problems = [];
const fail = (text) => problems.push(text);

function decompressHandlers() {
  return {
    zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
    lz4: (buffer, size) => lz4(buffer, Number(size)),
  };
}

// The file's channels (with schemas), messages by topic (raw records), metadata and attachments.
async function load(path) {
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
  const topics = new Map();  // topic -> { channel, schema, messages: [] }
  for (const channel of reader.channelsById.values())
    topics.set(channel.topic, { channel, schema: reader.schemasById.get(channel.schemaId), messages: [] });
  for await (const message of reader.readMessages({ validateCrcs: true }))
    topics.get(reader.channelsById.get(message.channelId).topic).messages.push(message);
  const metadata = [];
  for await (const m of reader.readMetadata()) metadata.push(m);
  const attachments = [];
  for await (const a of reader.readAttachments()) attachments.push(a);
  for (const [id, channel] of reader.channelsById) {
    const stat = reader.statistics?.channelMessageCounts.get(id);
    const count = topics.get(channel.topic).messages.length;
    if (stat !== undefined && stat !== BigInt(count))
      fail(`${path}: ${channel.topic}: statistics say ${stat} messages, the file holds ${count}`);
  }
  return { records, topics, metadata, attachments };
}

const hex = (data) => Buffer.from(data.buffer, data.byteOffset, data.byteLength).toString("hex");
const mapText = (map) => JSON.stringify([...map.entries()]);

// Every channel, message, metadata record and attachment of `input` is in `output`, equal.
function compareWithInput(path, output, inputPath, input) {
  for (const [topic, want] of input.topics) {
    const got = output.topics.get(topic);
    if (!got) {
      fail(`${path}: ${inputPath}'s topic ${topic} is missing`);
      continue;
    }
    const ws = want.schema, gs = got.schema;
    if (ws?.name !== gs?.name || ws?.encoding !== gs?.encoding ||
        (ws && hex(ws.data) !== hex(gs.data)))
      fail(`${path}: ${topic}: schema differs from the input's`);
    if (want.channel.messageEncoding !== got.channel.messageEncoding)
      fail(`${path}: ${topic}: message encoding ${got.channel.messageEncoding}, the input's ${want.channel.messageEncoding}`);
    if (mapText(want.channel.metadata) !== mapText(got.channel.metadata))
      fail(`${path}: ${topic}: channel metadata ${mapText(got.channel.metadata)}, the input's ${mapText(want.channel.metadata)}`);
    if (want.messages.length !== got.messages.length) {
      fail(`${path}: ${topic}: ${got.messages.length} messages, the input has ${want.messages.length}`);
      continue;
    }
    for (let k = 0; k < want.messages.length; ++k) {
      const w = want.messages[k], g = got.messages[k];
      if (w.sequence !== g.sequence || w.logTime !== g.logTime || w.publishTime !== g.publishTime ||
          hex(w.data) !== hex(g.data))
        fail(`${path}: ${topic} message ${k} differs from the input's (sequence, times or bytes)`);
    }
  }
  const metaKey = (m) => `${m.name} ${mapText(m.metadata)}`;
  const outMeta = new Set(output.metadata.map(metaKey));
  for (const m of input.metadata)
    if (!outMeta.has(metaKey(m))) fail(`${path}: the input's metadata record ${m.name} is missing`);
  const attKey = (a) => `${a.name} ${a.mediaType} ${a.logTime} ${a.createTime} ${hex(a.data)}`;
  const outAtt = new Set(output.attachments.map(attKey));
  for (const a of input.attachments)
    if (!outAtt.has(attKey(a))) fail(`${path}: the input's attachment ${a.name} is missing or differs`);
}

// A decoder of the topic's messages (PointCloud2 in CDR or ROS 1), or null.
function decoder(entry) {
  const { schema, channel } = entry;
  if (!schema || !schema.name.endsWith("PointCloud2")) return null;
  const text = new TextDecoder().decode(schema.data);
  if (channel.messageEncoding === "cdr") return new CdrReader(parse(text, { ros2: true }));
  if (channel.messageEncoding === "ros1") return new Ros1Reader(parse(text));
  return null;
}

const nanosec = (stamp) => stamp.nanosec ?? stamp.nsec;

// Field `f`'s bytes of point i (row-major) of a decoded PointCloud2.
function fieldBytes(msg, f, i) {
  const at = Math.floor(i / msg.width) * msg.row_step + (i % msg.width) * msg.point_step + f.offset;
  return Buffer.from(msg.data.buffer, msg.data.byteOffset + at, SIZES[f.datatype] * f.count).toString("hex");
}

// The layout every added cloud must have; "" when it has it.
function layoutProblem(msg) {
  if (msg.point_step % 4 !== 0) return `point_step ${msg.point_step} is not a multiple of 4`;
  for (const f of msg.fields) {
    const size = SIZES[f.datatype] ?? 0;
    if (!size || f.offset % size !== 0 || msg.point_step % size !== 0)
      return `field ${f.name} (offset ${f.offset}, datatype ${f.datatype}) is not aligned`;
  }
  if (msg.row_step !== msg.width * msg.point_step || msg.data.length !== msg.row_step * msg.height)
    return `${msg.data.length} data bytes for ${msg.height} rows of ${msg.width} x ${msg.point_step}`;
  return "";
}

function checkClouds(path, topic, output, labelFiles, labelsDir) {
  const entries = [topic, ...SUFFIXES.map((s) => topic + s)].map((t) => output.topics.get(t));
  const decoders = entries.map(decoder);
  if (decoders.some((d) => !d)) {
    fail(`${path}: ${topic} and its three clouds are not all decodable PointCloud2 topics`);
    return;
  }
  const count = entries[0].messages.length;
  for (const e of entries.slice(1))
    if (e.messages.length !== count)
      fail(`${path}: ${e.channel.topic}: ${e.messages.length} messages, ${topic} has ${count}`);
  if (labelFiles && labelFiles.length !== entries[1].messages.length)
    fail(`${path}: ${topic}/labelled: ${entries[1].messages.length} messages, ${labelsDir} has ${labelFiles.length} .label files`);
  for (let k = 0; k < Math.min(...entries.map((e) => e.messages.length)); ++k) {
    const [src, labelled, ground, nonground] =
        entries.map((e, j) => decoders[j].readMessage(e.messages[k].data));
    const where = `${path}: ${topic} message ${k}`;
    for (const [name, msg] of [["labelled", labelled], ["ground", ground], ["nonground", nonground]]) {
      const problem = layoutProblem(msg);
      if (problem) fail(`${where}: ${name}: ${problem}`);
      if (msg.header.stamp.sec !== src.header.stamp.sec ||
          nanosec(msg.header.stamp) !== nanosec(src.header.stamp) || msg.header.frame_id !== src.header.frame_id)
        fail(`${where}: ${name}: header differs from the input message's`);
    }
    const label = labelled.fields.find((f) => f.name === "label");
    if (!label || label.datatype !== UINT32 || label.count !== 1) {
      fail(`${where}: labelled: no uint32 label field`);
      continue;
    }
    const points = src.width * src.height;
    if (labelled.width !== src.width || labelled.height !== src.height)
      fail(`${where}: labelled is ${labelled.width} x ${labelled.height}, the input ${src.width} x ${src.height}`);
    if (ground.height !== 1 || nonground.height !== 1 || ground.width + nonground.width !== points)
      fail(`${where}: ground ${ground.width} + nonground ${nonground.width} points, the input has ${points}`);
    const labels = [];
    for (let i = 0; i < points; ++i) {
      const b = Buffer.from(fieldBytes(labelled, label, i), "hex");
      labels.push(labelled.is_bigendian ? b.readUInt32BE(0) : b.readUInt32LE(0));
    }
    const bad = labels.findIndex((v) => v > 1);
    if (bad >= 0) fail(`${where}: point ${bad} has label ${labels[bad]}, not 0 or 1`);
    const next = [0, 0];  // the next nonground, ground point
    const parts = [nonground, ground];
    let differ = 0;
    for (const f of src.fields) {
      const byName = (msg) => msg.fields.find((g) => g.name === f.name);
      const lf = byName(labelled), pf = [byName(nonground), byName(ground)];
      if (!lf || !pf[0] || !pf[1] || lf.datatype !== f.datatype || lf.count !== f.count) {
        fail(`${where}: field ${f.name} is not in the three clouds as the input has it`);
        continue;
      }
      next[0] = next[1] = 0;
      for (let i = 0; i < points; ++i) {
        const bytes = fieldBytes(src, f, i);
        if (fieldBytes(labelled, lf, i) !== bytes) ++differ;
        const side = labels[i] === 1 ? 1 : 0;
        if (next[side] >= parts[side].width || fieldBytes(parts[side], pf[side], next[side]) !== bytes)
          ++differ;
        ++next[side];
      }
    }
    if (differ) fail(`${where}: ${differ} field values differ from the input's or the split's`);
    if (labelFiles && k < labelFiles.length) {
      const file = readFileSync(join(labelsDir, labelFiles[k]));
      const want = new Uint32Array(file.buffer, file.byteOffset, Math.floor(file.length / 4));
      const at = want.length !== labels.length ? 0 : want.findIndex((v, j) => v !== labels[j]);
      if (want.length !== labels.length)
        fail(`${where}: ${labels.length} labels, ${labelFiles[k]} has ${want.length}`);
      else if (at >= 0)
        fail(`${where}: point ${at} labelled ${labels[at]}, ${labelFiles[k]} says ${want[at]}`);
    }
  }
}

async function main() {
  const args = process.argv.slice(2);
  let path, inputPath, labelsDir;
  const expect = [];
  for (let i = 0; i < args.length; ++i) {
    if (args[i] === "--expect") {
      const [topic, count] = (args[++i] ?? "").split(/:(?=[0-9]+$)/);
      expect.push({ topic, count: Number(count) });
    } else if (args[i] === "--labels") {
      labelsDir = args[++i];
    } else if (args[i] === "--input") {
      inputPath = args[++i];
    } else {
      path = args[i];
    }
  }
  if (!path) throw new Error("usage: read_mcap.mjs FILE.mcap [--input IN.mcap] [--expect TOPIC:COUNT]... [--labels DIR]");
  const labelFiles = labelsDir === undefined ? undefined :
      readdirSync(labelsDir).filter((n) => n.endsWith(".label"))
          .sort((a, b) => a.localeCompare(b, "en", { numeric: true }));
  await zstd.isLoaded;
  await lz4.isLoaded;
  const output = await load(path);
  for (const [topic, e] of output.topics)
    console.log(`${topic} ${e.schema?.name ?? "(no schema)"} ${e.channel.messageEncoding} ${e.messages.length}`);
  if (inputPath) compareWithInput(path, output, inputPath, await load(inputPath));
  for (const { topic, count } of expect) {
    const got = output.topics.get(topic)?.messages.length;
    if (got !== count) fail(`${path}: ${topic}: expected ${count} messages, found ${got ?? "no such topic"}`);
  }
  let checked = 0;
  for (const topic of output.topics.keys())
    if (SUFFIXES.every((s) => output.topics.has(topic + s))) {
      checkClouds(path, topic, output, labelFiles, labelsDir);
      ++checked;
    }
  if (labelsDir !== undefined && checked === 0)
    fail(`${path}: no topic T with T/labelled, T/ground and T/nonground to compare with ${labelsDir}`);
  if (problems.length) {
    for (const p of problems) console.error(`read_mcap: ${p}`);
    process.exit(1);
  }
  console.log(`read_mcap: ${path}: ${output.records} records, every check passed`);
}

main().catch((error) => {
  console.error(`read_mcap: ${process.argv[2]}: ${error.message}`);
  process.exit(1);
});
