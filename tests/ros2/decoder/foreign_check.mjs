// The other systems' messages SWA speaks, checked with an independent ROS 2 CDR implementation (@foxglove/rosmsg +
// @foxglove/rosmsg2-serialization, no code of SWA's) against the official definitions (issue #27):
//   node foreign_check.mjs CAPTURE.json PX4_MSG_DIR OUT.json
// 1. decodes every payload SWA serialised (tests/ros2/foreign_payloads.cpp write) and compares it field for field
//    with the values SWA set: vision_msgs, mrs_msgs and ArduPilot's messages completely, PX4's messages on the fields
//    the stand-in sets and zero everywhere else, each against the release's own .msg file
//    (PX4_MSG_DIR/<tag>/<Name>.msg);
// 2. serialises the same values of every payload but PX4's itself and writes them to OUT.json, for foreign_payloads
//    check to read as the agent, the bridge or the stand-in does.
// It first checks that it can fail: a Point definition with x and y swapped must not match.
// Exit 0: everything matched; 1: a difference (each printed); 2: bad usage.

import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { parse } from "@foxglove/rosmsg";
import { MessageReader, MessageWriter } from "@foxglove/rosmsg2-serialization";

import { differences, fullDefinition, hexBytes } from "./ros_cdr.mjs";

const [capturePath, px4Dir, outPath] = process.argv.slice(2);
if (!capturePath || !px4Dir || !outPath) {
  console.error("usage: node foreign_check.mjs CAPTURE.json PX4_MSG_DIR OUT.json");
  process.exit(2);
}

// The official definitions (fields only): std_msgs and geometry_msgs of ROS 2's common_interfaces, vision_msgs 4.x
// (ros-perception/vision_msgs, branch ros2), mrs_msgs (ctu-mrs/mrs_msgs, msg/general).
const STANDARD = {
  "std_msgs/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
  "geometry_msgs/Point": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n",
  "geometry_msgs/Vector3": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/Pose": "Point position\nQuaternion orientation\n",
  "geometry_msgs/PoseWithCovariance": "Pose pose\nfloat64[36] covariance\n",
  "vision_msgs/Detection3DArray": "std_msgs/Header header\nDetection3D[] detections\n",
  "vision_msgs/Detection3D":
    "std_msgs/Header header\nObjectHypothesisWithPose[] results\nBoundingBox3D bbox\nstring id\n",
  "vision_msgs/ObjectHypothesisWithPose": "ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n",
  "vision_msgs/ObjectHypothesis": "string class_id\nfloat64 score\n",
  "vision_msgs/BoundingBox3D": "geometry_msgs/Pose center\ngeometry_msgs/Vector3 size\n",
  "mrs_msgs/PoseWithCovarianceArrayStamped": "std_msgs/Header header\nPoseWithCovarianceIdentified[] poses\n",
  "mrs_msgs/PoseWithCovarianceIdentified": "uint32 id\ngeometry_msgs/Pose pose\nfloat64[36] covariance\n",
  // ArduPilot's DDS interface: sensor_msgs/Imu and geometry_msgs/Twist(Stamped) of common_interfaces, and
  // ardupilot_msgs (ArduPilot's Tools/ros2/ardupilot_msgs: msg/Status.msg, srv/ArmMotors.srv, srv/ModeSwitch.srv;
  // constants left out, they are not on the wire).
  "sensor_msgs/Imu":
    "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n" +
    "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n" +
    "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n",
  "sensor_msgs/NavSatFix":
    "std_msgs/Header header\nNavSatStatus status\nfloat64 latitude\nfloat64 longitude\nfloat64 altitude\n" +
    "float64[9] position_covariance\nuint8 position_covariance_type\n",
  "sensor_msgs/NavSatStatus": "int8 status\nuint16 service\n",
  "geometry_msgs/TwistStamped": "std_msgs/Header header\nTwist twist\n",
  "geometry_msgs/Twist": "Vector3 linear\nVector3 angular\n",
  "ardupilot_msgs/Status":
    "std_msgs/Header header\nuint8 vehicle_type\nbool armed\nuint8 mode\nbool flying\nbool external_control\n" +
    "uint8[] failsafe\n",
  "ardupilot_msgs/srv/ArmMotors_Request": "bool arm\n",
  "ardupilot_msgs/srv/ArmMotors_Response": "bool result\n",
  "ardupilot_msgs/srv/ModeSwitch_Request": "uint8 mode\n",
  "ardupilot_msgs/srv/ModeSwitch_Response": "bool status\nuint8 curr_mode\n",
};
function definitionText(full, tag, overrides) {
  if (overrides && overrides[full] !== undefined) return overrides[full];
  if (STANDARD[full] !== undefined) return STANDARD[full];
  const [pkg, name] = full.split("/");
  if (pkg === "px4_msgs") return readFileSync(join(px4Dir, tag, `${name}.msg`), "utf8");
  throw new Error(`no definition of ${full}`);
}

function fullDefinitionOf(rosType, tag, overrides) {
  return fullDefinition(rosType, (full) => definitionText(full, tag, overrides));
}

const hexOf = (bytes) => Buffer.from(bytes).toString("hex");

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
    const writer = new MessageWriter(parse(fullDefinitionOf(entry.ros_type), { ros2: true }));
    written.push({ ros_type: entry.ros_type, cdr_hex: hexOf(writer.writeMessage(entry.expected)) });
  }
}
writeFileSync(outPath, JSON.stringify(written, null, 1));
console.log(`foreign_check: ${capture.length - failures} of ${capture.length} payloads decoded as the official ` +
  `definitions say; ${written.length} written for SWA to read`);
process.exit(failures === 0 ? 0 : 1);
