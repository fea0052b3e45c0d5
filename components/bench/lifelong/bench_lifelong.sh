#!/usr/bin/env bash
# ./ltm bench lifelong --scenario S --days N [--out D] [--config lifelong|legacy] [--sensor M] [--realtime] [--resume]
# A robot's week on one site: every day (session d of the scenario) runs through a launch config
# and the host (./ltm run, the real components), under /usr/bin/time -v; then `ltm_eval lifelong`
# scores each day against the simulator's truth (ltm_sim --truth-only of the same session) and
# prints one row a day: scans with a map pose, rmse / p95 / max in ONE alignment fitted on day 0's
# final SLAM keyframes, poses more than 0.5 m off, scan time from each kidnap to a correct pose,
# metres of new ground, voxels of removed / moved / added objects in the map the next day
# localises on, static voxels kept, map and maintained state on disk, peak memory, CPU per scan;
# and a figure per day (D/score/dayN.svg).
#   --config lifelong  launch_configs/robot_lifelong.yaml every day (LTM_SITE=D/site): the site's
#                      newest version after day d (D/site/versions/vNNNN/map) is the next map
#   --sensor M         the scans of the simulator's sensor M (os1_64, hdl64e, vlp32c, vlp16,
#                      livox_avia) instead of the scenario's; the presets follow the scans (auto)
#   --realtime         the simulator at the sensor's rate (10 Hz) and the localisation skipping
#                      scans while busy, as on a live robot (default: as fast as the machine goes,
#                      every scan localised); the memory then holds what a robot's does, not the
#                      maintenance's queue of scans a fast run builds up
#   --config legacy    what a user does today: day 0 robot_maintain.yaml (maps), later days
#                      robot_localise_maintain.yaml on day 0's map, the maintained map carried
#                      from day to day (each day starts from a copy of the day before's)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
SCENARIO=""; DAYS=""; OUT=""; CONFIG=""; RESUME=0; SENSOR=""; REALTIME=0
# [s] after the sensor's last scan, for the final maintenance pass and every save (the launch
# configs' 60 s was too short on a shared 2-core machine: site_sessions' day 0, exit 3).
FINISH_S=600
usage() {
    echo "A robot's week on one site through the host, scored day by day against the truth"
    printf 'Usage: ./ltm bench lifelong --scenario S --days N [OPTIONS]\n\nOptions:\n'
    printf '  %-22s%s\n' "-h,--help" "Print this help message and exit" \
        "--scenario S" "the site's scenario (session d = day d), e.g. components/simulator/scenarios/site_week.yaml" \
        "--days N" "days to run (sessions 0..N-1)" \
        "--out D" "the run's folder (default results/lifelong-<time>)" \
        "--config C" "lifelong (default when launch_configs/robot_lifelong.yaml exists) or legacy" \
        "--sensor M" "the simulator's sensor for the scans (os1_64, hdl64e, vlp32c, vlp16, livox_avia)" \
        "--realtime" "the sensor's rate and skip_while_busy, as on a live robot (default: fast)" \
        "--resume" "keep the days of D that ran to the end (D/dayN/exit_status 0)"
}
fail() { echo "ltm bench lifelong: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --resume) RESUME=1; shift ;;
        --realtime) REALTIME=1; shift ;;
        --scenario|--days|--out|--config|--sensor)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --scenario) SCENARIO="$2" ;;
                --days) DAYS="$2" ;;
                --out) OUT="$2" ;;
                --config) CONFIG="$2" ;;
                --sensor) SENSOR="$2" ;;
            esac
            shift 2 ;;
        *) fail "unknown argument '$1' (--help)" ;;
    esac
done
[ -n "$SCENARIO" ] || fail "--scenario: required"
[ -f "$SCENARIO" ] || fail "--scenario: no such file: $SCENARIO"
SCENARIO="$(cd "$(dirname "$SCENARIO")" && pwd)/$(basename "$SCENARIO")"
[ -z "$SENSOR" ] || [[ "$SENSOR" =~ ^[a-z0-9_]+$ ]] || fail "--sensor: a simulator model (os1_64, hdl64e, vlp32c, vlp16, livox_avia), got '$SENSOR'"
[[ "$DAYS" =~ ^[1-9][0-9]*$ ]] || fail "--days: a positive whole number, got '$DAYS'"
LIFELONG_YAML="$ROOT/launch_configs/robot_lifelong.yaml"
if [ -z "$CONFIG" ]; then
    if [ -f "$LIFELONG_YAML" ]; then CONFIG=lifelong; else
        CONFIG=legacy
        echo "ltm bench lifelong: no launch_configs/robot_lifelong.yaml in this version: --config legacy"
    fi
fi
case "$CONFIG" in
    lifelong) [ -f "$LIFELONG_YAML" ] || fail "--config lifelong: no $LIFELONG_YAML in this version" ;;
    legacy) ;;
    *) fail "--config: lifelong or legacy, got '$CONFIG'" ;;
esac
[ -x /usr/bin/time ] || fail "/usr/bin/time is missing (Debian package 'time')"
OUT="${OUT:-$ROOT/results/lifelong-$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$OUT" || fail "--out: cannot create $OUT"
OUT="$(cd "$OUT" && pwd)"
for exe in ltm_host ltm_sim ltm_eval; do
    [ -x "$BIN/$exe" ] || fail "$BIN/$exe is not built (./ltm setup)"
done
SESSIONS=$(grep -cE '^  - name:' "$SCENARIO")
[ "$DAYS" -le "$SESSIONS" ] || fail "--days $DAYS: $SCENARIO has $SESSIONS sessions"
echo "ltm bench lifelong: $DAYS days of $(basename "$SCENARIO")${SENSOR:+ with a $SENSOR}, config $CONFIG, results in $OUT"

