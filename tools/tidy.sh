#!/usr/bin/env bash
# tools/tidy.sh BUILD_DIR: clang-tidy 14 with the root .clang-tidy over the sources of engine/,
# chart/, cli/, demos/ and examples/ compiled in BUILD_DIR/compile_commands.json (not tests/ or bench/:
# GoogleTest and Benchmark macros). Prints every finding once and exits non-zero on any.
#
#   cmake --preset ci-clang && tools/tidy.sh build/ci-clang
#
# Any CMake build directory of the project works (the GCC presets' flags parse too); clang's are
# the safest. Environment: CLANG_TIDY (default clang-tidy-14), TIDY_JOBS (default 2).
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: tools/tidy.sh BUILD_DIR" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
db="$build/compile_commands.json"
if [ ! -f "$db" ]; then
  echo "tidy: no $db: configure first (cmake --preset ci-clang)" >&2
  exit 2
fi
tidy=${CLANG_TIDY:-clang-tidy-14}
if ! command -v "$tidy" >/dev/null; then
  echo "tidy: $tidy not found (Debian: apt-get install clang-tidy)" >&2
  exit 2
fi
jobs=${TIDY_JOBS:-2}

# The translation units: CMake writes one `"file": "/abs/path"` line per entry. In a unity
# build (the ci preset) most are BUILD_DIR/<folder>/CMakeFiles/<target>.dir/Unity/unity_N_cxx.cxx,
# each including a batch of the target's sources: the standard library, Eigen, fmt and toml++
# are then parsed and matched once per batch instead of once per source, which is most of
# clang-tidy's time. Diagnostics in the included sources are reported under their own paths
# (HeaderFilterRegex), and bugprone-suspicious-include, which a unity file's `#include "x.cpp"`
# would trip, is off for those files only, and for engine/core/src/kernel_instances.cpp, which
# includes the kernel's member files to instantiate its class templates once.
files=()
while IFS= read -r f; do
  case "$f" in
    "$root"/engine/* | "$root"/chart/* | "$root"/cli/* | "$root"/demos/* | "$root"/examples/*) files+=("$f") ;;
    "$build"/engine/*/Unity/* | "$build"/chart/*/Unity/* | "$build"/cli/*/Unity/* | "$build"/demos/*/Unity/* | \
      "$build"/examples/*/Unity/*) files+=("$f") ;;
  esac
done < <(sed -n 's/^ *"file": "\(.*\)",\{0,1\}$/\1/p' "$db" | sort -u)
if [ ${#files[@]} -eq 0 ]; then
  echo "tidy: no engine/, chart/, cli/, demos/ or examples/ sources in $db" >&2
  exit 2
fi

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
start=$SECONDS
# One clang-tidy per file, $jobs at a time; each writes its own log (no interleaving) and
# leaves a .fail marker when it exits non-zero (a finding or a compile error).
export tidy build out
printf '%s\0' "${files[@]}" | xargs -0 -n1 -P"$jobs" bash -c '
  log="$out/$(echo "$1" | tr / _).log"
  case "$1" in
    */Unity/unity_* | */kernel_instances.cpp) unity=(--checks=-bugprone-suspicious-include) ;;
    *) unity=() ;;
  esac
  "$tidy" -p "$build" --quiet "${unity[@]}" "$1" >"$log" 2>&1 || touch "$log.fail"
' tidy || true

# A header's findings come once per file including it: keep each diagnostic (its line, the
# source excerpt and its notes) once, and drop clang's "N warnings generated." lines.
awk '
  FNR == 1 { keep = 1 }
  /^[0-9]+ (warning|error)s? (and [0-9]+ (warning|error)s? )?generated\.$/ { next }
  /^\/.*: (warning|error): / { keep = !seen[$0]++ }
  keep { print }
' "$out"/*.log >"$out/all.txt"
failed=$(find "$out" -name '*.fail' | wc -l)
cat "$out/all.txt"
findings=$(grep -E '^/.*: (warning|error): ' "$out/all.txt" || true)
if [ -n "$findings" ]; then
  echo
  echo "tidy: $(echo "$findings" | wc -l) findings:"
  echo "$findings" | sed "s|^$root/||" | sort
  echo
  echo "tidy: by check:"
  echo "$findings" | sed -E 's/.*\[([^],]+)(,-warnings-as-errors)?\]$/\1/' | sort | uniq -c |
    sort -rn
fi
echo "tidy: ${#files[@]} files, $failed failed, $((SECONDS - start)) s ($jobs jobs)"
[ "$failed" -eq 0 ]
