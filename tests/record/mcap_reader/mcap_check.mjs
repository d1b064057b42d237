// Reads an MCAP file written by SWA's own C++ MCAP writer with the reference MCAP implementation (@mcap/core, the
// library Foxglove Studio and the `mcap` tools are built on; no code of SWA's) and decodes every message
// independently (@foxglove/rosmsg + @foxglove/rosmsg2-serialization for ROS 2 CDR, JSON.parse + the channel's JSON
// Schema for JSON), so that a file our writer produces is known to open in the ecosystem's tools.
//
//   node mcap_check.mjs check FILE.mcap EXPECTED.json
//     EXPECTED.json: {"profile":"ros2","channels":{"/swa/uav0/imu":{"schema":"swa_msgs/msg/Imu",
//       "schema_encoding":"ros2msg","message_encoding":"cdr","messages":1234}, ...}}
//     Opens FILE with McapIndexedReader (it must be chunked, indexed and carry a Statistics record) and checks the
//     header's profile, the channel set and each channel's schema name, schema encoding and message encoding, each
//     channel's message count three ways (the Statistics record, readMessages() through the chunk and message
//     indexes, and a McapStreamReader pass over the data section) and that every message decodes. Messages out of
//     logTime order within a channel (in file order) are reported as a note, not a failure.
//     Each failure is one line "mcap_check: <what>" on stderr; stdout gets one JSON line
//     {"channels":N,"schemas":N,"messages":N,"decoded_cdr":N,"json":N,"chunks":N}.
//     Exit 0: no failure; 1: at least one failure (all reported); 2: usage or an unreadable EXPECTED.json.
//
//   node mcap_check.mjs recover FILE.mcap
//     For the file of a writer that crashed (no summary, no footer, maybe half a chunk at the end): reads it with
//     McapStreamReader as far as it goes and prints {"messages":N,"channels":{"topic":count,...},
//     "complete_chunks":K,"unparsed_bytes":B,"error":"<what the reader threw, or null>"}.
//     A record cut off by the end of the file is not an error for McapStreamReader (nextRecord() just returns
//     undefined): it shows as unparsed_bytes > 0 with error null.
//     Exit 0; 1 only if FILE does not start with the MCAP magic and a Header record.
//
// Chunks must be uncompressed (compression ""): no decompressor is installed, and a compressed chunk is reported.

import { open } from "node:fs/promises";
import { readFileSync } from "node:fs";
import { McapIndexedReader, McapStreamReader, hasMcapPrefix } from "@mcap/core";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";

const USAGE = "usage: node mcap_check.mjs check FILE.mcap EXPECTED.json\n" +
  "       node mcap_check.mjs recover FILE.mcap";
const [mode, mcapPath, expectedPath] = process.argv.slice(2);
if (!((mode === "check" && mcapPath && expectedPath) || (mode === "recover" && mcapPath))) {
  console.error(USAGE);
  process.exit(2);
}

const failures = [];
const fail = (what) => {
  failures.push(what);
  console.error(`mcap_check: ${what}`);
};
const note = (what) => console.error(`mcap_check: note: ${what}`);
const errorText = (e) => (e instanceof Error ? e.message : String(e));

// @mcap/core's IReadable over a Node FileHandle: size() resolves to a bigint, read(offset, size) with bigints to
// exactly `size` bytes (a short read is an error, not a shorter buffer).
function fileReadable(handle) {
  return {
    async size() {
      return BigInt((await handle.stat()).size);
    },
    async read(offset, size) {
      if (offset + size > BigInt(Number.MAX_SAFE_INTEGER)) throw new Error(`read beyond 2^53 bytes at ${offset}`);
      const buffer = new Uint8Array(Number(size));
      let done = 0;
      while (done < buffer.byteLength) {
        const { bytesRead } = await handle.read(buffer, done, buffer.byteLength - done, Number(offset) + done);
        if (bytesRead === 0) throw new Error(`file ends before ${offset + size} (read ${size} bytes at ${offset})`);
        done += bytesRead;
      }
      return buffer;
    },
  };
}

