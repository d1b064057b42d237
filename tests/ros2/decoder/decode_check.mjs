// Decodes every payload of a capture (tests/ros2/test_ros2_profile.cpp writes it) with an independent ROS 2 CDR
// implementation (@foxglove/rosmsg + @foxglove/rosmsg2-serialization, no code of SWA's) against the .msg files of
// idl/swa_msgs, and compares the result field by field with what Fast DDS's generated code decoded.
//   node decode_check.mjs CAPTURE.json MSG_DIR
// Exit 0: every payload decoded to exactly the expected fields and values; 1: a difference (each one printed).
// It first checks that it can fail: a definition with two fields swapped must not match.

import { readFileSync, existsSync } from "node:fs";
import { join } from "node:path";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";

const [capturePath, msgDir] = process.argv.slice(2);
if (!capturePath || !msgDir) {
  console.error("usage: node decode_check.mjs CAPTURE.json MSG_DIR");
  process.exit(2);
}

// ROS 2's own definitions of the standard types SWA also publishes (common_interfaces, geometry_msgs and std_msgs).
const STANDARD = {
  "geometry_msgs/TwistStamped": "std_msgs/Header header\nTwist twist\n",
  "geometry_msgs/Twist": "Vector3 linear\nVector3 angular\n",
  "geometry_msgs/Vector3": "float64 x\nfloat64 y\nfloat64 z\n",
  "std_msgs/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
};
const PRIMITIVES = new Set(["bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16",
  "int32", "uint32", "int64", "uint64", "string", "wstring", "builtin_interfaces/Time", "builtin_interfaces/Duration"]);

// The text of pkg/Name ("swa_msgs/Imu"): a .msg file of MSG_DIR for swa_msgs, the standard text otherwise.
function definitionText(full, overrides) {
  if (overrides && overrides[full] !== undefined) return overrides[full];
  if (STANDARD[full] !== undefined) return STANDARD[full];
  const [pkg, name] = full.split("/");
  const file = join(msgDir, `${name}.msg`);
  if (pkg !== "swa_msgs" || !existsSync(file)) throw new Error(`no definition of ${full}`);
  return readFileSync(file, "utf8");
}

// The complex types a definition uses, as pkg/Name (a bare name is of the same package).
function dependencies(text, pkg) {
  const deps = [];
  for (const raw of text.split("\n")) {
    const line = raw.replace(/#.*/, "").trim();
    if (!line || line.includes("=")) continue;
    const type = line.split(/\s+/)[0].replace(/\[.*\]$/, "");
    if (PRIMITIVES.has(type)) continue;
    deps.push(type.includes("/") ? type.replace("/msg/", "/") : `${pkg}/${type}`);
  }
  return deps;
}

// The full definition of a ROS type in the concatenated form rosbag2 and MCAP use: the type, then each dependency
// after a separator line and "MSG: pkg/Name".
function fullDefinition(rosType, overrides) {
  const root = rosType.replace("/msg/", "/");
  const order = [];
  const seen = new Set();
  const visit = (full) => {
    if (seen.has(full)) return;
    seen.add(full);
    order.push(full);
    for (const dep of dependencies(definitionText(full, overrides), full.split("/")[0])) visit(dep);
  };
  visit(root);
  return order
    .map((full, k) => (k === 0 ? "" : `${"=".repeat(80)}\nMSG: ${full}\n`) + definitionText(full, overrides))
    .join("\n");
}

function hexBytes(hex) {
  return Uint8Array.from(hex.match(/../g).map((h) => parseInt(h, 16)));
}

// Every difference between the decoded value and the expected JSON (64-bit integers are strings there).
function differences(actual, expected, path, out) {
  if (typeof actual === "bigint") {
    if (String(actual) !== String(expected)) out.push(`${path}: ${actual} != ${expected}`);
  } else if (ArrayBuffer.isView(actual) || Array.isArray(actual)) {
    const a = Array.from(actual);
    if (!Array.isArray(expected) || a.length !== expected.length) {
      out.push(`${path}: ${a.length} elements, expected ${Array.isArray(expected) ? expected.length : "none"}`);
      return out;
    }
    a.forEach((v, k) => differences(v, expected[k], `${path}[${k}]`, out));
  } else if (actual !== null && typeof actual === "object") {
    if (expected === null || typeof expected !== "object") {
      out.push(`${path}: an object, expected ${JSON.stringify(expected)}`);
      return out;
    }
    const keys = new Set([...Object.keys(actual), ...Object.keys(expected)]);
    for (const key of keys) {
      if (!(key in actual)) out.push(`${path}.${key}: missing in the decoded message`);
      else if (!(key in expected)) out.push(`${path}.${key}: decoded but not expected`);
      else differences(actual[key], expected[key], `${path}.${key}`, out);
    }
  } else if (actual !== expected) {
    out.push(`${path}: ${JSON.stringify(actual)} != ${JSON.stringify(expected)}`);
  }
  return out;
}

function decode(entry, overrides) {
  const reader = new MessageReader(parse(fullDefinition(entry.ros_type, overrides), { ros2: true }));
  return reader.readMessage(hexBytes(entry.cdr_hex));
}

const capture = JSON.parse(readFileSync(capturePath, "utf8"));

// The comparison can fail: Imu decoded with roll and pitch swapped in its definition must differ.
const imu = capture.find((e) => e.ros_type === "swa_msgs/msg/Imu" && e.expected.roll_rad !== e.expected.pitch_rad);
if (!imu) {
  console.error("decode_check: no Imu payload with roll != pitch to check the comparison with");
  process.exit(1);
}
const swapped = definitionText("swa_msgs/Imu").replace(/float64 roll_rad/, "float64 TMP")
  .replace(/float64 pitch_rad/, "float64 roll_rad").replace(/float64 TMP/, "float64 pitch_rad");
if (differences(decode(imu, { "swa_msgs/Imu": swapped }), imu.expected, "Imu", []).length === 0) {
  console.error("decode_check: a definition with roll and pitch swapped decoded to the same values: the check is blind");
  process.exit(1);
}

const types = new Map();
let failures = 0;
for (const entry of capture) {
  let found;
  try {
    found = differences(decode(entry), entry.expected, entry.ros_type, []);
  } catch (e) {
    found = [`${entry.ros_type}: does not decode: ${e.message}`];
  }
  types.set(entry.ros_type, (types.get(entry.ros_type) ?? 0) + 1);
  if (found.length > 0) {
    failures += 1;
    console.error(`MISMATCH on ${entry.topic}:\n  ${found.join("\n  ")}`);
  }
}
for (const [type, n] of [...types].sort()) console.log(`${type}: ${n} payload(s)`);
console.log(`decode_check: ${capture.length - failures} of ${capture.length} payloads of ${types.size} types decoded ` +
  `field for field as the .msg files say`);
process.exit(failures === 0 ? 0 : 1);
