// What decode_check.mjs and foreign_check.mjs share: the concatenated ROS 2 message definition (rosbag2's and MCAP's
// form) built from a lookup of .msg texts, hex payloads, and a field-for-field comparison with expected JSON.

export const PRIMITIVES = new Set(["bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16",
  "int32", "uint32", "int64", "uint64", "string", "wstring", "builtin_interfaces/Time", "builtin_interfaces/Duration"]);

// The complex types a definition uses, as pkg/Name (a bare name is of the same package).
export function dependencies(text, pkg) {
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

// The full definition of `rosType` ("pkg/msg/Name" or "pkg/Name"): the type, then each dependency after a separator
// line and "MSG: pkg/Name". `textOf(pkg/Name)` gives a type's .msg text.
export function fullDefinition(rosType, textOf) {
  const order = [];
  const seen = new Set();
  const visit = (full) => {
    if (seen.has(full)) return;
    seen.add(full);
    order.push(full);
    for (const dep of dependencies(textOf(full), full.split("/")[0])) visit(dep);
  };
  visit(rosType.replace("/msg/", "/"));
  return order.map((full, k) => (k === 0 ? "" : `${"=".repeat(80)}\nMSG: ${full}\n`) + textOf(full)).join("\n");
}

export function hexBytes(hex) {
  return Uint8Array.from(hex.match(/../g).map((h) => parseInt(h, 16)));
}

// Every difference between the decoded value and the expected JSON (64-bit integers are strings there).
export function differences(actual, expected, path, out) {
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
    for (const key of new Set([...Object.keys(actual), ...Object.keys(expected)])) {
      if (!(key in actual)) out.push(`${path}.${key}: missing in the decoded message`);
      else if (!(key in expected)) out.push(`${path}.${key}: decoded but not expected`);
      else differences(actual[key], expected[key], `${path}.${key}`, out);
    }
  } else if (actual !== expected) {
    out.push(`${path}: ${JSON.stringify(actual)} != ${JSON.stringify(expected)}`);
  }
  return out;
}