// Feeds the whole file to a McapStreamReader in 4 MiB pieces and calls onRecord for each record it returns (chunks
// included: the Chunk record first, then the records inside it). Returns {reader, error}: error is what nextRecord()
// threw (the reader stops there), or null.
async function streamRecords(handle, onRecord) {
  const reader = new McapStreamReader({ includeChunks: true, validateCrcs: true });
  const size = (await handle.stat()).size;
  const piece = new Uint8Array(4 << 20);
  try {
    for (let position = 0; position < size && !reader.done(); ) {
      const { bytesRead } = await handle.read(piece, 0, Math.min(piece.byteLength, size - position), position);
      if (bytesRead === 0) break;
      position += bytesRead;
      reader.append(piece.subarray(0, bytesRead));
      for (let record; (record = reader.nextRecord()); ) onRecord(record);
    }
  } catch (e) {
    return { reader, error: errorText(e) };
  }
  return { reader, error: null };
}

// The concatenated ROS 2 definition of a ros2msg schema, parsed; throws with the reason if it does not parse.
function ros2Reader(schema) {
  return new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true }));
}

// Decodes one CDR payload; returns null if it decodes, else why not. CDR ignores trailing bytes, so the decode must
// end at the payload's end, except for up to 3 zero bytes that pad the payload to a multiple of 4 (Fast DDS does so).
function cdrProblem(reader, data) {
  try {
    reader.readMessage(data);
  } catch (e) {
    return `throws: ${errorText(e)}`;
  }
  const used = reader.lastReadByteLength();
  const rest = data.subarray(used);
  if (rest.byteLength === 0 || (rest.byteLength < 4 && data.byteLength % 4 === 0 && rest.every((b) => b === 0))) {
    return null;
  }
  return `decodes ${used} of its ${data.byteLength} bytes`;
}

// The JSON Schema of a jsonschema schema: an object schema with properties and required.
function jsonSchemaOf(schema) {
  const value = JSON.parse(new TextDecoder().decode(schema.data));
  if (value === null || typeof value !== "object" || value.type !== "object") {
    throw new Error('not a JSON Schema with "type":"object"');
  }
  if (value.properties !== undefined && (value.properties === null || typeof value.properties !== "object")) {
    throw new Error('"properties" is not an object');
  }
  if (value.required !== undefined && !Array.isArray(value.required)) throw new Error('"required" is not an array');
  return { properties: value.properties ?? {}, required: value.required ?? [] };
}

const JSON_TYPES = {
  number: (v) => typeof v === "number",
  integer: (v) => Number.isInteger(v),
  string: (v) => typeof v === "string",
  boolean: (v) => typeof v === "boolean",
  array: (v) => Array.isArray(v),
  object: (v) => v !== null && typeof v === "object" && !Array.isArray(v),
  null: (v) => v === null,
};

// Returns null if the JSON message text satisfies the schema's required and top-level types, else why not.
function jsonProblem(schema, data) {
  let value;
  try {
    value = JSON.parse(new TextDecoder("utf-8", { fatal: true }).decode(data));
  } catch (e) {
    return `is not JSON: ${errorText(e)}`;
  }
  if (!JSON_TYPES.object(value)) return "is not a JSON object";
  const missing = schema.required.filter((key) => !(key in value));
  if (missing.length > 0) return `lacks required ${missing.join(", ")}`;
  for (const [key, property] of Object.entries(schema.properties)) {
    if (!(key in value) || property === null || typeof property !== "object" || property.type === undefined) continue;
    const types = [property.type].flat().filter((t) => JSON_TYPES[t] !== undefined);
    if (types.length > 0 && !types.some((t) => JSON_TYPES[t](value[key]))) {
      return `has ${key}=${JSON.stringify(value[key]).slice(0, 40)}, not of type ${types.join("|")}`;
    }
  }
  return null;
}

