#!/usr/bin/env bash
# Box2D v3 (a static archive linked into bench_discs) and Box2D 2.4 (Debian's shared library)
# in one executable: fails if the archive defines a global symbol that the shared library
# defines or needs (the executable's definition would interpose on the library's). v3's API
# has C linkage and 2.4's C++ linkage, so none is expected; 2.4's few C-named globals (b2_version,
# b2_gjkCalls...) are not v3's.
#   bash bench/box2d3_symbols.sh <libbox2d.a of v3> <libbox2d.so of 2.4>
set -euo pipefail
archive="$1" shared="$(readlink -f "$2")"
v3=$(nm -g --defined-only "$archive" | awk 'NF == 3 { print $3 }' | sort -u)
v24=$(nm -D "$shared" | awk '{ print $NF }' | sed 's/@.*//' | sort -u)
[ -n "$v3" ] && [ -n "$v24" ] || { echo "box2d3_symbols: no symbols read from $archive or $shared" >&2; exit 1; }
common=$(comm -12 <(echo "$v3") <(echo "$v24"))
if [ -n "$common" ]; then
  echo "box2d3_symbols: Box2D v3 ($archive) and 2.4 ($shared) share symbols:" >&2
  echo "$common" >&2
  exit 1
fi
echo "box2d3_symbols: $(echo "$v3" | wc -l) global symbols of Box2D v3, $(echo "$v24" | wc -l) of 2.4 (defined or needed), none in common"
