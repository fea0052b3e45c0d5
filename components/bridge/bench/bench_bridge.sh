#!/usr/bin/env bash
# ./ltm bench bridge [--scenario S] [--count N] [--clients 0|1] [--out D]
# The Foxglove bridge's cost to the robot: robot_composed.yaml (the demo: simulator, odometry,
# mapping, mesh, maintenance, writers, tf, the bridge) runs a scenario through the host with
# `--clients` Foxglove clients (Foxglove's own client library, tests/bridge/foxglove_client.mjs
# --all: every advertised topic subscribed, the map cloud and the mesh scene included) and reads
# the CPU time of the bridge's threads (`bridge`: DDS samples in, the map cloud built; `bridge/io`:
# the WebSocket server) from /proc/PID/task/*/stat every 0.5 s. Prints the bridge's CPU time, per
# scan, and as a share of one core at the sensor's 10 Hz; what the client received per topic; the
# map cloud's size and build time (the bridge's log). The pipeline runs offline (as fast as it
# goes), so a share at 10 Hz is CPU a scan x 10.
# Runs on DDS domain LTM_BENCH_DOMAIN (default 65), the bridge on port LTM_BENCH_PORT (18765).
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
DOMAIN="${LTM_BENCH_DOMAIN:-65}"
PORT="${LTM_BENCH_PORT:-18765}"
SCENARIO="$ROOT/components/simulator/scenarios/site_loop.yaml"; COUNT=0; CLIENTS=1; OUT=""
fail() { echo "ltm bench bridge: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) sed -n 2,12p "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        --scenario|--count|--clients|--out)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --scenario) SCENARIO="$2" ;; --count) COUNT="$2" ;;
                --clients) CLIENTS="$2" ;; --out) OUT="$2" ;;
            esac
            shift 2 ;;
        *) fail "unknown argument '$1' (--help)" ;;
    esac
done
[ -f "$SCENARIO" ] || fail "--scenario: no such file: $SCENARIO"
[[ "$COUNT" =~ ^[0-9]+$ ]] || fail "--count: a number of scans, got '$COUNT'"
[[ "$CLIENTS" =~ ^[01]$ ]] || fail "--clients: 0 or 1, got '$CLIENTS'"
OUT="${OUT:-$ROOT/results/bench-bridge-$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$OUT" || fail "cannot make $OUT"
MODULES="$BUILD/tests/bridge_npm"
if [ "$CLIENTS" = 1 ]; then
    command -v node > /dev/null || fail "node is needed for the client (apt-get install nodejs npm)"
    if [ ! -d "$MODULES/node_modules/@foxglove/ws-protocol" ]; then
        mkdir -p "$MODULES" && cp "$ROOT/tests/bridge/package.json" "$MODULES/" &&
            (cd "$MODULES" && npm install --no-audit --no-fund --silent) ||
            fail "npm install of Foxglove's client libraries into $MODULES failed"
    fi
    cp "$ROOT/tests/bridge/foxglove_client.mjs" "$MODULES/"
fi

LTM_OUT="$OUT" LTM_SCENARIO="$SCENARIO" "$BUILD/bin/ltm_host" "$ROOT/launch_configs/robot_composed.yaml" \
    --set "domain_id=$DOMAIN" --set "bridge.port=$PORT" --set "sensor.count=$COUNT" \
    --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}' > "$OUT/host.log" 2>&1 &
host=$!
trap 'kill $host 2>/dev/null' EXIT
for _ in $(seq 1 300); do grep -q "Foxglove: connect to\|Foxglove bridge is off" "$OUT/host.log" && break; sleep 0.1; done
grep -q "Foxglove: connect to" "$OUT/host.log" || { tail -5 "$OUT/host.log"; fail "the bridge did not start"; }
[ "$CLIENTS" = 1 ] && node "$MODULES/foxglove_client.mjs" --all "ws://127.0.0.1:$PORT" "$OUT/client.json" &

# The bridge's threads' CPU ticks (utime + stime), the last seen of each thread.
declare -A TICKS
hz="$(getconf CLK_TCK)"
start=$(date +%s.%N)
while kill -0 $host 2>/dev/null; do
    for stat in /proc/$host/task/*/stat; do
        { read -r line < "$stat"; } 2>/dev/null || continue
        name="${line#*(}"; name="${name%%)*}"
        case "$name" in bridge|bridge/*) ;; *) continue ;; esac
        rest="${line##*) }"; set -- $rest
        TICKS["$name ${stat//[!0-9]/}"]=$(( ${12} + ${13} ))
    done
    sleep 0.5
done
wait $host; rc=$?
end=$(date +%s.%N)
wait
[ "$rc" = 0 ] || echo "warning: the host exited $rc (see $OUT/host.log)"
scans="$(grep -o 'sensor: [0-9]*/[0-9]*' "$OUT/host.log" | tail -1 | cut -d' ' -f2 | cut -d/ -f1)"
{
    echo "# ./ltm bench bridge: $(basename "$SCENARIO"), ${scans:-?} scans, $CLIENTS client(s)"
    echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); run $(awk "BEGIN{printf \"%.0f\", $end-$start}") s"
    total=0
    for k in "${!TICKS[@]}"; do
        echo "thread ${k% *}: $(awk "BEGIN{printf \"%.2f\", ${TICKS[$k]}/$hz}") s CPU"
        total=$((total + TICKS[$k]))
    done
    awk -v t="$total" -v hz="$hz" -v n="${scans:-0}" 'BEGIN{
        s = t / hz; printf "bridge CPU: %.2f s", s;
        if (n > 0) printf ", %.2f ms a scan, %.2f %% of one core at 10 Hz", 1000 * s / n, 100 * s * 10 / n;
        printf "\n" }'
    grep "map cloud: " "$OUT/host.log" | tail -1 | sed 's/^.*\] /last /'
    grep "Foxglove: .* connections" "$OUT/host.log" | tail -1 | sed 's/^.*\] //'
    if [ -f "$OUT/client.json" ]; then
        node -e 'const r = JSON.parse(require("fs").readFileSync(process.argv[1]));
          for (const [t, c] of Object.entries(r.counts).sort())
            console.log(`client: ${t} (${c.schema}, ${c.encoding}): ${c.messages} messages, ${(c.bytes / 1048576).toFixed(1)} MiB` +
              (c.messages ? `, latency from the DDS source timestamp p50 ${c.latency_p50_ms} / p99 ${c.latency_p99_ms} / max ${c.latency_max_ms} ms` : ""));' "$OUT/client.json"
    fi
} | tee "$OUT/report.txt"
