#!/usr/bin/env bash
# Builds examples/consumer the two ways a project uses fixstep and checks both (run by .ci/run):
#  1. installed: `cmake --install BUILD_DIR` into a temporary prefix, then find_package;
#  2. as a subproject: add_subdirectory of this source tree, which must define no test,
#     benchmark or demo target.
# Each consumer must print the summary line `fixstep run` prints for the same world (state hash,
# energy, dissipated energy, balance), and link neither OSMesa nor SDL2 (ldd).
# Usage: bash examples/consumer/check.sh BUILD_DIR   (a configured and built fixstep tree)
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:?usage: check.sh BUILD_DIR}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "consumer: FAIL: $*" >&2; exit 1; }

expected=$("$build/bin/fixstep" run "$src/assets/scenes/default.toml" --steps 1000 |
           grep '^ticks=')
echo "consumer: fixstep run default.toml --steps 1000: $expected"

check_program() {  # check_program HOW BINARY
  local how=$1 program=$2 got
  got=$("$program" | grep '^ticks=')
  [[ $got == "$expected" ]] || fail "$how consumer printed $got, fixstep run $expected"
  if ldd "$program" | grep -Ei 'osmesa|sdl2'; then fail "$how consumer links OSMesa or SDL2"; fi
  echo "consumer: $how: $got, links neither OSMesa nor SDL2"
}

# 1. Installed package + find_package(fixstep 0.3 REQUIRED COMPONENTS core io).
cmake --install "$build" --prefix "$work/prefix" >/dev/null
# The installed headers hold no kernel: no detail/ folder, no world_kernel.hpp; and a program
# that includes fixstep/core/world.hpp compiles against fewer than 600 lines of fixstep headers.
kernel=$(find "$work/prefix/include" \( -name detail -o -name world_kernel.hpp \) -print)
[[ -z $kernel ]] || fail "the installed headers hold the kernel: $kernel"
echo '#include <fixstep/core/world.hpp>' >"$work/world_only.cpp"
lines=$(c++ -std=c++20 -M -I"$work/prefix/include" "$work/world_only.cpp" | tr ' \\' '\n\n' |
        grep "^$work/prefix/include/fixstep/" | sort -u | xargs cat | wc -l)
((lines < 600)) || fail "fixstep/core/world.hpp brings $lines lines of fixstep headers (at most 600)"
echo "consumer: installed headers hold no kernel; fixstep/core/world.hpp brings $lines lines"
cmake -S "$src/examples/consumer" -B "$work/installed" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/installed" >/dev/null
check_program installed "$work/installed/consumer"

# Each installed component brings only the libraries it needs: the link line of a program that
# links it alone (the linker's --as-needed would drop them from ldd's view of an empty program).
cmake -S "$src/examples/consumer/components" -B "$work/components" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/components" >/dev/null
# capture loads FFmpeg when it writes a video and render libOSMesa when it creates a context
# (dlopen), so nothing links libavcodec and only window (SDL2) links a graphics library.
declare -A brings=([core]="" [io]="" [scene]="" [render]="" [capture]="deflate"
                   [window]="sdl2" [app]="deflate sdl2" [net]="enet" [net_app]="deflate sdl2 enet")
for component in core io scene render capture window app net net_app; do
  libs=$(ninja -C "$work/components" -t commands "link_$component" | tail -1 |
         tr '[:upper:]' '[:lower:]')
  for lib in osmesa avcodec deflate sdl2 enet; do
    wanted=" ${brings[$component]} "
    if [[ $libs == *"lib$lib"* && $wanted != *" $lib "* ]]; then
      fail "fixstep::$component brings lib$lib"
    elif [[ $libs != *"lib$lib"* && $wanted == *" $lib "* ]]; then
      fail "fixstep::$component does not bring lib$lib (the check itself is wrong?)"
    fi
  done
  echo "consumer: fixstep::$component brings: ${brings[$component]:-none of OSMesa, FFmpeg, libdeflate, SDL2, ENet}"
done

# 2. add_subdirectory: only libraries; the program builds core and io alone (as a unity build,
# as CI builds everything: a parent project's CMAKE_UNITY_BUILD reaches fixstep's targets).
# Unoptimised (-O0, no debug information): it compiles in about half the time of -O3, and its
# line must still equal the -O2 fixstep's, bit for bit (optimisation changes no result).
cmake -S "$src/examples/consumer" -B "$work/subproject" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16 -DFIXSTEP_SOURCE_DIR="$src" >/dev/null
if ninja -C "$work/subproject" -t targets all |
   grep -E '(^|/)(test_[a-z_]*|bench_[a-z_]*|hello_fixstep|integration_basics|work_precision|fuzz_[a-z_]*|fixstep|[0-9][0-9]_[a-z_]*|fixstep_chart):'; then
  fail "add_subdirectory defines test, benchmark or demo targets (above)"
fi
# Only the consumer and what it links (core, io): the other libraries are the ci build's, already
# built and checked there (building them again here cost CI ~2 minutes).
cmake --build "$work/subproject" --target consumer >/dev/null
check_program subproject "$work/subproject/consumer"
echo "consumer: OK (installed and add_subdirectory)"
