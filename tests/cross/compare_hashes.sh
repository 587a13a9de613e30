#!/usr/bin/env bash
# Same bits everywhere: runs state_hashes (per-tick state hashes) for every case of
# tests/cross/cases.txt on this x86-64 machine at every SIMD level fixstep has and with glibc's
# FMA / AVX2 / AVX-512 code paths turned off (GLIBC_TUNABLES), and in each cross build through
# its emulator (aarch64: qemu-aarch64, wasm32: node), and compares every output with the native
# default run's, naming the first tick that differs.
#
#   tests/cross/compare_hashes.sh NATIVE_BUILD [CROSS_BUILD...]    e.g. build/ci build/aarch64 build/wasm
#
# Each build needs bin/state_hashes.sh (written by its configure step: state_hashes through the
# build's emulator) and state_hashes built; a build without either is refused (exit 2) before
# any case runs. The outputs stay in
# NATIVE_BUILD/cross-hashes/NAME.RUN.txt ("TICK HASH" lines). Exit 0 when every run of every
# case gives the native hashes, 1 otherwise (every difference is printed), 2 on bad usage.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
[ $# -ge 1 ] || { echo "compare_hashes: no build directory given" >&2; sed -n '2,14p' "$0" >&2; exit 2; }
# Every build must have its tool before any case runs: one line naming the build and the fix
# instead of every case failing.
for build in "$@"; do
  if [ ! -d "$build" ]; then
    echo "compare_hashes: $build: no such build directory (give build directories, e.g. build/ci build/aarch64)" >&2
    exit 2
  fi
  if [ ! -x "$build/bin/state_hashes.sh" ]; then
    echo "compare_hashes: $build has no executable bin/state_hashes.sh: configure it (cmake --preset ...) and build the state_hashes target" >&2
    exit 2
  fi
done
for build in "$@"; do
  if ! why=$("$build/bin/state_hashes.sh" "$root/assets/scenes/projectile.toml" --ticks 0 2>&1 >/dev/null); then
    echo "compare_hashes: $build/bin/state_hashes.sh does not run (${why%%$'\n'*}): build the state_hashes target there (cmake --build $build --target state_hashes), or install its emulator" >&2
    exit 2
  fi
done
native=$1
shift
out=$native/cross-hashes
mkdir -p "$out"

# runs: "LABEL|ENVIRONMENT|COMMAND PREFIX" (the case's arguments follow the prefix).
native_tool=$native/bin/state_hashes.sh
runs=("native||$native_tool")
no_fma=glibc.cpu.hwcaps=-FMA
no_avx=glibc.cpu.hwcaps=-AVX512F,-AVX2,-FMA
runs+=("native-glibc-no-fma|GLIBC_TUNABLES=$no_fma|$native_tool")
runs+=("native-glibc-sse2-simd-baseline|GLIBC_TUNABLES=$no_avx|$native_tool --simd baseline")
for level in baseline avx2 avx512; do
  if "$native_tool" "$root/assets/scenes/projectile.toml" --ticks 0 --simd $level >/dev/null 2>&1; then
    runs+=("native-simd-$level||$native_tool --simd $level")
  else
    echo "compare_hashes: SIMD level $level not supported on this CPU: skipped"
  fi
done
for build in "$@"; do
  runs+=("$(basename "$build")||$build/bin/state_hashes.sh")
done

# cases: the file's lines, then the cause scenes it does not name.
mapfile -t cases < <(grep -v '^\s*\(#\|$\)' "$root/tests/cross/cases.txt")
for scene in "$root"/tests/scenes/cross/*.toml; do
  [ -e "$scene" ] || continue
  rel=${scene#"$root"/}
  grep -q " $rel " "$root/tests/cross/cases.txt" || cases+=("$(basename "$scene" .toml) $rel 2000 1")
done

# first_difference REF GOT: "tick T: HASH_REF vs HASH_GOT" at the first differing line.
first_difference() {
  paste -d' ' "$1" "$2" | awk '$1 != $3 || $2 != $4 { printf "tick %s: %s vs %s\n", $1, $2, $4; found = 1; exit }
    END { if (!found) print "equal lines, different line counts" }'
}

failed=0
for c in "${cases[@]}"; do
  read -r name scene ticks every options <<<"$c"
  args="$root/$scene --ticks $ticks --every $every ${options:-}"
  ref=""
  for r in "${runs[@]}"; do
    IFS='|' read -r label environment prefix <<<"$r"
    file=$out/$name.$label.txt
    start=$SECONDS
    # shellcheck disable=SC2086  # the prefix and the arguments are word lists
    if ! env $environment $prefix $args >"$file" 2>"$file.err"; then
      echo "FAIL $name $label: exit status, $(head -c 300 "$file.err")"
      failed=1
      [ -n "$ref" ] && continue
      break  # no native reference: nothing to compare with
    fi
    if [ -z "$ref" ]; then
      ref=$file
      echo "ok   $name $label: $(wc -l <"$file") hashes, final $(tail -n 1 "$file") ($((SECONDS - start)) s)"
    elif cmp -s "$ref" "$file"; then
      echo "ok   $name $label: same $(wc -l <"$file") hashes ($((SECONDS - start)) s)"
    else
      echo "FAIL $name $label: first difference at $(first_difference "$ref" "$file")"
      failed=1
    fi
  done
done
exit $failed
