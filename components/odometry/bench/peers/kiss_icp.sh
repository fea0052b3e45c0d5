#!/usr/bin/env bash
# KISS-ICP as a side-by-side peer of ltm's odometry: builds KISS-ICP's C++ core and pipeline from a
# snapshot of its public repository (github.com/PRBonn/kiss-icp) together with ltm's runner
# (kiss_icp_runner.cpp, CMakeLists.txt beside this script) in a build folder OUTSIDE the
# repository, then runs the runner on a scan folder. Nothing of KISS-ICP is part of ltm.
#
#   kiss_icp.sh [--source DIR] [--sophus DIR] [--build-dir DIR] build
#   kiss_icp.sh [--source DIR] [--sophus DIR] [--build-dir DIR] path    # build, print the runner
#   kiss_icp.sh [--source DIR] [--sophus DIR] [--build-dir DIR] SCAN_DIR [RUNNER ARGS]
#                                  (kiss_icp.sh --help-runner: the runner's own options)
#
# Where things are (options win over the environment, which wins over the defaults; OUT is the
# folder that holds the ltm checkout):
#   KISS-ICP source   --source, KISS_ICP_SOURCE   default OUT/peers/kiss-icp-src
#   Sophus source     --sophus, SOPHUS_SOURCE     default OUT/peers/sophus-src
#   build folder      --build-dir, KISS_ICP_BUILD default OUT/peers/kiss-icp-build
# A missing source folder is unpacked from a bare git mirror when there is one (KISS_ICP_GIT,
# default OUT/.mirror/PRBonn+kiss-icp/repo, its HEAD; SOPHUS_GIT, default
# OUT/.mirror/strasdat+Sophus/repo, tag 1.24.6, the version KISS-ICP pins); otherwise put a
# checkout there. Sophus is only needed when no Sophus is installed (Debian 12 has no package).
# Debian packages the build needs (not dependencies of ltm): cmake ninja-build g++ libeigen3-dev
# libtbb-dev robin-map-dev; missing ones are installed with apt-get (as root or through sudo).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="$(dirname "$(cd "$HERE/../../../.." && pwd)")"  # the folder that holds the checkout
SOURCE="${KISS_ICP_SOURCE:-$OUT/peers/kiss-icp-src}"
SOPHUS="${SOPHUS_SOURCE:-$OUT/peers/sophus-src}"
BUILD="${KISS_ICP_BUILD:-$OUT/peers/kiss-icp-build}"
KISS_GIT="${KISS_ICP_GIT:-$OUT/.mirror/PRBonn+kiss-icp/repo}"
SOPHUS_GIT_DIR="${SOPHUS_GIT:-$OUT/.mirror/strasdat+Sophus/repo}"
SOPHUS_TAG=1.24.6
PACKAGES=(cmake ninja-build g++ libeigen3-dev libtbb-dev robin-map-dev)

say() { printf 'kiss_icp.sh: %s\n' "$*" >&2; }
die() { printf 'kiss_icp.sh: error: %s\n' "$*" >&2; exit 1; }

while [ $# -gt 0 ]; do
    case "$1" in
        --source|--sophus|--build-dir)
            [ $# -ge 2 ] || die "$1 needs a folder"
            case "$1" in
                --source) SOURCE="$2" ;;
                --sophus) SOPHUS="$2" ;;
                --build-dir) BUILD="$2" ;;
            esac
            shift 2 ;;
        -h|--help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) break ;;
    esac
done
[ $# -ge 1 ] || die "usage: kiss_icp.sh [--source DIR] [--sophus DIR] [--build-dir DIR] build|path|SCAN_DIR [ARGS] (--help)"

install_packages() {
    local missing=() p
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    say "the KISS-ICP peer build needs Debian packages that are missing (not dependencies of ltm): ${missing[*]}; installing them"
    local sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || die "not root and no sudo: install ${missing[*]} first"
        sudo="sudo"
    fi
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q >/dev/null
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
}

# unpack GIT_DIR REV DEST: a source tree from a bare git mirror, its commit in DEST/SNAPSHOT_COMMIT.
unpack() {
    local git_dir="$1" rev="$2" dest="$3" commit
    commit="$(git --git-dir="$git_dir" rev-parse "$rev^{commit}")" || die "$git_dir: no $rev"
    say "unpacking $git_dir at $rev ($commit) into $dest"
    mkdir -p "$dest"
    git --git-dir="$git_dir" archive "$commit" | tar -x -C "$dest"
    echo "$commit" > "$dest/SNAPSHOT_COMMIT"
}

sources() {
    if [ ! -f "$SOURCE/cpp/kiss_icp/CMakeLists.txt" ]; then
        [ -d "$KISS_GIT" ] || die "no KISS-ICP source in $SOURCE (no cpp/kiss_icp/CMakeLists.txt) and no mirror $KISS_GIT: put a checkout of github.com/PRBonn/kiss-icp there or give --source"
        unpack "$KISS_GIT" HEAD "$SOURCE"
    fi
    # Sophus: from a mirror when there is no source tree; an installed Sophus (found by CMake) makes
    # it unnecessary, and CMake says so when neither is there.
    if [ ! -f "$SOPHUS/sophus/se3.hpp" ] && [ -d "$SOPHUS_GIT_DIR" ]; then
        unpack "$SOPHUS_GIT_DIR" "$SOPHUS_TAG" "$SOPHUS"
    fi
}

# build: configure once, then an incremental build (quiet unless it fails).
build() {
    install_packages
    sources
    local log="$BUILD/build.log"
    mkdir -p "$BUILD"
    if [ ! -f "$BUILD/build.ninja" ] ||
        ! grep -qxF "KISS_ICP_SOURCE:PATH=$SOURCE" "$BUILD/CMakeCache.txt" 2>/dev/null; then
        say "configuring KISS-ICP ($SOURCE) and the runner in $BUILD (Release)"
        cmake -S "$HERE" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DKISS_ICP_SOURCE="$SOURCE" -DSOPHUS_SOURCE="$SOPHUS" > "$log" 2>&1 \
            || { cat "$log" >&2; die "configuring failed (log above, $log)"; }
    fi
    cmake --build "$BUILD" --target kiss_icp_runner -- -j "${LTM_JOBS:-$(nproc)}" > "$log" 2>&1 \
        || { cat "$log" >&2; die "building failed (log above, $log)"; }
    [ -x "$BUILD/kiss_icp_runner" ] || die "no runner in $BUILD after the build"
}

case "$1" in
    build)
        build
        commit="$(cat "$SOURCE/SNAPSHOT_COMMIT" 2>/dev/null || git -C "$SOURCE" rev-parse HEAD 2>/dev/null || echo "unknown")"
        say "built $BUILD/kiss_icp_runner from KISS-ICP $SOURCE (commit $commit)" ;;
    path) build; echo "$BUILD/kiss_icp_runner" ;;
    --help-runner) build; exec "$BUILD/kiss_icp_runner" --help ;;
    -*) die "unknown option '$1' (--help)" ;;
    *) build; exec "$BUILD/kiss_icp_runner" "$@" ;;
esac
