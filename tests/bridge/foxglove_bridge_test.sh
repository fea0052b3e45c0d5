#!/usr/bin/env bash
# The Foxglove bridge with Foxglove's own client library (npm: @foxglove/ws-protocol,
# @foxglove/omgidl-serialization, @mcap/core): a simulated robot runs in real time through the
# host; the client subscribes, decodes every message with the schema the bridge advertised, and
# each message must be byte for byte one the recorder took from DDS in the same run.
# Skipped (exit 77) when node/npm or the npm registry are not there.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
HERE="$ROOT/tests/bridge"
command -v node > /dev/null && command -v npm > /dev/null ||
    { echo "SKIP: node and npm are needed for Foxglove's client library"; exit 77; }
MODULES="$BUILD/tests/bridge_npm"
if [ ! -d "$MODULES/node_modules/@foxglove/ws-protocol" ]; then
    mkdir -p "$MODULES"
    cp "$HERE/package.json" "$MODULES/"
    (cd "$MODULES" && timeout 300 npm install --no-audit --no-fund --silent > npm.log 2>&1) ||
        { echo "SKIP: npm install of Foxglove's client libraries failed (no registry?): $(tail -1 "$MODULES/npm.log")"; exit 77; }
fi
cp "$HERE/foxglove_client.mjs" "$MODULES/"
TMP="$(mktemp -d)"
trap 'kill $host 2>/dev/null; rm -rf "$TMP"' EXIT
port=$((20000 + $$ % 20000))
domain=$((100 + $$ % 100))
LTM_OUT="$TMP" LTM_BRIDGE_PORT="$port" LTM_SCENARIO="$ROOT/components/simulator/scenarios/tiny_loop.yaml" \
    "$BUILD/bin/ltm_host" "$HERE/bridge_test.yaml" --set "domain_id=$domain" --set "bridge.port=$port" \
    --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}' > "$TMP/host.log" 2>&1 &
host=$!
for _ in $(seq 1 200); do grep -q "Foxglove: connect to" "$TMP/host.log" && break; sleep 0.1; done
grep -q "Foxglove: connect to ws://127.0.0.1:$port" "$TMP/host.log" ||
    { echo "FAIL: the bridge did not say its address"; cat "$TMP/host.log"; exit 1; }
node "$MODULES/foxglove_client.mjs" "ws://127.0.0.1:$port" /robot/odometry,/tf 10 "$TMP/seen.json" ||
    { echo "FAIL: the client did not get 10 of each: $(head -c 300 "$TMP/seen.json")"; cat "$TMP/host.log"; exit 1; }
wait $host; rc=$?
[ "$rc" = 0 ] || { echo "FAIL: host exit $rc"; tail -5 "$TMP/host.log"; exit 1; }
node "$MODULES/foxglove_client.mjs" --compare "$TMP/seen.json" "$TMP/run.mcap" || { echo "FAIL: compare"; exit 1; }
echo "PASS"
