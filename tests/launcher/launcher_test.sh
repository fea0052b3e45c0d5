#!/usr/bin/env bash
# The launcher (./ltm) as a user runs it: a signal to the launcher's own pid stops the host and
# leaves a complete recording (no orphan host), options without a value are refused with one line,
# read-only commands never set up or install, `bench list` names every benchmark, and the
# launch configs the launcher uses are valid with the --set arguments it gives them.
# Needs LTM_BUILD_DIR (the CMake build folder). Prints "N passed, N failed".
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
: "${LTM_BUILD_DIR:?set LTM_BUILD_DIR to the build folder}"
export LTM_BUILD_DIR
LTM="$ROOT/ltm"
HOST="$LTM_BUILD_DIR/bin/ltm_host"
MCAP="$LTM_BUILD_DIR/bin/ltm_mcap"
TMP="$(mktemp -d)"
DOMAIN=187
passed=0 failed=0
cleanup() {
    [ -n "${PLAYER_PID:-}" ] && kill "$PLAYER_PID" 2>/dev/null
    rm -rf "$TMP"
}
trap cleanup EXIT

check() {  # check NAME COMMAND...: one test case
    local name="$1"
    shift
    if "$@"; then
        echo "PASS $name"
        passed=$((passed + 1))
    else
        echo "FAIL $name"
        failed=$((failed + 1))
    fi
}

# Waits up to $2 s for pid $1 to end; its exit code in WAIT_RC.
wait_pid() {
    local pid="$1" i
    for ((i = 0; i < $2 * 10; ++i)); do
        if ! kill -0 "$pid" 2>/dev/null; then
            wait "$pid"
            WAIT_RC=$?
            return 0
        fi
        sleep 0.1
    done
    return 1
}

# A publisher of /robot/points on the test domain (the real KITTI fixture, looping at 10 Hz).
start_player() {
    cat > "$TMP/player.yaml" <<EOT
domain_id: $DOMAIN
namespace: /robot
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
exit_when_sources_done: false
components:
  - name: player
    type: kitti_player
    params: {path: "$ROOT/tests/fixtures/kitti00_mini", loop: true}
EOT
    "$HOST" "$TMP/player.yaml" > "$TMP/player.log" 2>&1 &
    PLAYER_PID=$!
}

# record, signal SIG to the launcher's pid: the host (exec'd: the same pid) stops cleanly.
record_then_signal() {
    local sig="$1" out="$TMP/rec_$1.mcap" pid
    "$LTM" record -o "$out" --topics /robot/points --domain "$DOMAIN" --loopback \
        > "$TMP/rec_$sig.log" 2>&1 &
    pid=$!
    sleep 4
    kill -0 "$pid" 2>/dev/null || { echo "  launcher ended early: $(cat "$TMP/rec_$sig.log")"; return 1; }
    kill "-$sig" "$pid"
    if ! wait_pid "$pid" 15; then
        echo "  launcher still running 15 s after SIG$sig"
        kill -9 "$pid"
        return 1
    fi
    [ "$WAIT_RC" = 0 ] || { echo "  exit code $WAIT_RC: $(tail -3 "$TMP/rec_$sig.log")"; return 1; }
    if pgrep -f "recorder.file=$out" > /dev/null; then
        echo "  a host is still recording to $out (orphan)"
        pkill -9 -f "recorder.file=$out"
        return 1
    fi
    # Complete: the MCAP footer magic ends the file and the summary counts messages.
    [ "$(tail -c 8 "$out" | od -An -c | tr -d ' \n')" = '211MCAP0\r\n' ] ||
        { echo "  $out does not end with the MCAP magic"; return 1; }
    local info
    info="$("$MCAP" info "$out")" || { echo "  ltm_mcap info failed"; return 1; }
    local count
    count="$(echo "$info" | awk '/rt\/robot\/points/ {for (i = 1; i <= NF; ++i) if ($i ~ /^[0-9]+$/) {print $i; exit}}')"
    [ "${count:-0}" -ge 5 ] || { echo "  expected at least 5 scans recorded, info says:"; echo "$info"; return 1; }
}

option_without_value() {
    local err rc
    err="$("$LTM" run robot_composed.yaml --out 2>&1)"
    rc=$?
    [ "$rc" = 2 ] && [ "$(echo "$err" | wc -l)" = 1 ] && [[ "$err" == *"--out: needs a value"* ]] ||
        { echo "  rc=$rc: $err"; return 1; }
    err="$("$LTM" record --topics /a -o 2>&1)"
    rc=$?
    [ "$rc" = 2 ] && [[ "$err" == *"-o: needs a value"* ]] || { echo "  rc=$rc: $err"; return 1; }
    err="$("$LTM" replay x.mcap --remap /a 2>&1)"
    rc=$?
    [ "$rc" = 2 ] && [[ "$err" == *"FROM:=TO"* ]] || { echo "  rc=$rc: $err"; return 1; }
}

readonly_never_sets_up() {
    local err rc
    err="$(LTM_BUILD_DIR="$TMP/empty_build" "$LTM" info "$TMP/none.mcap" 2>&1)"
    rc=$?
    [ "$rc" = 1 ] && [[ "$err" == *"is not built"*"./ltm setup"* ]] || { echo "  rc=$rc: $err"; return 1; }
    [ ! -e "$TMP/empty_build/build.ninja" ] || { echo "  info configured a build"; return 1; }
    err="$(LTM_BUILD_DIR="$TMP/empty_build" "$LTM" components 2>&1)"
    rc=$?
    [ "$rc" = 1 ] && [[ "$err" == *"is not built"* ]] || { echo "  rc=$rc: $err"; return 1; }
}

