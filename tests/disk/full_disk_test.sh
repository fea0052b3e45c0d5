#!/usr/bin/env bash
# The recorder and the disk (issue 28, item 4), through the host: a folder of recordings kept
# within the launch config's budget (the oldest whole files removed, never the one being
# written), a recording that alone outgrows it stopped cleanly, and a full disk (a small tmpfs)
# and a free-space floor each said in ONE line with the file closed and readable (ltm_mcap
# verify). The tmpfs cases need root (mount); without it they are skipped (exit 77) with the reason.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
HOST="$BUILD/bin/ltm_host"
MCAP="$BUILD/bin/ltm_mcap"
DOMAIN=189
TMP="$(mktemp -d /tmp/ltm_full_disk.XXXXXX)"
cleanup() {  # the mounts are listed in a file: each check runs in a subshell
    [ -f "$TMP/mounts" ] && while read -r m; do umount -l "$m" 2>/dev/null; done < "$TMP/mounts"
    rm -rf "$TMP"
}
trap cleanup EXIT
for f in "$HOST" "$MCAP"; do [ -x "$f" ] || { echo "SKIPPED: $f is not built"; exit 77; }; done

# run_recorder NAME SECONDS PARAMS...: a KITTI fixture player (looping, 10 Hz) and a recorder of
# /robot/points in one host for SECONDS, then SIGINT; the log in $TMP/NAME.log, the exit code in RC.
run_recorder() {
    local name="$1" seconds="$2"; shift 2
    {
        echo "domain_id: $DOMAIN"
        echo "namespace: /robot"
        echo "dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}"
        echo "exit_when_sources_done: false"
        echo "components:"
        echo "  - name: player"
        echo "    type: kitti_player"
        echo "    params: {path: \"$ROOT/tests/fixtures/kitti00_mini\", loop: true, rate: 3}"
        echo "  - name: recorder"
        echo "    type: recorder"
        echo "    params:"
        echo "      topics: [points]"
        for kv in "$@"; do echo "      $kv"; done
    } > "$TMP/$name.yaml"
    "$HOST" "$TMP/$name.yaml" > "$TMP/$name.log" 2>&1 &
    local pid=$!
    sleep "$seconds"
    cp "$TMP/$name.log" "$TMP/$name.before"  # what it said while running (the stop sums up)
    kill -INT "$pid"
    wait "$pid"; RC=$?
}
fails=0
check() {  # check NAME FUNCTION
    local out rc
    out="$("$2" 2>&1)"; rc=$?
    if [ "$rc" = 0 ]; then echo "ok   $1"
    elif [ "$rc" = 77 ]; then echo "skip $1: ${out##*SKIPPED: }"
    else echo "FAIL $1"; echo "${out//$'\n'/$'\n'     }"; fails=$((fails + 1)); fi
}
readable() {  # readable FILE: closed properly, CRCs and indexes whole, messages in it
    "$MCAP" verify "$1" > "$TMP/verify.txt" 2>&1 || { echo "ltm_mcap verify $1:"; cat "$TMP/verify.txt"; return 1; }
    "$MCAP" info "$1" | grep -q 'rt/robot/points' || { echo "no scans in $1"; return 1; }
}
small_disk() {  # small_disk DIR SIZE: a tmpfs, or exit 77
    mkdir -p "$1"
    [ "$(id -u)" -eq 0 ] || { echo "SKIPPED: needs root to mount a small tmpfs"; exit 77; }
    mount -t tmpfs -o "size=$2" ltm_full_disk "$1" 2>"$TMP/mount.err" ||
        { echo "SKIPPED: cannot mount a tmpfs here: $(cat "$TMP/mount.err")"; exit 77; }
    echo "$1" >> "$TMP/mounts"
}

