#!/usr/bin/env bash
# The robot and the base station over a lossy link (issue 15): tiny_loop through robot.yaml and
# base_station.yaml in two network namespaces, 5 % of the frames dropped each way, every keyframe
# and local map must arrive once; an outage and a base-station crash and restart in one run must
# lose nothing, apply nothing twice and leave the base station with the composed run's map; with
# DDS Security a participant without credentials on a third link hears nothing; a run stopped
# half-way must leave no namespace behind. Needs root, network namespaces and nft:
# skipped (exit 77) with the reason otherwise.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BENCH="$ROOT/components/bench/link/bench_link.sh"
skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "needs root (network namespaces, nftables, tc)"
command -v nft >/dev/null || skip "nft is not installed (./ltm setup installs nftables)"
probe="ltm_link_probe_$$"
ip netns add "$probe" 2>/dev/null || skip "network namespaces are not available here"
# Entering one needs a mount namespace of its own (in a chroot whose / is no mount point it fails).
err="$(ip netns exec "$probe" true 2>&1)"; rc=$?
ip netns del "$probe"
[ "$rc" = 0 ] || skip "network namespaces cannot be entered here (ip netns exec: ${err//$'\n'/ })"

fails=0
check() {  # check NAME FUNCTION
    local out
    if out="$("$2" 2>&1)"; then
        echo "ok   $1"
    else
        echo "FAIL $1"; echo "${out//$'\n'/$'\n'     }"; fails=$((fails + 1))
    fi
}
namespaces() { ip netns list | grep -c '^ltm_' || true; }
# all_delivered TOPIC < bench output: every message of robot/TOPIC sent was delivered, once. The
# robot's own recorder finds the topics by discovery and can miss a topic's first message; the
# bench then counts what only the base station recorded as sent and says so in brackets.
all_delivered() {
    grep -Eq "^   robot/$1 +sent +([1-9][0-9]*) .*delivered +\\1 +late +[0-9]+ +missing 0( \\[[0-9]+ only in the base station's recording\\])?\$"
}

every_local_map_at_5_percent_loss() {
    local out rc
    out="$(bash "$BENCH" --loss 5 --require local_map --require keyframe 2>&1)"; rc=$?
    echo "$out"
    [ "$rc" = 0 ] || return 1
    # Frames were really dropped, and local maps and keyframes were really sent (and all
    # delivered, once).
    echo "$out" | grep -Eq 'frames dropped for loss: [1-9][0-9]* robot -> base' || return 1
    echo "$out" | all_delivered local_map || return 1
    echo "$out" | all_delivered keyframe
}

# tiny_loop played at half speed (~16 s, so that a loaded machine's odometry still takes every
# scan, as the composed run does): the link is cut from 4 s to 10 s, the base station is killed at
# 12 s and started again (its journal replayed, the robot's backlog resent).
outage_and_restart_lose_nothing() {
    local out rc
    out="$(bash "$BENCH" --loss 1 --outage 6@4 --restart-base 12 --robot-set player.rate=0.5 \
        --require local_map --require keyframe --require-same-map 2>&1)"; rc=$?
    echo "$out"
    [ "$rc" = 0 ] || return 1
    grep -q 'base station killed (SIGKILL)' <<< "$out" || return 1
    echo "$out" | grep -Eq 'replayed from the journal' || return 1
    grep -q '^   same map$' <<< "$out"
}

# DDS Security on the link: an intruder on a link of its own, without the site's credentials,
# hears nothing while the robot's messages all arrive; without security the same intruder hears
# the topics (the check can fail).
intruder_hears_nothing_with_security() {
    local out rc
    out="$(bash "$BENCH" --intruder --frames 0:15 2>&1)"; rc=$?
    echo "$out"
    [ "$rc" = 0 ] || return 1
    echo "$out" | grep -Eq 'without credentials .*: [1-9][0-9]* messages received' || return 1
    out="$(bash "$BENCH" --security --require keyframe --require local_map 2>&1)"; rc=$?
    echo "$out"
    [ "$rc" = 0 ] || return 1
    echo "$out" | grep -Eq 'without credentials .*: 0 messages received' || return 1
    echo "$out" | all_delivered keyframe
}

stopped_run_cleans_up() {
    local before rc
    before="$(namespaces)"
    timeout --preserve-status -s INT 5 bash "$BENCH" --loss 1; rc=$?
    [ "$rc" = 130 ] || { echo "exit code $rc, expected 130 (SIGINT)"; return 1; }
    [ "$(namespaces)" = "$before" ] || { echo "namespaces left: $(ip netns list)"; return 1; }
}

usage_errors_are_one_line() {
    local err rc
    err="$(bash "$BENCH" --loss 120 2>&1)"; rc=$?
    if [ "$rc" != 2 ] || [ "$err" != "ltm bench link: --loss: expected a percentage 0..100, got '120'" ]; then
        echo "rc=$rc: $err"; return 1
    fi
    err="$(bash "$BENCH" --outage 30 2>&1)"; rc=$?
    if [ "$rc" != 2 ] || [ "$err" != "ltm bench link: --outage: expected SECONDS@START (30@20), got '30'" ]; then
        echo "rc=$rc: $err"; return 1
    fi
}

check "usage errors are one line" usage_errors_are_one_line
check "every local map arrives at 5 % loss" every_local_map_at_5_percent_loss
check "an outage and a base-station restart lose nothing" outage_and_restart_lose_nothing
check "an intruder hears nothing with DDS Security" intruder_hears_nothing_with_security
check "a run stopped with SIGINT leaves no namespace" stopped_run_cleans_up
[ "$fails" = 0 ]
