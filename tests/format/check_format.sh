#!/usr/bin/env bash
# Fails when a C++ file of the repository differs from what clang-format (the repository's
# .clang-format) makes of it, and names the files. Fix with:
#   clang-format -i $(git ls-files '*.cpp' '*.hpp' '*.h')
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$ROOT"
FORMAT="${CLANG_FORMAT:-clang-format}"
command -v "$FORMAT" > /dev/null || { echo "clang-format is not installed (./ltm setup installs it)"; exit 1; }
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h')
else
    mapfile -t files < <(find components runtime tests -name '*.cpp' -o -name '*.hpp' -o -name '*.h')
fi
bad=0
for f in "${files[@]}"; do
    [ -f "$f" ] || continue
    if ! "$FORMAT" --dry-run --Werror "$f" > /dev/null 2>&1; then
        echo "not formatted: $f"
        bad=$((bad + 1))
    fi
done
echo "${#files[@]} files checked, $bad not formatted ($("$FORMAT" --version | head -1))"
[ "$bad" = 0 ]
