#!/usr/bin/env bash
# ./ltm bench site MAP_DIR [--out DIR]: the site's versions on a saved map (a copy of it in DIR,
# default a temporary folder): MAP_DIR imported as v0001, then again as v0002 (an unchanged
# session: every file hard-linked), then `versions` (checks both) and `check` (the newest);
# time and peak memory of each, and the disk the site and each version take.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)"
BIN="${LTM_BUILD_DIR:-$ROOT/build}/bin"
[ $# -ge 1 ] && [ "${1:0:1}" != "-" ] || { echo "usage: ./ltm bench site MAP_DIR [--out DIR]" >&2; exit 2; }
MAP="$1"; shift
OUT=""
while [ $# -gt 0 ]; do
    case "$1" in
        --out) [ $# -ge 2 ] || { echo "bench site: --out: needs a value" >&2; exit 2; }; OUT="$2"; shift 2 ;;
        *) echo "bench site: unknown argument '$1'" >&2; exit 2 ;;
    esac
done
[ -f "$MAP/manifest.txt" ] || { echo "bench site: $MAP: no manifest.txt (not a saved map)" >&2; exit 2; }
[ -x "$BIN/ltm_site" ] || { echo "bench site: $BIN/ltm_site is not built" >&2; exit 2; }
if [ -z "$OUT" ]; then OUT="$(mktemp -d)"; trap 'rm -rf "$OUT"' EXIT; fi
rm -rf "$OUT/map" "$OUT/site"
cp -r "$MAP" "$OUT/map"   # the copy: the site's hard links never touch MAP's files
timed() { /usr/bin/time -f "  -> %e s, peak %M KiB" "$@"; }
echo "== import as v0001"; timed "$BIN/ltm_site" import "$OUT/site" --map "$OUT/map"
echo "== import again as v0002 (unchanged)"; timed "$BIN/ltm_site" import "$OUT/site" --map "$OUT/map"
echo "== versions (both checked)"; timed "$BIN/ltm_site" versions "$OUT/site"
echo "== check (the newest)"; timed "$BIN/ltm_site" check "$OUT/site"
rm -rf "$OUT/map"
echo "== disk"; du -sh "$OUT/site"; du -sh "$OUT/site/versions/"* | sed 's/^/  /'
