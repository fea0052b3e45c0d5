#!/usr/bin/env bash
# The shipped systemd units (launch_configs/systemd/): valid for systemd-analyze (with this
# checkout's paths in place of /opt/ltm), Type=notify with a watchdog, a stop timeout above the
# host's stop deadline, and the launch config each starts passes `ltm_host --check`. What the
# host does under such a unit (READY, WATCHDOG, STOPPING, exit 0 after SIGTERM) is
# HostTest.SystemdNotifyReadyWatchdogAndStop.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
deadline=$(sed -n 's/.*double shutdown_timeout_s = \([0-9.]*\);.*/\1/p' "$ROOT/runtime/launch_config.hpp")
[ -n "$deadline" ] || fail "cannot read the default stop deadline from runtime/launch_config.hpp"
for unit in "$ROOT"/launch_configs/systemd/*.service; do
    name="$(basename "$unit")"
    value() { sed -n "s/^$1=//p" "$unit" | tail -n 1; }
    [ "$(value Type)" = notify ] || fail "$name: Type is not notify"
    [ -n "$(value WatchdogSec)" ] || fail "$name: no WatchdogSec"
    stop="$(value TimeoutStopSec)"
    awk -v s="$stop" -v d="$deadline" 'BEGIN {exit !(s + 0 >= d + 10)}' ||
        fail "$name: TimeoutStopSec=$stop is not the stop deadline ($deadline s) plus a margin"
    # This checkout in place of the image's /opt/ltm.
    sed -e "s|/opt/ltm/bin|$BUILD/bin|g" -e "s|/opt/ltm|$ROOT|g" -e "s|/var/lib/ltm|$T|g" \
        -e '/^StateDirectory=/d' "$unit" > "$T/$name"
    exec_start="$(sed -n 's/^ExecStart=//p' "$T/$name")"
    # shellcheck disable=SC2086
    LTM_OUT="$T/out" LTM_DATA="$ROOT/tests/fixtures/kitti00_mini" $exec_start --check > "$T/check.log" 2>&1 ||
        fail "$name: $exec_start --check: $(tail -n 1 "$T/check.log")"
    if command -v systemd-analyze > /dev/null; then
        # Only the unit's own problems (not the machine's other units, nor a missing systemd).
        out="$(SYSTEMD_LOG_LEVEL=warning systemd-analyze verify "$T/$name" 2>&1 | grep -F "$name" || true)"
        [ -z "$out" ] || fail "$name: systemd-analyze verify: $out"
    else
        echo "note: systemd-analyze is not installed; $name checked without it"
    fi
    echo "ok   $name"
done
[ "$fails" = 0 ]
