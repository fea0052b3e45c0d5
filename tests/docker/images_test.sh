#!/usr/bin/env bash
# The images' recipe, checked without building an image (docker/README.md):
#  - the Dockerfile's stages; its build stage installs debian-packages.txt (minus the lines marked
#    "not in the images") and its runtime stage runtime-packages.txt, no package named elsewhere;
#  - runtime-packages.txt holds no -dev package and no compiler, only packages Debian knows, and
#    every library the installed programs are linked against (NEEDED) comes from one of them;
#  - `cmake --install` of this build holds every program the Dockerfile builds and every path the
#    Dockerfile, compose.yaml and the systemd units name under /opt/ltm, and the entry points'
#    launch configs pass `ltm_host --check` from the install tree with the image's environment.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${LTM_BUILD_DIR:-$ROOT/build}"
D="$ROOT/docker"
T="$(mktemp -d)"; trap 'rm -rf "$T"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
section=0
ok() { [ "$fails" != "$section" ] || echo "ok   $*"; section=$fails; }
packages() { sed -e 's/#.*//' -e 's/[[:space:]]//g' "$1" | sed '/^$/d'; }

# 1. Stages and what each installs.
for stage in build runtime robot base-station; do
    grep -qE "^FROM .* AS $stage\$" "$D/Dockerfile" || fail "Dockerfile: no stage '$stage'"
done
installs="$(grep -c 'apt-get install' "$D/Dockerfile")"
[ "$installs" = 2 ] || fail "Dockerfile: $installs apt-get install lines (the build and runtime stages: 2)"
grep -q "grep -v 'not in the images' /tmp/debian-packages.txt" "$D/Dockerfile" ||
    fail "Dockerfile: the build stage does not install debian-packages.txt"
grep -qF "sed -e 's/#.*//' /tmp/runtime-packages.txt | xargs apt-get install" "$D/Dockerfile" ||
    fail "Dockerfile: the runtime stage does not install runtime-packages.txt"
# Package names written out in an install line (only ccache, the build stage's compiler cache).
extra="$(grep -A2 'apt-get install' "$D/Dockerfile" | grep -oE 'install -y -q --no-install-recommends( [a-z0-9][a-z0-9.+-]*)*' |
    sed 's/.*--no-install-recommends//' | tr ' ' '\n' | sed '/^$/d' | grep -vx ccache || true)"
[ -z "$extra" ] || fail "Dockerfile: packages outside the lists: $extra"
ok "Dockerfile stages install debian-packages.txt and runtime-packages.txt"

# 2. The runtime list.
bad="$(packages "$D/runtime-packages.txt" | grep -E -- '-dev$|^(build-essential|cmake|ninja-build|g\+\+.*|gcc.*|clang.*)$' || true)"
[ -z "$bad" ] || fail "runtime-packages.txt: build packages: $bad"
apt-cache pkgnames > "$T/known" 2> /dev/null  # this machine's package lists, no network
if grep -qx libc6 "$T/known"; then
    for p in $(packages "$D/runtime-packages.txt") $(packages "$D/debian-packages.txt"); do
        grep -qxF "$p" "$T/known" || fail "no Debian package '$p' (apt-cache pkgnames)"
    done
    ok "every listed package is known to apt"
else
    echo "note: no apt-cache with package lists: package names not checked"
fi

# 3. The install tree.
programs="$(sed -n '/^set(LTM_INSTALL_PROGRAMS/,/)/p' "$ROOT/cmake/LtmInstall.cmake" | grep -oE 'ltm_[a-z_]+' | grep -v LTM_INSTALL)"
targets="$(grep -oE -- '--target( ltm_[a-z_]+)+' "$D/Dockerfile" | sed 's/--target//' | tr ' ' '\n' | sed '/^$/d')"
[ "$(sort <<< "$programs")" = "$(sort <<< "$targets")" ] ||
    fail "the Dockerfile builds [$(echo $targets)], cmake/LtmInstall.cmake installs [$(echo $programs)]"
missing_built=""
for p in $programs; do [ -x "$BUILD/bin/$p" ] || missing_built+=" $p"; done
if [ -n "$missing_built" ]; then
    echo "note: not built in $BUILD:$missing_built; the install tree is not checked"
