// The live page in headless Chromium, driven over the DevTools protocol with Node's own WebSocket (no npm package):
//   node --experimental-websocket page_check.mjs URL OUT_PREFIX [TIMEOUT_MS]
// Chromium's own --dump-dom / --screenshot do not wait for WebSocket data in real time (--virtual-time-budget runs
// out before the first message, --timeout only caps the wait), so this opens the page, waits until it has received
// data (body[data-messages] > 0 and body[data-uavs] > 0), lets frames draw, then writes OUT_PREFIX.1.html, and two
// seconds later OUT_PREFIX.2.html and OUT_PREFIX.png. Exit 0; 1 on a timeout or a page error (an exception or a
// console error), with the reason on stdout.
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const [url, prefix, timeoutArg] = process.argv.slice(2);
if (!url || !prefix) {
  console.log("usage: node --experimental-websocket page_check.mjs URL OUT_PREFIX [TIMEOUT_MS]");
  process.exit(2);
}
const timeoutMs = Number(timeoutArg || 20000);
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// A fresh profile, and no background traffic: this machine has no internet, and refused connections slow Chromium.
const profile = mkdtempSync(join(tmpdir(), "swa_page_check_"));
const chromium = spawn("chromium", ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync", `--user-data-dir=${profile}`,
  "--window-size=1200,900", "--remote-debugging-port=0", "about:blank"], { stdio: ["ignore", "ignore", "pipe"] });

function finish(code, message) {
  console.log(message);
  chromium.kill("SIGTERM");
  setTimeout(() => {
    rmSync(profile, { recursive: true, force: true });
    process.exit(code);
  }, 300);
}
setTimeout(() => finish(1, `FAIL: no result within ${timeoutMs + 10000} ms`), timeoutMs + 10000);

// Chromium prints the DevTools port it picked on stderr.
let stderr = "";
let started = false;
chromium.stderr.on("data", (chunk) => {
  stderr += chunk;
  const m = /DevTools listening on ws:\/\/[^:]+:(\d+)\//.exec(stderr);
  if (!m || started) return;
  started = true;
  check(m[1]).catch((e) => finish(1, `FAIL: ${e}`));
});
chromium.on("exit", (code) => { if (!started) finish(1, `FAIL: chromium exited (${code}): ${stderr.slice(-300)}`); });

async function check(port) {
  const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
  const ws = new WebSocket(targets.find((t) => t.type === "page").webSocketDebuggerUrl);
  await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
  let nextId = 0;
  const pending = new Map();
  const pageErrors = [];
  ws.onmessage = (event) => {
    const m = JSON.parse(event.data);
    if (m.method === "Runtime.exceptionThrown") {
      const d = m.params.exceptionDetails;
      pageErrors.push(d.exception?.description ?? d.text);
    }
    if (m.method === "Runtime.consoleAPICalled" && m.params.type === "error") pageErrors.push(JSON.stringify(m.params.args));
    if (m.id && pending.has(m.id)) {
      pending.get(m.id)(m);
      pending.delete(m.id);
    }
  };
  const send = (method, params = {}) => new Promise((resolve) => {
    const id = ++nextId;
    pending.set(id, resolve);
    ws.send(JSON.stringify({ id, method, params }));
  });
  const evaluate = async (expression) => (await send("Runtime.evaluate", { expression, returnByValue: true })).result?.result?.value;
  const dom = () => evaluate("document.documentElement.outerHTML");

  await send("Page.enable");
  await send("Runtime.enable");
  await send("Page.navigate", { url });
  const t0 = Date.now();
  let state = [0, 0];
  while (Date.now() - t0 < timeoutMs) {
    state = await evaluate("document.body ? [+(document.body.dataset.messages || 0), +(document.body.dataset.uavs || 0)] : [0, 0]");
    if (state[0] > 0 && state[1] > 0) break;
    await sleep(200);
  }
  if (!(state[0] > 0 && state[1] > 0)) return finish(1, `FAIL: the page received no data within ${timeoutMs} ms`);
  await sleep(1000);  // a few animation frames: the swarm and the plots drawn
  writeFileSync(`${prefix}.1.html`, await dom());
  await sleep(2000);
  writeFileSync(`${prefix}.2.html`, await dom());
  const shot = await send("Page.captureScreenshot", { format: "png" });
  writeFileSync(`${prefix}.png`, Buffer.from(shot.result.data, "base64"));
  if (pageErrors.length > 0) return finish(1, `FAIL: page errors: ${pageErrors.join(" | ")}`);
  finish(0, `OK: ${state[0]} messages, ${state[1]} UAVs after ${Date.now() - t0} ms`);
}
