// The other systems' messages SWA speaks, checked with an independent ROS 2 CDR implementation (@foxglove/rosmsg +
// @foxglove/rosmsg2-serialization, no code of SWA's) against the official definitions (issue #27):
//   node foreign_check.mjs CAPTURE.json UPSTREAM_DIR OUT.json
// 1. decodes every payload SWA serialised (tests/ros2/foreign_payloads.cpp write) and compares it field for field
//    with the values SWA set: vision_msgs, mrs_msgs and ArduPilot's messages completely, PX4's messages on the fields
//    the stand-in sets and zero everywhere else, each with upstream's own .msg/.srv texts as its definition
//    (UPSTREAM_DIR: tests/upstream, never a definition typed here);
// 2. serialises the same values of every payload but PX4's itself and writes them to OUT.json, for foreign_payloads
//    check to read as the agent, the bridge or the stand-in does.
// It first checks that it can fail: a Point definition with x and y swapped must not match; and that the decoder's
// built-in builtin_interfaces/Time (it reads stamps itself, not from a .msg) is upstream's Time.msg.
// Exit 0: everything matched; 1: a difference (each printed); 2: bad usage.

import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { parse } from "@foxglove/rosmsg";
import { MessageReader, MessageWriter } from "@foxglove/rosmsg2-serialization";

import { differences, fullDefinition, hexBytes } from "./ros_cdr.mjs";

const [capturePath, upstreamDir, outPath] = process.argv.slice(2);
if (!capturePath || !upstreamDir || !outPath) {
  console.error("usage: node foreign_check.mjs CAPTURE.json UPSTREAM_DIR OUT.json");
  process.exit(2);
}

// The definitions are upstream's own files (UPSTREAM_DIR = tests/upstream, each with its source in its README):
// <pkg>/msg/<Name>.msg, a service's halves from <pkg>/srv/<Service>.srv, PX4's px4_msgs/<tag>/<Name>.msg.
function upstreamText(full, tag) {
  const [pkg, name] = full.split("/").filter((part) => part !== "msg" && part !== "srv");
  if (pkg === "px4_msgs") return readFileSync(join(upstreamDir, "px4_msgs", tag, `${name}.msg`), "utf8");
  const half = name.match(/^(.*)_(Request|Response)$/);
  if (full.includes("/srv/") && half) {
    const [request, response] = readFileSync(join(upstreamDir, pkg, "srv", `${half[1]}.srv`), "utf8").split(/^---$/m);
    return half[2] === "Request" ? request : response;
  }
  return readFileSync(join(upstreamDir, pkg, "msg", `${name}.msg`), "utf8");
}
function definitionText(full, tag, overrides) {
  if (overrides && overrides[full] !== undefined) return overrides[full];
  return upstreamText(full, tag);
}

function fullDefinitionOf(rosType, tag, overrides) {
  return fullDefinition(rosType, (full) => definitionText(full, tag, overrides));
}

const hexOf = (bytes) => Buffer.from(bytes).toString("hex");

// The expected JSON as the writer takes it: 64-bit integers (strings in the JSON, which has no exact 64-bit number)
// as BigInt, found by the definition's field types.
function writable(value, definitions, definition = definitions[0]) {
  const out = {};
  for (const f of definition.definitions) {
    if (f.isConstant) continue;
    const one = (v) => f.isComplex ? writable(v, definitions, definitions.find((d) => d.name === f.type))
                                   : /int64$/.test(f.type) ? BigInt(v) : v;
    out[f.name] = f.isArray ? Array.from(value[f.name], one) : one(value[f.name]);
  }
  return out;
}

// PX4: the fields given must hold their values, every other one must be zero (false, 0, 0n, zeros).
function px4Differences(actual, expected, path) {
  const out = [];
  for (const key of Object.keys(expected)) {
    if (!(key in actual)) out.push(`${path}.${key}: not in the release's definition`);
  }
  for (const [key, value] of Object.entries(actual)) {
    if (key in expected) {
      differences(value, expected[key], `${path}.${key}`, out);
    } else {
      const zero = ArrayBuffer.isView(value) || Array.isArray(value) ? Array.from(value).every((v) => Number(v) === 0)
                                                                     : Number(value) === 0;
      if (!zero) out.push(`${path}.${key}: ${value}, expected zero`);
    }
  }
  return out;
}

function reader(entry, overrides) {
  return new MessageReader(parse(fullDefinitionOf(entry.ros_type, entry.px4_release, overrides), { ros2: true }));
}

const capture = JSON.parse(readFileSync(capturePath, "utf8"));

// The comparison can fail: with x and y of Point swapped, the detections must read differently.
const vision = capture.find((e) => e.ros_type === "vision_msgs/msg/Detection3DArray");
if (!vision) {
  console.error("foreign_check: no vision_msgs payload to check the comparison with");
  process.exit(1);
}
const swapped = { "geometry_msgs/Point": "float64 y\nfloat64 x\nfloat64 z\n" };
if (differences(reader(vision, swapped).readMessage(hexBytes(vision.cdr_hex)), vision.expected, "x", []).length === 0) {
  console.error("foreign_check: a Point with x and y swapped decoded to the same values: the check is blind");
  process.exit(1);
}

// Stamps: the decoder reads builtin_interfaces/Time as its own primitive (int32 sec, uint32 nanosec); upstream's
// Time.msg must say the same, or every header above would be checked against the decoder's belief.
const spelling = (f) => `${f.type}${f.isArray ? `[${f.arrayLength ?? ""}]` : ""} ${f.name}`;
const time = parse(upstreamText("builtin_interfaces/Time"), { ros2: true })[0].definitions
  .filter((f) => !f.isConstant).map(spelling).join(", ");
if (time !== "int32 sec, uint32 nanosec") {
  console.error(`foreign_check: upstream's builtin_interfaces/Time is '${time}', not the decoder's ` +
    "int32 sec, uint32 nanosec");
  process.exit(1);
}

let failures = 0;
const written = [];
for (const entry of capture) {
  const name = `${entry.ros_type}${entry.px4_release ? ` (PX4 ${entry.px4_release})` : ""}`;
  let found;
  try {
    const decoded = reader(entry).readMessage(hexBytes(entry.cdr_hex));
    found = entry.zero_elsewhere ? px4Differences(decoded, entry.expected, name)
                                 : differences(decoded, entry.expected, name, []);
  } catch (e) {
    found = [`${name}: does not decode: ${e.message}`];
  }
  if (found.length > 0) {
    failures += 1;
    console.error(`MISMATCH:\n  ${found.join("\n  ")}`);
  } else {
    console.log(`${name}: decoded field for field`);
  }
  if (!entry.px4_release) {
    const definitions = parse(fullDefinitionOf(entry.ros_type), { ros2: true });
    const writer = new MessageWriter(definitions);
    const bytes = writer.writeMessage(writable(entry.expected, definitions));
    written.push({ ros_type: entry.ros_type, cdr_hex: hexOf(bytes) });
  }
}
writeFileSync(outPath, JSON.stringify(written, null, 1));
console.log(`foreign_check: ${capture.length - failures} of ${capture.length} payloads decoded as the official ` +
  `definitions say; ${written.length} written for SWA to read`);
process.exit(failures === 0 ? 0 : 1);