else
    P="$T/opt/ltm"
    cmake --install "$BUILD" --prefix "$P" > "$T/install.log" 2>&1 ||
        fail "cmake --install: $(tail -n 1 "$T/install.log")"
    for p in $programs; do [ -x "$P/bin/$p" ] || fail "install tree: no bin/$p"; done
    # Every /opt/ltm path the recipe and the units name.
    for f in "$D/Dockerfile" "$D/compose.yaml" "$ROOT"/launch_configs/systemd/*.service; do
        for path in $(grep -v '^ *#' "$f" | grep -oE '/opt/ltm(/[A-Za-z0-9_.-]+)*' | sort -u); do
            [ -e "$P${path#/opt/ltm}" ] || fail "$(basename "$f") names $path: not in the install tree"
        done
    done
    ok "the install tree holds every program and path the Dockerfile, compose.yaml and the units name"
    # The libraries come from the runtime list.
    if command -v dpkg > /dev/null && command -v objdump > /dev/null; then
        # program soname path, for every library a program names (NEEDED), then one dpkg -S.
        for p in $programs; do
            ldd "$P/bin/$p" > "$T/ldd"
            for so in $(objdump -p "$P/bin/$p" | awk '/NEEDED/ {print $2}'); do
                lib="$(awk -v s="$so" '$1 == s {print $3; exit}' "$T/ldd")"
                [ -n "$lib" ] && [ -e "$lib" ] && echo "$p $so $lib $(readlink -f "$lib")"
            done
        done > "$T/needed"
        # shellcheck disable=SC2046
        dpkg -S $(awk '{print $3; print $4}' "$T/needed" | sort -u) 2> /dev/null | sed 's/^\([^:]*\):[^ ]* /\1 /' > "$T/owners"
        packages "$D/runtime-packages.txt" > "$T/runtime"
        while read -r p so lib real; do
            pkg="$(awk -v l="$lib" -v r="$real" '$2 == l || $2 == r {print $1; exit}' "$T/owners")"
            [ -n "$pkg" ] || { echo "note: $so ($lib) belongs to no Debian package"; continue; }
            grep -qx "$pkg" "$T/runtime" || fail "$p needs $so from $pkg: not in docker/runtime-packages.txt"
        done < "$T/needed"
        ok "every library the programs need comes from runtime-packages.txt"
    else
        echo "note: no dpkg/objdump: the programs' libraries not checked"
    fi
    # The entry points, as the image runs them (its ENV, the paths under the prefix).
    for cfg in robot base_station kitti_composed robot_composed; do
        env LTM_ROOT="$P" LTM_OUT="$T/results" LTM_SITE="$T/results/site" \
            LTM_DATA="$P/data/kitti00_mini" LTM_SCENARIO="$P/scenarios/site_loop.yaml" \
            "$P/bin/ltm_host" "$P/launch_configs/$cfg.yaml" --check > "$T/check.log" 2>&1 ||
            fail "$cfg.yaml from the install tree: $(tail -n 1 "$T/check.log")"
    done
    ok "the entry points' launch configs pass --check from the install tree"
fi

# 4. compose.yaml: the two services on the images ./ltm image builds.
if python3 -c 'import yaml' 2> /dev/null; then
    python3 - "$D/compose.yaml" "$D/image.sh" << 'EOF' || fail "compose.yaml (above)"
import re, sys, yaml
compose = yaml.safe_load(open(sys.argv[1]))
script = open(sys.argv[2]).read()
services = compose.get("services", {})
errors = []
for name in ("robot", "base-station"):
    s = services.get(name)
    if not s:
        errors.append(f"no service {name}")
        continue
    if s.get("build", {}).get("target") != name:
        errors.append(f"{name}: builds stage {s.get('build', {}).get('target')}")
    if f"{name}) echo {s.get('image')} ;;" not in script:
        errors.append(f"{name}: image {s.get('image')} is not the one ./ltm image builds")
    if not any(v.endswith(":/results") for v in s.get("volumes", [])):
        errors.append(f"{name}: results not on the host (no volume on /results)")
for e in errors:
    print("compose.yaml:", e)
sys.exit(1 if errors else 0)
EOF
    ok "compose.yaml: robot and base-station on the images ./ltm image builds, results on the host"
else
    echo "note: no python3-yaml: compose.yaml not checked"
fi

# 5. The launcher's image command: its help, and one-line usage errors with exit code 2.
"$ROOT/ltm" image help > "$T/help" 2>&1 && grep -q 'image run robot|base-station' "$T/help" ||
    fail "./ltm image help: $(head -n 1 "$T/help")"
for args in "run" "run nope" "build nope" "nope"; do
    # shellcheck disable=SC2086
    out="$(LTM_IMAGE_ENGINE=podman "$ROOT/ltm" image $args 2>&1)"; rc=$?
    [ "$rc" = 2 ] && [ "$(wc -l <<< "$out")" = 1 ] || fail "./ltm image $args: exit $rc, '$out' (a one-line usage error, exit 2)"
done
ok "./ltm image: help and usage errors"

[ "$fails" = 0 ]
