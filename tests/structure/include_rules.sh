#!/usr/bin/env bash
# Fails when a file breaks the rooms' include rules, one line per violation:
#   - localisation, mesh and maintenance never include mapping/ (the map is map/, place
#     recognition places/, shared verification registration/);
#   - components/common never includes runtime/ (the runtime is built on common);
#   - map/ and places/ include neither mapping/, localisation/, runtime/ nor dds/;
#   - the SLAM benchmark (bench_slam.cpp) lives under components/slam.
#   include_rules.sh [ROOT]   (default: the checkout this script is in)
set -uo pipefail
ROOT="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
cd "$ROOT" || exit 1
bad=0

# forbid DIR PATTERN WHY: every #include in DIR's C++ files that matches PATTERN is a violation.
forbid() {
    local dir="$1" pattern="$2" why="$3" hit
    [ -d "$dir" ] || return 0
    while IFS= read -r hit; do
        echo "include rule: ${hit%%:#*} includes ${hit#*#include } ($why)"
        bad=$((bad + 1))
    done < <(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' \
        "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]($pattern)" "$dir" | sed -E 's/:[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*/:#include /')
}

for room in localisation mesh maintenance; do
    forbid "components/$room" 'mapping/' "$room stands beside mapping: use map/, places/ or registration/"
done
forbid components/common 'runtime/' "common is below the runtime"
for room in map places; do
    forbid "components/$room" 'mapping/|localisation/|runtime/|dds/' "$room is a pure core below mapping and localisation"
done

if [ ! -f components/slam/bench/bench_slam.cpp ]; then
    echo "include rule: components/slam/bench/bench_slam.cpp is missing (the SLAM benchmark lives with the slam pipeline)"
    bad=$((bad + 1))
fi
while IFS= read -r f; do
    case "$f" in components/slam/*) ;; *)
        echo "include rule: $f is outside components/slam (the SLAM benchmark lives with the slam pipeline)"
        bad=$((bad + 1)) ;;
    esac
done < <(find components -name bench_slam.cpp -not -path '*/build*' | sort)

[ "$bad" = 0 ] && echo "include rules: no violation" || echo "include rules: $bad violation(s)"
[ "$bad" = 0 ]