# Yesterday's and older recordings (sparse files: their size counts) beside today's.
oldest_recordings_go_first() {
    local d="$TMP/budget"
    mkdir -p "$d/day1" "$d/day2" "$d/day3" "$d/day4"
    truncate -s 30M "$d/day1/lifelong.mcap"; touch -d '3 days ago' "$d/day1/lifelong.mcap"
    truncate -s 20M "$d/day2/lifelong.mcap"; touch -d '2 days ago' "$d/day2/lifelong.mcap"
    truncate -s 10M "$d/day3/lifelong.mcap"; touch -d '1 day ago' "$d/day3/lifelong.mcap"
    run_recorder budget 3 "file: $d/day4/lifelong.mcap" "budget_dir: $d" "max_total_mb: 50"
    [ "$RC" = 0 ] || { echo "exit code $RC"; cat "$TMP/budget.log"; return 1; }
    [ ! -e "$d/day1/lifelong.mcap" ] || { echo "the oldest recording is still there"; return 1; }
    [ -e "$d/day2/lifelong.mcap" ] && [ -e "$d/day3/lifelong.mcap" ] ||
        { echo "a newer recording was removed"; ls -R "$d"; return 1; }
    grep -q '\[recorder\] removed 1 recording (30 MiB, oldest first: lifelong.mcap); 3 kept' "$TMP/budget.log" ||
        { echo "no one-line report of the removal:"; cat "$TMP/budget.log"; return 1; }
    readable "$d/day4/lifelong.mcap"
}

# A recording that alone outgrows the budget stops (one line), closed and readable.
a_recording_over_the_budget_stops() {
    local d="$TMP/over"
    run_recorder over 7 "file: $d/rec.mcap" "max_total_mb: 1"
    [ "$RC" = 0 ] || { echo "exit code $RC"; cat "$TMP/over.log"; return 1; }
    [ "$(grep -c 'recording stopped: this recording alone is [0-9]* MiB, over max_total_mb 1' "$TMP/over.log")" = 1 ] ||
        { echo "expected one 'recording stopped' line:"; cat "$TMP/over.log"; return 1; }
    readable "$d/rec.mcap"
}

# A full disk: one line from the recorder, the file closed with its summary (readable), the
# host's exit code 4 names the recording NOT saved whole.
a_full_disk_is_one_line_and_the_file_stays_readable() {
    local m="$TMP/small"
    small_disk "$m" 3M
    run_recorder full 6 "file: $m/rec.mcap" "min_free_mb: 0"
    [ "$RC" = 4 ] || { echo "exit code $RC, expected 4 (NOT saved)"; cat "$TMP/full.log"; return 1; }
    local lines
    lines="$(grep -c 'disk full' "$TMP/full.before")"
    [ "$lines" = 1 ] || { echo "expected one line saying the disk is full, got $lines:"; cat "$TMP/full.log"; return 1; }
    grep -q "NOT saved: recording.*disk full" "$TMP/full.log" || { echo "no NOT saved line:"; cat "$TMP/full.log"; return 1; }
    readable "$m/rec.mcap"
}

# The free-space floor: recording stops before the disk is full, leaving the room to the map.
the_free_space_floor_stops_the_recording() {
    local m="$TMP/floor"
    small_disk "$m" 64M
    run_recorder floor 7 "file: $m/rec.mcap" "min_free_mb: 40"
    [ "$RC" = 0 ] || { echo "exit code $RC"; cat "$TMP/floor.log"; return 1; }
    [ "$(grep -c 'recording stopped: [0-9]* MiB free on the disk, under min_free_mb 40' "$TMP/floor.log")" = 1 ] ||
        { echo "expected one 'recording stopped' line:"; cat "$TMP/floor.log"; return 1; }
    grep -q 'disk full' "$TMP/floor.log" && { echo "the disk filled:"; cat "$TMP/floor.log"; return 1; }
    [ "$(df -k --output=avail "$m" | tail -1)" -gt 16384 ] || { echo "the floor did not keep the room"; return 1; }
    readable "$m/rec.mcap"
}

check "the oldest recordings go first, never today's" oldest_recordings_go_first
check "a recording alone over the budget stops, readable" a_recording_over_the_budget_stops
check "a full disk is one line, the recording readable" a_full_disk_is_one_line_and_the_file_stays_readable
check "the free-space floor stops the recording" the_free_space_floor_stops_the_recording
[ "$fails" = 0 ]