async function check() {
  let expected;
  try {
    expected = JSON.parse(readFileSync(expectedPath, "utf8"));
    if (typeof expected.profile !== "string" || expected.channels === null || typeof expected.channels !== "object") {
      throw new Error('needs "profile" (a string) and "channels" (an object)');
    }
  } catch (e) {
    console.error(`mcap_check: cannot use ${expectedPath}: ${errorText(e)}`);
    process.exit(2);
  }

  const handle = await open(mcapPath, "r");
  let reader;
  try {
    reader = await McapIndexedReader.Initialize({ readable: fileReadable(handle) });
  } catch (e) {
    fail(`${mcapPath} does not open as an indexed MCAP file: ${errorText(e)}`);
    process.exit(1);
  }

  if (reader.header.profile !== expected.profile) {
    fail(`header profile is "${reader.header.profile}", expected "${expected.profile}"`);
  }
  if (reader.chunkIndexes.length === 0) fail("the summary has no chunk indexes (the file is not chunked and indexed)");
  const stats = reader.statistics;
  if (!stats) fail("the summary has no Statistics record");
  const compressed = reader.chunkIndexes.filter((chunk) => chunk.compression !== "");
  if (compressed.length > 0) {
    fail(`${compressed.length} of ${reader.chunkIndexes.length} chunk(s) are compressed (first at ` +
      `${compressed[0].chunkStartOffset}: "${compressed[0].compression}"); only "" is readable here`);
  }
  const unindexed = reader.chunkIndexes.filter((chunk) => chunk.messageIndexOffsets.size === 0);
  if (unindexed.length > 0) {
    fail(`${unindexed.length} of ${reader.chunkIndexes.length} chunk(s) have no message indexes (first at ` +
      `${unindexed[0].chunkStartOffset})`);
  }

  // Channels and their schemas against EXPECTED.
  const channelByTopic = new Map();
  for (const channel of reader.channelsById.values()) {
    if (channelByTopic.has(channel.topic)) fail(`topic ${channel.topic} has two channels`);
    channelByTopic.set(channel.topic, channel);
  }
  const expectedTopics = Object.keys(expected.channels);
  const missing = expectedTopics.filter((t) => !channelByTopic.has(t));
  const unexpected = [...channelByTopic.keys()].filter((t) => !(t in expected.channels));
  if (missing.length > 0) fail(`missing channel(s): ${missing.sort().join(", ")}`);
  if (unexpected.length > 0) fail(`unexpected channel(s): ${unexpected.sort().join(", ")}`);

  for (const [topic, want] of Object.entries(expected.channels)) {
    const channel = channelByTopic.get(topic);
    if (!channel) continue;
    const schema = reader.schemasById.get(channel.schemaId);
    const schemaName = schema?.name ?? "";
    const schemaEncoding = schema?.encoding ?? "";
    if (schemaName !== want.schema) fail(`channel ${topic}: schema "${schemaName}", expected "${want.schema}"`);
    if (schemaEncoding !== want.schema_encoding) {
      fail(`channel ${topic}: schema encoding "${schemaEncoding}", expected "${want.schema_encoding}"`);
    }
    if (channel.messageEncoding !== want.message_encoding) {
      fail(`channel ${topic}: message encoding "${channel.messageEncoding}", expected "${want.message_encoding}"`);
    }
  }

  // Per channel id of every channel in the file, expected or not: how to decode its messages ({kind, problem}, with
  // problem(data) null or what is wrong), or null if it cannot be.
  const decoders = new Map();
  for (const channel of reader.channelsById.values()) {
    const topic = channel.topic;
    const schema = reader.schemasById.get(channel.schemaId);
    const schemaName = schema?.name ?? "";
    const schemaEncoding = schema?.encoding ?? "";
    if (channel.schemaId !== 0 && !schema) fail(`channel ${topic}: schema id ${channel.schemaId} is not in the summary`);
    let decoder = null;
    if (channel.messageEncoding === "cdr" && schemaEncoding === "ros2msg") {
      try {
        const messageReader = ros2Reader(schema);
        decoder = { kind: "cdr", problem: (data) => cdrProblem(messageReader, data) };
      } catch (e) {
        fail(`channel ${topic}: schema ${schemaName} does not parse as a ROS 2 definition: ${errorText(e)}`);
      }
    } else if (channel.messageEncoding === "json" && schemaEncoding === "jsonschema") {
      try {
        const jsonSchema = jsonSchemaOf(schema);
        decoder = { kind: "json", problem: (data) => jsonProblem(jsonSchema, data) };
      } catch (e) {
        fail(`channel ${topic}: schema ${schemaName} is not a usable JSON Schema: ${errorText(e)}`);
      }
    } else {
      fail(`channel ${topic}: no independent decoder for message encoding "${channel.messageEncoding}" with ` +
        `schema encoding "${schemaEncoding}"`);
    }
    decoders.set(channel.id, decoder);
  }

  // Every message through the indexes: count, decode.
  const indexed = new Map(); // channel id -> {count, bad, firstProblem}
  let decodedCdr = 0;
  let validJson = 0;
  let total = 0;
  try {
    for await (const message of reader.readMessages()) {
      total += 1;
      const entry = indexed.get(message.channelId) ?? { count: 0, bad: 0, firstProblem: null };
      indexed.set(message.channelId, entry);
      entry.count += 1;
      const decoder = decoders.get(message.channelId);
      if (!decoder) continue;
      const problem = decoder.problem(message.data);
      if (problem === null) {
        if (decoder.kind === "cdr") decodedCdr += 1;
        else validJson += 1;
      } else {
        entry.bad += 1;
        entry.firstProblem ??= `log time ${message.logTime} ${problem}`;
      }
    }
  } catch (e) {
    fail(`readMessages() stopped after ${total} message(s): ${errorText(e)}`);
  }
  for (const [channelId, entry] of indexed) {
    if (entry.bad > 0) {
      const topic = reader.channelsById.get(channelId)?.topic ?? `#${channelId}`;
      fail(`channel ${topic}: ${entry.bad} of ${entry.count} message(s) do not decode (first: ${entry.firstProblem})`);
    }
  }
  for (const channelId of indexed.keys()) {
    if (!reader.channelsById.has(channelId)) fail(`readMessages() returned messages of unknown channel id ${channelId}`);
  }

  // The data section in file order: per channel counts and logTime order.
  const streamed = new Map(); // channel id -> {count, lastLogTime, outOfOrder}
  let streamedChunks = 0;
  const { reader: streamReader, error: streamError } = await streamRecords(handle, (record) => {
    if (record.type === "Chunk") streamedChunks += 1;
    if (record.type !== "Message") return;
    const entry = streamed.get(record.channelId) ?? { count: 0, lastLogTime: null, outOfOrder: 0 };
    streamed.set(record.channelId, entry);
    entry.count += 1;
    if (entry.lastLogTime !== null && record.logTime < entry.lastLogTime) entry.outOfOrder += 1;
    entry.lastLogTime = record.logTime;
  });
  if (streamError !== null) fail(`McapStreamReader fails on the file: ${streamError}`);
  else if (!streamReader.done()) fail("McapStreamReader did not reach the footer and closing magic");
  if (streamError === null && streamedChunks !== reader.chunkIndexes.length) {
    fail(`the data section has ${streamedChunks} chunk(s), the summary indexes ${reader.chunkIndexes.length}`);
  }

  // Counts: Statistics, readMessages() and the data section each against EXPECTED.
  for (const [topic, want] of Object.entries(expected.channels)) {
    const channel = channelByTopic.get(topic);
    if (!channel) continue;
    const counts = [
      ["the Statistics record", stats ? Number(stats.channelMessageCounts.get(channel.id) ?? 0n) : null],
      ["readMessages()", indexed.get(channel.id)?.count ?? 0],
      ["the data section", streamError === null ? streamed.get(channel.id)?.count ?? 0 : null],
    ];
    for (const [where, count] of counts) {
      if (count !== null && count !== want.messages) {
        fail(`channel ${topic}: ${where} counts ${count} message(s), expected ${want.messages}`);
      }
    }
    const outOfOrder = streamed.get(channel.id)?.outOfOrder ?? 0;
    if (outOfOrder > 0) note(`channel ${topic}: ${outOfOrder} message(s) with a logTime earlier than the one before`);
  }
  if (stats) {
    const sum = [...stats.channelMessageCounts.values()].reduce((a, b) => a + b, 0n);
    if (stats.messageCount !== sum) fail(`Statistics: messageCount ${stats.messageCount}, channel counts sum to ${sum}`);
    if (stats.messageCount !== BigInt(total)) {
      fail(`Statistics: messageCount ${stats.messageCount}, readMessages() returned ${total}`);
    }
    if (stats.chunkCount !== reader.chunkIndexes.length) {
      fail(`Statistics: chunkCount ${stats.chunkCount}, the summary indexes ${reader.chunkIndexes.length} chunk(s)`);
    }
    if (stats.channelCount !== reader.channelsById.size) {
      fail(`Statistics: channelCount ${stats.channelCount}, the summary has ${reader.channelsById.size} channel(s)`);
    }
    if (stats.schemaCount !== reader.schemasById.size) {
      fail(`Statistics: schemaCount ${stats.schemaCount}, the summary has ${reader.schemasById.size} schema(s)`);
    }
  }
  await handle.close();

  console.log(JSON.stringify({
    channels: reader.channelsById.size,
    schemas: reader.schemasById.size,
    messages: total,
    decoded_cdr: decodedCdr,
    json: validJson,
    chunks: reader.chunkIndexes.length,
  }));
  process.exit(failures.length === 0 ? 0 : 1);
}

