#!/usr/bin/env bash
# Two Box2D libraries in one executable (bench_discs, bench_boxes): a static archive of Box2D v3
# and either Debian's shared library of Box2D 2.4 or the static archive of another v3 release
# (v3.2's, its symbols prefixed by box2d3_prefix.sh). Fails if the first archive defines a global
# symbol that the other library defines or needs (the executable's definition would interpose
# on the shared library's; two archives' definitions of one name would clash or one would
# silently win). v3's API has C linkage and 2.4's C++ linkage, so none is expected against 2.4;
# 2.4's few C-named globals (b2_version, b2_gjkCalls...) are not v3's. Against another v3
# release none is expected once one of the two is prefixed (checked both ways).
#   bash bench/box2d3_symbols.sh <libbox2d.a of v3> <libbox2d.so of 2.4 | other v3 archive .a>
set -euo pipefail
archive="$1" other="$(readlink -f "$2")"
v3=$(nm -g --defined-only "$archive" | awk 'NF == 3 { print $3 }' | sort -u)
if [[ "$other" == *.a ]]; then  # defined or needed by the other archive, and the reverse
  them=$(nm -g "$other" | awk 'NF >= 2 { print $NF }' | sort -u)
  theirs=$(nm -g --defined-only "$other" | awk 'NF == 3 { print $3 }' | sort -u)
  ours=$(nm -g "$archive" | awk 'NF >= 2 { print $NF }' | sort -u)
  common=$(comm -12 <(echo "$theirs") <(echo "$ours"))
  if [ -n "$common" ]; then
    echo "box2d3_symbols: $other defines symbols $archive defines or needs:" >&2
    echo "$common" >&2
    exit 1
  fi
else
  them=$(nm -D "$other" | awk '{ print $NF }' | sed 's/@.*//' | sort -u)
fi
[ -n "$v3" ] && [ -n "$them" ] || { echo "box2d3_symbols: no symbols read from $archive or $other" >&2; exit 1; }
common=$(comm -12 <(echo "$v3") <(echo "$them"))
if [ -n "$common" ]; then
  echo "box2d3_symbols: $archive and $other share symbols:" >&2
  echo "$common" >&2
  exit 1
fi
echo "box2d3_symbols: $(echo "$v3" | wc -l) global symbols of $(basename "$archive"), $(echo "$them" | wc -l) of $(basename "$other") (defined or needed), none in common"
