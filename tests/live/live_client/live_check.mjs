#!/usr/bin/env node
// Independent client check for `swa_monitor --live PORT` (see the SWA live wire spec):
// speaks the Foxglove WebSocket protocol v1 through @foxglove/ws-protocol's FoxgloveClient
// (no hand-rolled framing), subscribes to /swa/live/swarm and /swa/monitor/metrics,
// validates the swarm payloads and writes what it received to OUT.json.
//
// Usage: node live_check.mjs URL OUT.json [--messages N]
//          [--subprotocol foxglove.websocket.v1|foxglove.sdk.v1]
//          [--timeout-s S] [--disconnect-after N]
//
// Exit 0: everything checked out. Exit 1: one or more failures, each printed on stderr
// as "live_check: <what>". Exit 2: bad command line.
// Stdout: exactly one summary JSON line (also on failure).

import { writeFileSync } from "node:fs";
// @foxglove/ws-protocol ships CommonJS as "main" (its ESM build uses extensionless imports that
// Node cannot load) and Node cannot detect its named exports: import the default and destructure.
import foxglove from "@foxglove/ws-protocol";
import WebSocket from "ws";

const { FoxgloveClient } = foxglove;

const SWARM_TOPIC = "/swa/live/swarm";
const METRICS_TOPIC = "/swa/monitor/metrics";
const EXPECTED = {
  [SWARM_TOPIC]: { schemaName: "swa_live/Swarm" },
  [METRICS_TOPIC]: { schemaName: "swa_monitor/StepMetrics" },
};
const SUBPROTOCOLS = ["foxglove.websocket.v1", "foxglove.sdk.v1"];
const USAGE =
  "usage: node live_check.mjs URL OUT.json [--messages N] " +
  "[--subprotocol foxglove.websocket.v1|foxglove.sdk.v1] [--timeout-s S] [--disconnect-after N]";

function usage(msg) {
  process.stderr.write(`live_check: ${msg}\n${USAGE}\n`);
  process.exit(2);
}

function parseArgs(argv) {
  const opts = {
    url: null,
    out: null,
    messages: 100,
    subprotocol: FoxgloveClient.SUPPORTED_SUBPROTOCOL,
    timeoutS: 30,
    disconnectAfter: null,
  };
  const positional = [];
  const posInt = (name, v) => {
    if (!/^\d+$/.test(v ?? "") || Number(v) < 1) usage(`${name} needs a positive integer, got ${v}`);
    return Number(v);
  };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const [flag, inline] = a.startsWith("--") && a.includes("=") ? a.split(/=(.*)/s) : [a, undefined];
    const value = () => {
      if (inline !== undefined) return inline;
      if (i + 1 >= argv.length) usage(`${flag} needs a value`);
      return argv[++i];
    };
    switch (flag) {
      case "--messages":
        opts.messages = posInt(flag, value());
        break;
      case "--disconnect-after":
        opts.disconnectAfter = posInt(flag, value());
        break;
      case "--timeout-s": {
        const v = value();
        const n = Number(v);
        if (!Number.isFinite(n) || n <= 0) usage(`--timeout-s needs a positive number, got ${v}`);
        opts.timeoutS = n;
        break;
      }
      case "--subprotocol": {
        const v = value();
        if (!SUBPROTOCOLS.includes(v)) usage(`--subprotocol must be one of ${SUBPROTOCOLS.join(", ")}, got ${v}`);
        opts.subprotocol = v;
        break;
      }
      case "-h":
      case "--help":
        process.stdout.write(USAGE + "\n");
        process.exit(0);
        break;
      default:
        if (a.startsWith("-")) usage(`unknown option ${a}`);
        positional.push(a);
    }
  }
  if (positional.length !== 2) usage("need exactly URL and OUT.json");
  [opts.url, opts.out] = positional;
  if (!/^wss?:\/\//.test(opts.url)) usage(`URL must start with ws:// or wss://, got ${opts.url}`);
  return opts;
}

const isObj = (v) => v !== null && typeof v === "object" && !Array.isArray(v);
const isNum = (v) => typeof v === "number" && Number.isFinite(v);

/** Returns a list of problems with one /swa/live/swarm payload (empty when it is fine). */
function checkSwarm(p) {
  const bad = [];
  if (!isObj(p)) return ["payload is not a JSON object"];
  if (!isNum(p.t_s)) bad.push(`t_s is not a number (${JSON.stringify(p.t_s)})`);
  if (!Array.isArray(p.uavs)) {
    bad.push(`uavs is not an array (${JSON.stringify(p.uavs)})`);
  } else {
    p.uavs.forEach((u, k) => {
      if (!isObj(u)) {
        bad.push(`uavs[${k}] is not an object`);
        return;
      }
      for (const f of ["id", "x_m", "y_m"]) {
        if (!isNum(u[f])) bad.push(`uavs[${k}].${f} is not a number (${JSON.stringify(u[f])})`);
      }
    });
  }
  return bad;
}

