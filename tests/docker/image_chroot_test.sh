#!/usr/bin/env bash
# The built images run (issue 29 item 4): the robot image's and the base-station image's entry
# points run from their exported file systems by chroot (`./ltm image run --chroot`: this
# sandbox refuses `podman run`, docker/README.md). The robot image runs kitti_composed.yaml on its
# built-in KITTI scans and must stop cleanly with every scan's pose saved on the host; the
# base station starts and stops cleanly on SIGINT. Never builds an image: skipped (exit 77) with
# the reason where podman, root or the two images (`./ltm image build all`) are missing.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "needs root (chroot into an exported image)"
command -v podman > /dev/null || skip "podman is not installed"
for image in localhost/ltm-robot localhost/ltm-base-station; do
    podman image exists "$image" 2> /dev/null ||
        skip "no image $image here (./ltm image build all makes both, ~10 min with ccache)"
done
OUT="$(mktemp -d /tmp/ltm_image_chroot.XXXXXX)"
trap 'rm -rf "$OUT"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }

# The robot: three KITTI scans through the composed pipeline, results on the host.
"$ROOT/ltm" image run robot --chroot --results "$OUT/robot" -- \
    /opt/ltm/launch_configs/kitti_composed.yaml --set domain_id=193 > "$OUT/robot.log" 2>&1
rc=$?
if [ "$rc" != 0 ] || ! grep -q "stopped cleanly" "$OUT/robot.log"; then
    fail "robot image: exit $rc"; tail -20 "$OUT/robot.log"
elif [ "$(grep -c . "$OUT/robot/odometry.txt" 2> /dev/null)" != 3 ]; then
    fail "robot image: $OUT/robot/odometry.txt has not the 3 scans' poses"
else
    echo "ok   robot image: kitti_composed.yaml ran by chroot, 3 poses on the host, stopped cleanly"
fi

# The base station: up, then SIGINT; a clean stop is exit 0.
timeout --preserve-status -s INT 8 "$ROOT/ltm" image run base-station --chroot \
    --results "$OUT/base" -- /opt/ltm/launch_configs/base_station.yaml --set domain_id=193 \
    > "$OUT/base.log" 2>&1
rc=$?
if [ "$rc" != 0 ] || ! grep -q "received SIGINT" "$OUT/base.log" ||
    ! grep -q "stopped cleanly" "$OUT/base.log"; then
    fail "base-station image: exit $rc"; tail -20 "$OUT/base.log"
else
    echo "ok   base-station image: base_station.yaml ran by chroot and stopped cleanly on SIGINT"
fi
# Nothing of the chroot stays mounted.
if mount | grep -q "/var/tmp/ltm-image-"; then fail "mounts left: $(mount | grep /var/tmp/ltm-image-)"; fi
[ "$fails" = 0 ]
