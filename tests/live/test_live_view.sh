#!/usr/bin/env bash
# The live view during a run (issue #14):
#   test_live_view.sh BIN_DIR WORK_DIR
# 1. installs what it needs if missing (Debian: nodejs, npm, chromium; npm: @foxglove/ws-protocol and ws from
#    live_client/package-lock.json) into WORK_DIR;
# 2. starts a realtime 4-UAV run with swa_launch --live 0 (a free port, read from the monitor's log);
# 3. while it flies: the reference client (@foxglove/ws-protocol) receives the advertised channels, subscribes and
#    decodes >= 100 swarm messages; a second client disconnects on purpose after 20; a third speaks the other
#    subprotocol name (foxglove.sdk.v1); headless Chromium shows the page (page_check.mjs: the DOM shows 4 UAVs and a
#    d_NB that changes within 2 s, and a screenshot that is not blank); the port is not reachable through a
#    non-loopback address of this host;
# 4. after the run: PASS (the clients did not disturb it), and every swarm message on the 0.5 s grid has exactly the
#    positions of the monitor's trajectories.csv.
# The run uses the launcher's own swarm partition on a random domain.
# shellcheck source-path=SCRIPTDIR source=../script_tools.sh
source "$(dirname "${BASH_SOURCE[0]}")/../script_tools.sh"
bin=$1
work=$2
launch=""
cleanup() {
  if [ -n "$launch" ]; then
    kill "$launch" 2>/dev/null || true
    wait "$launch" 2>/dev/null || true
  fi
}
trap cleanup EXIT

ensure_packages chromium
rm -rf "$work"
install_npm_folder "$here/live_client" "$work/client" live_check.mjs
client() { node "$work/client/live_check.mjs" "$@"; }

reserve_test_domain $((120 + RANDOM % 100))

# 2.
run=$work/run
"$bin/swa_launch" --scenario "$root/deploy/scenarios/dropout_4.yaml" --set duration_s=40 --set clock.mode=realtime \
  --domain "$TEST_DOMAIN" --out "$run" --live 0 --timeout-s 180 >"$work/launch.log" 2>&1 &