function main() {
  const opts = parseArgs(process.argv.slice(2));
  const target = opts.disconnectAfter ?? opts.messages;
  const failures = [];
  const fail = (msg) => failures.push(msg);

  const channels = new Map(); // id -> channel (every channel ever advertised)
  const topicsInOrder = [];
  const swarm = [];
  const metrics = [];
  let metricsCount = 0;
  let serverInfo = null;
  let selectedProtocol = null;
  let opened = false;
  let subscribed = false;
  let closingOnPurpose = false;
  let finished = false;
  let closeInfo = null;
  let prevLogTime = null;
  let monotonic = true;
  let tsMatchesLogTime = true;
  const subs = new Map(); // subscription id -> topic
  const decoder = new TextDecoder("utf-8", { fatal: true });

  // The library never picks the subprotocol itself: FoxgloveClient takes a ready WebSocket
  // (anything implementing its IWebSocket) and the caller offers the subprotocol when creating it.
  const ws = new WebSocket(opts.url, [opts.subprotocol]);
  const client = new FoxgloveClient({ ws });

  let timer = null;
  const arm = (what) => {
    clearTimeout(timer);
    timer = setTimeout(() => {
      fail(`timeout after ${opts.timeoutS} s ${what()}`);
      finish(true);
    }, opts.timeoutS * 1000);
  };
  arm(() =>
    !opened
      ? `waiting for the WebSocket connection to ${opts.url}`
      : `waiting for serverInfo and an advertise of ${SWARM_TOPIC} and ${METRICS_TOPIC}` +
        ` (serverInfo ${serverInfo ? "received" : "not received"}; advertised: ${JSON.stringify(topicsInOrder)})`,
  );

  const findTopic = (topic) => [...channels.values()].find((c) => c.topic === topic);

  function maybeSubscribe() {
    if (subscribed || !serverInfo) return;
    const sw = findTopic(SWARM_TOPIC);
    const me = findTopic(METRICS_TOPIC);
    if (!sw || !me) return;
    subscribed = true;
    for (const ch of [sw, me]) {
      if (ch.encoding !== "json") fail(`channel ${ch.topic} has encoding ${JSON.stringify(ch.encoding)}, expected "json"`);
      const want = EXPECTED[ch.topic].schemaName;
      if (ch.schemaName !== want) fail(`channel ${ch.topic} has schemaName ${JSON.stringify(ch.schemaName)}, expected "${want}"`);
      subs.set(client.subscribe(ch.id), ch.topic);
    }
    // From here the timeout is an inactivity limit: fail if no swarm message comes for timeout-s.
    arm(() => `waiting for ${SWARM_TOPIC} messages (got ${swarm.length} of ${target})`);
  }

  client.on("open", () => {
    opened = true;
    selectedProtocol = ws.protocol;
    if (selectedProtocol !== opts.subprotocol) {
      fail(`server selected subprotocol ${JSON.stringify(selectedProtocol)}, offered "${opts.subprotocol}"`);
    }
  });

  client.on("error", (err) => {
    const msg = err?.message || String(err);
    if (finished) return;
    if (!opened) fail(`cannot connect to ${opts.url}: ${msg}${err?.code ? ` (${err.code})` : ""}`);
    else fail(`protocol/connection error: ${msg}`);
  });

  client.on("serverInfo", (info) => {
    if (serverInfo) return;
    serverInfo = info;
    if (typeof info.name !== "string") fail(`serverInfo.name is not a string (${JSON.stringify(info.name)})`);
    maybeSubscribe();
  });

  client.on("advertise", (newChannels) => {
    for (const ch of newChannels) {
      channels.set(ch.id, ch);
      if (!topicsInOrder.includes(ch.topic)) topicsInOrder.push(ch.topic);
    }
    maybeSubscribe();
  });

  client.on("message", ({ subscriptionId, timestamp, data }) => {
    if (finished || closingOnPurpose) return;
    const topic = subs.get(subscriptionId);
    if (topic === undefined) {
      fail(`message for unknown subscription id ${subscriptionId}`);
      return;
    }
    const logTime = timestamp.toString();
    let payload;
    try {
      // data is a DataView into the frame, after the 13-byte header.
      payload = JSON.parse(decoder.decode(data));
    } catch (e) {
      const k = topic === SWARM_TOPIC ? swarm.length : metricsCount;
      fail(`${topic} message #${k} (log_time_ns ${logTime}): payload is not UTF-8 JSON (${e.message})`);
      payload = undefined;
    }
    if (topic === METRICS_TOPIC) {
      metricsCount++;
      if (metrics.length < 5) metrics.push(payload ?? null);
      return;
    }
    const k = swarm.length;
    if (payload !== undefined) {
      for (const p of checkSwarm(payload)) fail(`${SWARM_TOPIC} message #${k} (log_time_ns ${logTime}): ${p}`);
    }
    if (prevLogTime !== null && timestamp < prevLogTime) monotonic = false;
    prevLogTime = timestamp;
    if (isObj(payload) && isNum(payload.t_s) && Math.abs(Number(timestamp) / 1e9 - payload.t_s) > 1e-3) {
      tsMatchesLogTime = false;
    }
    swarm.push(isObj(payload) ? { ...payload, log_time_ns: logTime } : { log_time_ns: logTime, payload: payload ?? null });
    arm(() => `waiting for ${SWARM_TOPIC} messages (got ${swarm.length} of ${target})`);
    if (swarm.length >= target) stop();
  });

  client.on("close", (ev) => {
    closeInfo = { code: ev?.code, reason: ev?.reason || "" };
    if (finished) return;
    if (closingOnPurpose) {
      finish(false);
      return;
    }
    if (opened) {
      fail(
        `connection closed by the server before ${target} ${SWARM_TOPIC} messages ` +
          `(got ${swarm.length}; code ${closeInfo.code}${closeInfo.reason ? `, reason ${JSON.stringify(closeInfo.reason)}` : ""})`,
      );
    } else if (failures.length === 0) {
      fail(`cannot connect to ${opts.url} (code ${closeInfo.code})`);
    }
    if (opened && !serverInfo) fail("no serverInfo received before the connection closed");
    else if (opened && !subscribed) {
      for (const t of [SWARM_TOPIC, METRICS_TOPIC]) if (!findTopic(t)) fail(`channel ${t} was never advertised`);
    }
    finish(false);
  });

  function stop() {
    closingOnPurpose = true;
    clearTimeout(timer);
    if (opts.disconnectAfter === null) {
      // Normal end: unsubscribe politely, then close.
      try {
        for (const id of subs.keys()) client.unsubscribe(id);
      } catch (e) {
        fail(`unsubscribe failed: ${e.message}`);
      }
    }
    // --disconnect-after: drop the connection mid-stream without unsubscribing (on purpose).
    client.close();
    // If the server does not complete the close handshake, give up on it after 3 s.
    setTimeout(() => {
      if (!finished) {
        ws.terminate();
        finish(false);
      }
    }, 3000).unref();
  }

  function finish(fromTimeout) {
    if (finished) return;
    finished = true;
    clearTimeout(timer);
    if (fromTimeout) {
      if (serverInfo && !subscribed) {
        for (const t of [SWARM_TOPIC, METRICS_TOPIC]) if (!findTopic(t)) fail(`channel ${t} was never advertised`);
      }
      try {
        ws.terminate();
      } catch {
        /* ignore */
      }
    }
    const ok = failures.length === 0;
    const out = {
      subprotocol: selectedProtocol,
      server: serverInfo?.name ?? null,
      channels: topicsInOrder,
      swarm,
      metrics_count: metricsCount,
      metrics,
      ok,
      failures,
    };
    try {
      writeFileSync(opts.out, JSON.stringify(out, null, 1) + "\n");
    } catch (e) {
      failures.push(`cannot write ${opts.out}: ${e.message}`);
    }
    const summary = {
      ok: failures.length === 0,
      url: opts.url,
      subprotocol_offered: opts.subprotocol,
      subprotocol: selectedProtocol,
      server: serverInfo?.name ?? null,
      channels: topicsInOrder.length,
      swarm_count: swarm.length,
      swarm_target: target,
      metrics_count: metricsCount,
      uavs_last: swarm.length && Array.isArray(swarm.at(-1).uavs) ? swarm.at(-1).uavs.length : null,
      t_s_first: swarm[0]?.t_s ?? null,
      t_s_last: swarm.at(-1)?.t_s ?? null,
      log_time_monotonic: monotonic,
      t_s_matches_log_time: tsMatchesLogTime,
      disconnected_on_purpose: opts.disconnectAfter !== null && swarm.length >= target,
      failures: failures.length,
      out: opts.out,
    };
    process.stdout.write(JSON.stringify(summary) + "\n");
    for (const f of failures) process.stderr.write(`live_check: ${f}\n`);
    process.exitCode = failures.length === 0 ? 0 : 1;
    // Do not let a half-open socket keep the process alive.
    setTimeout(() => process.exit(process.exitCode), 200).unref();
  }
}

main();
