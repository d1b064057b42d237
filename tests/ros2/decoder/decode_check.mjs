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

import { differences, fullDefinition, hexBytes } from "./ros_cdr.mjs";

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
// The text of pkg/Name ("swa_msgs/Imu"): a .msg file of MSG_DIR for swa_msgs, the standard text otherwise.
function definitionText(full, overrides) {
  if (overrides && overrides[full] !== undefined) return overrides[full];
  if (STANDARD[full] !== undefined) return STANDARD[full];
  const [pkg, name] = full.split("/");
  const file = join(msgDir, `${name}.msg`);
  if (pkg !== "swa_msgs" || !existsSync(file)) throw new Error(`no definition of ${full}`);
  return readFileSync(file, "utf8");
}

// The full definition of a ROS type (ros_cdr.mjs), with `overrides` replacing some texts.
function fullDefinitionOf(rosType, overrides) {
  return fullDefinition(rosType, (full) => definitionText(full, overrides));
}

function decode(entry, overrides) {
  const reader = new MessageReader(parse(fullDefinitionOf(entry.ros_type, overrides), { ros2: true }));
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
