#!/usr/bin/env bash
# ./ltm bench dds [--points N] [--count N] [--rate HZ] [--security DIR]
# Measures the spine: host start-up time, latency of PointCloud2 scans in one process and between
# two processes (loopback, unicast discovery) with the CPU each used, and the CPU an idle host uses.
# --security DIR: every participant with DDS Security, DIR made by
# launch_configs/security/make_site_certs.sh (the sink is base_station, the source its first robot).
set -euo pipefail
BIN="$(cd "$(dirname "$0")" && pwd)"
HOST="$BIN/ltm_host"
POINTS=120000; COUNT=150; RATE=10; SECURITY=""
usage() {
    echo "Measures the spine: host start-up, PointCloud2 latency in one process and between two,"
    echo "idle CPU"
    printf 'Usage: ltm_bench_dds [OPTIONS]\n\nOptions:\n'
    printf '  %-30s%s\n' "-h,--help" "Print this help message and exit" \
        "--points UINT=$POINTS" "points a scan" "--count UINT=$COUNT" "scans sent" \
        "--rate FLOAT=$RATE" "scans a second" \
        "--security DIR" "DDS Security with the site in DIR (make_site_certs.sh)"
}
# The usage errors of every ltm tool: one line, exit code 2.
fail() { echo "ltm_bench_dds: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --points|--count|--rate)
            [ $# -ge 2 ] || fail "$1: needs a value"
            if [ "$1" = --rate ]; then
                [[ "$2" =~ ^[0-9]+([.][0-9]+)?$ ]] || fail "$1: expected a number, got '$2'"
                RATE="$2"
            else
                [[ "$2" =~ ^[0-9]+$ ]] || fail "$1: expected a non-negative integer, got '$2'"
                if [ "$1" = --points ]; then POINTS="$2"; else COUNT="$2"; fi
            fi
            shift 2 ;;
        --security)
            [ $# -ge 2 ] || fail "$1: needs a value"
            SECURITY="$(cd "$2" 2>/dev/null && pwd)" || fail "--security: no such folder: $2"
            shift 2 ;;
        -*) fail "$1: unknown option" ;;
        *) fail "$1: unexpected argument" ;;
    esac
done
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
DOMAIN=$(( 100 + RANDOM % 100 ))
ROBOT=""
if [ -n "$SECURITY" ]; then
    for f in identity_ca.pem permissions_ca.pem governance.p7s base_station/cert.pem; do
        [ -f "$SECURITY/$f" ] || fail "--security: $SECURITY/$f missing (make_site_certs.sh DIR ROBOT)"
    done
    for d in "$SECURITY"/*/; do
        d="$(basename "$d")"
        if [ "$d" != base_station ] && [ -f "$SECURITY/$d/cert.pem" ]; then ROBOT="$d"; break; fi
    done
    [ -n "$ROBOT" ] || fail "--security: no robot in $SECURITY (make_site_certs.sh DIR ROBOT)"
fi
# The dds: line of participant $1 (base_station or the robot): loopback, unicast, security if asked.
dds() {
    local sec=""
    if [ -n "$SECURITY" ]; then
        sec=", security: {identity_ca: $SECURITY/identity_ca.pem, certificate: $SECURITY/$1/cert.pem"
        sec+=", private_key: $SECURITY/$1/key.pem, permissions_ca: $SECURITY/permissions_ca.pem"
        sec+=", governance: $SECURITY/governance.p7s, permissions: $SECURITY/$1/permissions.p7s}"
    fi
    echo "dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]$sec}"
}
# Runs a host (launch config $1), appending "user+sys CPU seconds" to file $2.
timed_host() {
    local TIMEFORMAT='%U %S'
    { time "$HOST" "$1" --log-level warn; } 2>>"$2.raw"
    tail -n 1 "$2.raw" | awk '{printf "%.2f\n", $1 + $2}' >> "$2"
}
[ -z "$SECURITY" ] || echo "== DDS Security on: site $SECURITY, sink base_station, source $ROBOT"

source_entry="  - {name: source, type: bench_latency_source, params: {points: $POINTS, count: $COUNT, rate_hz: $RATE}}"
sink_entry() { echo "  - {name: sink, type: bench_latency_sink, params: {report: $1}}"; }

echo "== start-up: ltm_host --check on launch_configs/kitti_composed.yaml (10 runs)"
ROOT="$(cd "$BIN/../.." 2>/dev/null && pwd)"
export LTM_ROOT="${LTM_ROOT:-$ROOT}"  # its own line: the next one reads it
export LTM_DATA="${LTM_DATA:-$LTM_ROOT/tests/fixtures/kitti00_mini}" LTM_OUT="$WORK/out"
times=()
for _ in $(seq 10); do
    s=$(date +%s%N); "$HOST" "$LTM_ROOT/launch_configs/kitti_composed.yaml" --check >/dev/null; e=$(date +%s%N)
    times+=($(( (e - s) / 1000000 )))
done
printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR]=$1} END {printf "   process start to all components configured: median %d ms, max %d ms\n", a[int((NR+1)/2)], a[NR]}'

echo "== latency, one process: $COUNT scans of $POINTS points at $RATE Hz"
cat > "$WORK/inproc.yaml" <<YAML
domain_id: $DOMAIN
$(dds base_station)
components:
$source_entry
$(sink_entry "$WORK/inproc.txt")
YAML
timed_host "$WORK/inproc.yaml" "$WORK/inproc.cpu"
echo "   $(cat "$WORK/inproc.txt")"
echo "   CPU: $(cat "$WORK/inproc.cpu") s (user+sys, whole process)"

echo "== latency, two processes on loopback (unicast discovery): same scans"
# With security in the robot's namespace: a robot may publish only there (make_site_certs.sh).
NS_LINE=""; [ -n "$ROBOT" ] && NS_LINE="namespace: /$ROBOT"
cat > "$WORK/pub.yaml" <<YAML
domain_id: $DOMAIN
$NS_LINE
$(dds "${ROBOT:-base_station}")
components:
$source_entry
YAML
cat > "$WORK/sub.yaml" <<YAML
domain_id: $DOMAIN
$NS_LINE
$(dds base_station)
idle_exit_s: 3
components:
$(sink_entry "$WORK/interproc.txt")
YAML
timed_host "$WORK/sub.yaml" "$WORK/sub.cpu" & sub=$!
timed_host "$WORK/pub.yaml" "$WORK/pub.cpu"
wait $sub
echo "   $(cat "$WORK/interproc.txt")"
echo "   CPU: source $(cat "$WORK/pub.cpu") s, sink $(cat "$WORK/sub.cpu") s (user+sys; the sink's includes its 3 s idle exit)"

echo "== idle host: trajectory and cloud writers with no input, 10 s"
cat > "$WORK/idle.yaml" <<YAML
domain_id: $DOMAIN
$(dds base_station)
components:
  - {name: traj, type: trajectory_writer, params: {kitti_file: $WORK/idle.txt}}
  - {name: clouds, type: cloud_writer, params: {dir: $WORK/idle_clouds}}
YAML
"$HOST" "$WORK/idle.yaml" --log-level warn & pid=$!
sleep 2
t0=$(awk '{print $14+$15}' /proc/$pid/stat)
sleep 10
t1=$(awk '{print $14+$15}' /proc/$pid/stat)
kill -TERM $pid; wait $pid || true
hz=$(getconf CLK_TCK)
awk -v d=$((t1 - t0)) -v hz="$hz" 'BEGIN {printf "   CPU: %.2f %% of one core (%.3f s in 10 s)\n", 100 * d / hz / 10, d / hz}'