launch=$!
port=""
for _ in $(seq 300); do
  if [ -f "$run/logs/monitor.log" ]; then
    port=$(sed -n 's|.*live view at http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$run/logs/monitor.log" | head -n1)
  fi
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || fail "the monitor printed no live view URL (see $run/logs/monitor.log)"
echo "test_live_view: live view on port $port"

# 3. Three clients at once, one leaving early.
client "ws://127.0.0.1:$port/" "$work/a.json" --messages 100 --timeout-s 60 >"$work/a.txt" &
a=$!
client "ws://127.0.0.1:$port/" "$work/b.json" --disconnect-after 20 --timeout-s 60 >"$work/b.txt" &
b=$!
client "ws://127.0.0.1:$port/" "$work/c.json" --messages 30 --subprotocol foxglove.sdk.v1 --timeout-s 60 \
  >"$work/c.txt" &
c=$!
wait $a || fail "client a: $(cat "$work/a.txt")"
wait $b || fail "client b (disconnects after 20): $(cat "$work/b.txt")"
wait $c || fail "client c (foxglove.sdk.v1): $(cat "$work/c.txt")"
echo "test_live_view: client a: $(cat "$work/a.txt")"
grep -q '"subprotocol":"foxglove.sdk.v1"' "$work/c.txt" || fail "the server did not select foxglove.sdk.v1"

# The page in a browser: the swarm drawn, a d_NB that moves (two DOM snapshots 2 s apart), a screenshot.
node --experimental-websocket "$here/page_check.mjs" "http://127.0.0.1:$port/" "$work/page" 30000 >"$work/page.txt" \
  || fail "headless Chromium: $(cat "$work/page.txt")"
echo "test_live_view: chromium: $(cat "$work/page.txt")"
python3 - "$work" <<'PY'
import re, sys, zlib, struct
work = sys.argv[1]
problems = []
def field(dom, name):
    m = re.search(r'id="%s"[^>]*>([^<]*)<' % name, dom)
    return m.group(1).strip() if m else None
doms = [open(f"{work}/page.{i}.html").read() for i in (1, 2)]
for i, dom in enumerate(doms, 1):
    if field(dom, "uav-count") != "4":
        problems.append(f"snapshot {i}: the page shows {field(dom, 'uav-count')!r} UAVs, not 4")
    if not re.search(r'data-messages="[1-9]', dom):
        problems.append(f"snapshot {i}: the page received no message")
    # The monitor draws the pictures (svg_plot.h); the page shows them: a labelled dot per UAV, lines on the plots.
    swarm = re.search(r'id="swarm"[^>]*>(.*?)</svg>', dom, re.S)
    dots = re.findall(r'<circle class="marker"', swarm.group(1)) if swarm else []
    labels = re.findall(r'class="point-label"[^>]*>(\d+)<', swarm.group(1)) if swarm else []
    if len(dots) != 4 or sorted(labels) != ["0", "1", "2", "3"]:
        problems.append(f"snapshot {i}: the swarm picture shows {len(dots)} dots labelled {labels}, not UAVs 0-3")
    for plot in ("d_nb", "drift", "min_separation"):
        picture = re.search(r'id="plot-%s"[^>]*>(.*?)</svg>\s*</div>' % plot, dom, re.S)
        if not picture or 'class="series"' not in picture.group(1):
            problems.append(f"snapshot {i}: the {plot} plot shows no line")
dnb = [field(d, "dnb") for d in doms]
try:
    values = [float(v) for v in dnb]
    if values[0] == values[1]:
        problems.append(f"d_NB did not change in 2 s: {dnb}")
except (TypeError, ValueError):
    problems.append(f"d_NB is not a number on the page: {dnb}")
# The screenshot: a PNG whose pixels are not all one colour (the canvas drew something).
try:
    data = open(f"{work}/page.png", "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        if kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    distinct = len(set(raw[i:i + 3] for i in range(1, len(raw), 97)))
    if width < 600 or distinct < 8:
        problems.append(f"the screenshot looks blank ({width}x{height}, {distinct} distinct samples)")
except Exception as e:  # noqa: BLE001 - any failure to read it is a failure of the check
    problems.append(f"no usable screenshot: {e}")
for p in problems:
    print("test_live_view: FAIL:", p, file=sys.stderr)
print(f"test_live_view: page: d_NB {dnb[0]} then {dnb[1]}")
sys.exit(1 if problems else 0)
PY

# Not reachable from another host: the default address is the loopback one.
other=$(ip -4 -o addr show scope global 2>/dev/null | awk '{split($4, a, "/"); print a[1]; exit}')
if [ -n "$other" ]; then
  if curl -s -m 3 -o /dev/null "http://$other:$port/"; then
    fail "the live view answers on $other, a non-loopback address, without being told to"
  fi
  echo "test_live_view: $other:$port refused, as it should be"
else
  echo "test_live_view: this host has no non-loopback IPv4 address: the refusal is not checked here"
fi

# 4.
set +e
wait "$launch"
status=$?
set -e
launch=""
[ "$status" -eq 0 ] || fail "the run with live clients did not PASS (exit $status, see $work/launch.log)"
grep -q "live view: [1-9][0-9]* page request(s), [3-9][0-9]* client(s)" "$run/logs/monitor.log" \
  || fail "the monitor did not count the page and the three clients: $(grep 'live view:' "$run/logs/monitor.log")"
python3 - "$work/a.json" "$run/trajectories.csv" <<'PY'
import csv, json, sys
swarm = json.load(open(sys.argv[1]))["swarm"]
truth = {}
for row in csv.DictReader(open(sys.argv[2])):
    truth[(round(float(row["t_s"]) * 10), int(row["uav"]))] = (float(row["x_m"]), float(row["y_m"]))
compared, problems = 0, []
for m in swarm:
    tick = round(m["t_s"] * 10)
    if tick % 5:
        continue
    for u in m["uavs"]:
        want = truth.get((tick, u["id"]))
        if want is None:
            continue
        compared += 1
        if (u["x_m"], u["y_m"]) != want:
            problems.append(f"t {m['t_s']} uav {u['id']}: live ({u['x_m']}, {u['y_m']}), truth {want}")
if compared < 20:
    problems.append(f"only {compared} live positions on the trajectories' 0.5 s grid to compare")
for p in problems[:10]:
    print("test_live_view: FAIL:", p, file=sys.stderr)
print(f"test_live_view: {compared} live positions equal to the truth of trajectories.csv")
sys.exit(1 if problems else 0)
PY
echo "test_live_view: PASS"