bench_list_names_every_benchmark() {
    local list name
    list="$("$LTM" bench list)" || return 1
    for name in dds odometry slam localise localise_real mcap sim sim_compare hard_cases stop site lifelong; do
        grep -q "^  $name " <<< "$list" || { echo "  '$name' missing from: $list"; return 1; }
    done
    local err rc
    err="$("$LTM" bench nosuch 2>&1)"
    rc=$?
    [ "$rc" = 1 ] && [[ "$err" == *"no benchmark 'nosuch'"* ]] || { echo "  rc=$rc: $err"; return 1; }
}

# The lifelong benchmark refuses a bad command line in one line (exit 2), before running anything.
bench_lifelong_refuses_bad_arguments() {
    local script="$ROOT/components/bench/lifelong/bench_lifelong.sh" err rc args
    local scenario="$ROOT/components/simulator/scenarios/tiny_loop.yaml"
    for args in "--days 2" "--scenario $TMP/none.yaml --days 2" "--scenario $scenario --days 0" \
        "--scenario $scenario --days 3" "--scenario $scenario --days 1 --config nightly" "--frobnicate"; do
        # shellcheck disable=SC2086
        err="$(bash "$script" $args --out "$TMP/lifelong" 2>&1 >/dev/null)"
        rc=$?
        [ "$rc" = 2 ] && [ "$(echo "$err" | wc -l)" = 1 ] && [[ "$err" == "ltm bench lifelong: "* ]] ||
            { echo "  $args: rc=$rc: $err"; return 1; }
    done
    [ ! -e "$TMP/lifelong/day0" ] || { echo "  a day ran"; return 1; }
}

# The KISS-ICP comparison (a script) without the shared data: skips, builds nothing, exits 0.
bench_hard_cases_skips_without_data() {
    local out rc
    out="$(LTM_SHARED_DATA="$TMP/no_data" KISS_ICP_BUILD="$TMP/kiss_build" "$LTM" bench hard_cases 2>&1)"
    rc=$?
    [ "$rc" = 0 ] && [[ "$out" == *"no shared data at $TMP/no_data"*"no cases to run"* ]] ||
        { echo "  rc=$rc: $out"; return 1; }
    [ ! -e "$TMP/kiss_build" ] || { echo "  built KISS-ICP with nothing to run"; return 1; }
    out="$("$LTM" bench hard_cases --bogus 2>&1)"
    rc=$?
    [ "$rc" = 1 ] && [ "$(echo "$out" | wc -l)" = 1 ] && [[ "$out" == *"unknown option '--bogus'"* ]] ||
        { echo "  rc=$rc: $out"; return 1; }
}

# The localisation real-data script without the shared data: skips and exits 0.
bench_localise_real_skips_without_data() {
    local out rc
    out="$(LTM_SHARED_DATA="$TMP/no_data" "$LTM" bench localise_real 2>&1)"
    rc=$?
    [ "$rc" = 0 ] && [[ "$out" == *"no shared data under $TMP/no_data"*"skipped"* ]] ||
        { echo "  rc=$rc: $out"; return 1; }
}

tool_launch_configs_are_valid() {
    touch "$TMP/some.mcap.parent"
    "$HOST" "$ROOT/launch_configs/tools/recorder.yaml" --check --set "recorder.file=$TMP/x.mcap" \
        --set 'recorder.topics=["/robot/points"]' --set recorder.all=false \
        --set 'dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}' > /dev/null || return 1
    "$HOST" "$ROOT/launch_configs/tools/map_request.yaml" --check --set map_request.command=save \
        --set "map_request.map_dir=$TMP/map" > /dev/null || return 1
    "$HOST" "$ROOT/launch_configs/tools/map_request.yaml" --check --set map_request.command=mesh \
        --set "map_request.mesh_file=$TMP/mesh.ply" > /dev/null || return 1
    local rec="$TMP/rec_TERM.mcap"
    [ -f "$rec" ] || rec="$TMP/rec_INT.mcap"
    "$HOST" "$ROOT/launch_configs/tools/replayer.yaml" --check --set "replayer.file=$rec" \
        --set replayer.fast=true --set 'replayer.remap./robot/points=/other/points' > /dev/null || return 1
}

"$HOST" --list-components > /dev/null 2>&1 || { echo "ltm_host not built in $LTM_BUILD_DIR"; exit 1; }
start_player
check "SIGTERM to the launcher's pid stops the recording host, file complete" record_then_signal TERM
check "SIGINT to the launcher's pid (a background job) stops the host, file complete" record_then_signal INT
check "an option without its value is refused with one line, exit 2" option_without_value
check "read-only commands never set up or install" readonly_never_sets_up
check "bench list names every benchmark" bench_list_names_every_benchmark
check "bench lifelong refuses bad arguments" bench_lifelong_refuses_bad_arguments
check "bench hard_cases skips without the shared data" bench_hard_cases_skips_without_data
check "bench localise_real skips without the shared data" bench_localise_real_skips_without_data
check "the launch configs of record, replay and map are valid" tool_launch_configs_are_valid
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
