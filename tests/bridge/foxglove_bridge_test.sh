#!/usr/bin/env bash
# The Foxglove bridge with Foxglove's own client library (npm: @foxglove/ws-protocol,
# @foxglove/rosmsg2-serialization, @foxglove/omgidl-serialization, @mcap/core): a simulated robot
# runs in real time through the host; the client subscribes, decodes every message with the
# schema the bridge advertised (ros2msg for ROS 2's types), each message must be byte for byte one
# the recorder took from DDS in the same run and decode as the recorder's IDL decodes it; the map
# cloud (PointCloud2, <= max_points) and the mesh scene (SceneUpdate) decode and hold together.
# Then, under DDS Security (a site's certificates made here), the bridge stays off unless asked.
# Skipped (exit 77) when node/npm or the npm registry are not there.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
HERE="$ROOT/tests/bridge"
command -v node > /dev/null && command -v npm > /dev/null ||
    { echo "SKIP: node and npm are needed for Foxglove's client library"; exit 77; }
MODULES="$BUILD/tests/bridge_npm"
if [ ! -d "$MODULES/node_modules/@foxglove/rosmsg2-serialization" ] ||
    ! cmp -s "$HERE/package.json" "$MODULES/package.json"; then
    mkdir -p "$MODULES"
    cp "$HERE/package.json" "$MODULES/"
    (cd "$MODULES" && timeout 300 npm install --no-audit --no-fund --silent > npm.log 2>&1) ||
        { echo "SKIP: npm install of Foxglove's client libraries failed (no registry?): $(tail -1 "$MODULES/npm.log")"; exit 77; }
fi
cp "$HERE/foxglove_client.mjs" "$MODULES/"
# The layout file: JSON, every panel of its tree configured, every topic one ltm publishes.
node -e '
const l = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
const leaves = (n) => (typeof n === "string" ? [n] : [...leaves(n.first), ...leaves(n.second)]);
const missing = leaves(l.layout).filter((id) => !l.configById[id]);
const topics = JSON.stringify(l.configById).match(/"\/(robot\/[a-z_]+|tf)[".]/g) ?? [];
const known = ["map_cloud", "mesh_scene", "points", "path", "odometry", "corrected_odometry", "localisation_status", "map_changes"];
const unknown = topics.filter((t) => t.startsWith("\"/robot/") && !known.includes(t.slice(8, -1)));
if (missing.length || unknown.length) { console.log(`panels ${missing} not configured; topics ${unknown} unknown`); process.exit(1); }
' "$ROOT/components/bridge/foxglove_layout.json" || { echo "FAIL: foxglove_layout.json"; exit 1; }
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
node "$MODULES/foxglove_client.mjs" "ws://127.0.0.1:$port" \
    /robot/odometry:10,/tf:10,/tf_static:1,/robot/map_cloud:2,/robot/mesh_scene:1 "$TMP/seen.json" ||
    { echo "FAIL: the client did not get what it waited for: $(head -c 300 "$TMP/seen.json")"; cat "$TMP/host.log"; exit 1; }
wait $host; rc=$?
[ "$rc" = 0 ] || { echo "FAIL: host exit $rc"; tail -5 "$TMP/host.log"; exit 1; }
node "$MODULES/foxglove_client.mjs" --compare "$TMP/seen.json" "$TMP/run.mcap" || { echo "FAIL: compare"; exit 1; }
grep "map cloud: " "$TMP/host.log" | tail -1

# Under DDS Security: off with one line saying why, unless enable_with_security.
if ! command -v openssl > /dev/null; then echo "PASS (the DDS Security part skipped: no openssl)"; exit 0; fi
bash "$ROOT/launch_configs/security/make_site_certs.sh" "$TMP/site" robot > "$TMP/certs.log" 2>&1 ||
    { echo "FAIL: make_site_certs.sh"; cat "$TMP/certs.log"; exit 1; }
secure_bridge() {  # $1: enable_with_security; prints the host's log
    local log="$TMP/secure_$1.log"
    cat > "$TMP/secure.yaml" <<YAML
namespace: /robot
components:
  - name: bridge
    type: foxglove_bridge
    params: {port: $port, enable_with_security: $1}
YAML
    LTM_SECURITY_DIR="$TMP/site" LTM_PARTICIPANT=robot "$BUILD/bin/ltm_host" "$TMP/secure.yaml" \
        --set "domain_id=$domain" --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}' \
        --set "dds.security=$(cat "$ROOT/launch_configs/security/dds_security.yaml")" > "$log" 2>&1 &
    host=$!
    for _ in $(seq 1 200); do grep -qs "Foxglove bridge is off\|Foxglove: connect to\|error" "$log" && break; sleep 0.1; done
    kill -INT $host; wait $host
    cat "$log"
}
off="$(secure_bridge false)"
grep -q "the Foxglove bridge is off: this site runs DDS Security" <<< "$off" ||
    { echo "FAIL: under DDS Security the bridge did not say it is off"; echo "$off"; exit 1; }
grep -q "Foxglove: connect to" <<< "$off" && { echo "FAIL: under DDS Security the bridge served"; exit 1; }
on="$(secure_bridge true)"
grep -q "Foxglove: connect to ws://127.0.0.1:$port" <<< "$on" ||
    { echo "FAIL: enable_with_security: true did not serve"; echo "$on"; exit 1; }
echo "PASS"