async function recover() {
  const handle = await open(mcapPath, "r");
  const prefix = new Uint8Array(8);
  const { bytesRead } = await handle.read(prefix, 0, 8, 0);
  if (!hasMcapPrefix(new DataView(prefix.buffer, 0, bytesRead))) {
    console.error(`mcap_check: ${mcapPath} does not start with the MCAP magic`);
    process.exit(1);
  }

  const topics = new Map(); // channel id -> topic
  const counts = new Map(); // topic -> messages
  let messages = 0;
  let first = null;
  let completeChunks = 0;
  let openChunk = false; // a Chunk record was returned, and none of its contents has failed yet
  const { reader, error } = await streamRecords(handle, (record) => {
    first ??= record.type;
    // The records of a chunk follow its Chunk record; a later record that cannot be inside a chunk, or the next Chunk,
    // means the previous one was read to its end.
    if (openChunk && !["Schema", "Channel", "Message", "Unknown"].includes(record.type)) {
      completeChunks += 1;
      openChunk = false;
    }
    if (record.type === "Chunk") openChunk = true;
    else if (record.type === "Channel") topics.set(record.id, record.topic);
    else if (record.type === "Message") {
      const topic = topics.get(record.channelId) ?? `#${record.channelId}`;
      counts.set(topic, (counts.get(topic) ?? 0) + 1);
      messages += 1;
    }
  });
  if (openChunk && error === null) completeChunks += 1;
  await handle.close();
  if (first !== "Header") {
    console.error(`mcap_check: ${mcapPath} has no Header record after the magic` + (error ? ` (${error})` : ""));
    process.exit(1);
  }

  console.log(JSON.stringify({
    messages,
    channels: Object.fromEntries([...counts].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0))),
    complete_chunks: completeChunks,
    unparsed_bytes: reader.bytesRemaining(),
    error,
  }));
  process.exit(0);
}

await (mode === "check" ? check() : recover());