# run_day D: the host for day D under /usr/bin/time -v; links what the scoring reads.
run_day() {
    local d="$1" dir="$OUT/day$1" launch rc newest
    local -a env_vars
    env_vars=(LTM_SCENARIO="$SCENARIO" LTM_OUT="$dir")
    if [ "$CONFIG" = legacy ]; then
        if [ "$d" = 0 ]; then
            launch="$ROOT/launch_configs/robot_maintain.yaml"
        else
            launch="$ROOT/launch_configs/robot_localise_maintain.yaml"
            mkdir -p "$dir/maintenance"
            cp "$OUT/day$((d - 1))/maintenance/long_term_map.bin" "$dir/maintenance/long_term_map.bin" ||
                return 1
            env_vars+=(LTM_MAP="$OUT/day0/map"
                       LTM_MAINTAINED_MAP="$dir/maintenance/long_term_map.bin")
        fi
    else
        launch="$LIFELONG_YAML"
        env_vars+=(LTM_SITE="$OUT/site")
    fi
    local start=$SECONDS
    local rate=()
    [ "$REALTIME" = 0 ] || rate=(--set sensor.mode=realtime --set localisation.skip_while_busy=true)
    # A DDS domain of this run's own (LTM_BENCH_DOMAIN): two runs on one machine stay apart.
    env "${env_vars[@]}" /usr/bin/time -v -o "$dir/time.txt" "$ROOT/ltm" run "$launch" \
        --set domain_id="$DOMAIN" \
        --set sensor.session="$d" ${SENSOR:+--set sensor.sensor="$SENSOR"} "${rate[@]}" \
        --set finish_timeout_s="$FINISH_S" --out "$dir" > "$dir/host.log" 2>&1 &
    local run_pid=$!
    sample_memory "$run_pid" "$dir/memory.txt"
    wait "$run_pid"
    rc=$?
    echo "$rc" > "$dir/exit_status"
    echo "  day $d: host exit $rc after $((SECONDS - start)) s ($(basename "$launch")); log $dir/host.log"
    [ "$rc" = 0 ] || return 1
    if [ "$CONFIG" = legacy ]; then
        if [ "$d" = 0 ]; then
            ln -sfn slam_online_tum.txt "$dir/map_poses_tum.txt"
        else
            ln -sfn localisation_tum.txt "$dir/map_poses_tum.txt"
        fi
        ln -sfn "$OUT/day0/map" "$dir/next_map"
        ln -sfn "$dir/maintenance/long_term_map.bin" "$dir/maintained"
    else
        ln -sfn localisation_tum.txt "$dir/map_poses_tum.txt"
        newest=$(ls -d "$OUT/site/versions/v"* 2>/dev/null | sort | tail -n 1)
        [ -n "$newest" ] || { echo "  day $d: no version in $OUT/site/versions" >&2; return 1; }
        # The site keeps a bounded number of versions: the day's map is copied for the scoring.
        rm -rf "$dir/next_map"
        cp -r "$newest/map" "$dir/next_map" || return 1
        ln -sfn "$newest/maintenance" "$dir/maintained"
        echo "$newest" > "$dir/version"
    fi
}

DOMAIN="${LTM_BENCH_DOMAIN:-$((100 + $$ % 100))}"

# The host's resident memory every 0.5 s while the day runs (D/dayN/memory.txt: seconds since the
# start, VmRSS in kB): where in the day the peak falls (the drive, the stop's passes and saves).
sample_memory() {
    local run_pid="$1" file="$2" host="" rss
    echo "# seconds VmRSS_kB (the host of ./ltm run, domain $DOMAIN)" > "$file"
    local start_ns
    start_ns=$(date +%s%N)
    while kill -0 "$run_pid" 2>/dev/null; do
        [ -n "$host" ] && kill -0 "$host" 2>/dev/null ||
            host=$(pgrep -n -f "ltm_host .*domain_id=$DOMAIN " || true)
        if [ -n "$host" ]; then
            rss=$(awk '/^VmRSS/ {print $2}' "/proc/$host/status" 2>/dev/null)
            [ -z "$rss" ] || echo "$(( ($(date +%s%N) - start_ns) / 1000000 )) $rss" |
                awk '{printf "%.1f %d\n", $1 / 1000, $2}' >> "$file"
        fi
        sleep 0.5
    done
}

ran=0
for ((d = 0; d < DAYS; d++)); do
    dir="$OUT/day$d"
    if [ "$RESUME" = 1 ] && [ "$(cat "$dir/exit_status" 2>/dev/null)" = 0 ]; then
        echo "  day $d: kept from an earlier run (--resume)"
    else
        rm -rf "$dir"
        mkdir -p "$dir"
        run_day "$d" || { echo "ltm bench lifelong: day $d failed: $dir/host.log" >&2; break; }
    fi
    "$BIN/ltm_sim" "$SCENARIO" --session "$d" --truth-only ${SENSOR:+--sensor "$SENSOR"} --quiet \
        --out "$dir/truth" ||
        { echo "ltm bench lifelong: ltm_sim --truth-only failed for day $d" >&2; break; }
    ran=$((d + 1))
done
[ "$ran" -ge 1 ] || { echo "ltm bench lifelong: no day ran to the end" >&2; exit 1; }
echo
"$BIN/ltm_eval" lifelong --run "$OUT" --days "$ran" --out "$OUT/score" || exit 1
echo "figures: $OUT/score/day0..$((ran - 1)).svg; numbers: $OUT/score/metrics.json"
[ "$ran" = "$DAYS" ] || exit 1
