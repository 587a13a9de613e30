#!/usr/bin/env bash
# The engine's layering, checked from the #include lines (run by ctest as `layering`):
#   core <- io <- scene, capture;  core <- render <- window;  all of them <- app <- programs;
#   core, io <- net;  net, app <- net_app (net itself never uses app, render or window)
# 1. each component's files include only fixstep headers of the components it may use; a
#    component's public headers are fixstep/<component>/*.hpp, plus its umbrella
#    fixstep/<component>.hpp;
# 2. the include graph of engine/ and chart/ files has no cycle (tsort finds loops);
# 3. core does no I/O: none of its files includes a header that opens files, reads paths or
#    installs signal handlers (that is fixstep::io's).
# Usage: tools/check_layering.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"
status=0

components="core io scene render capture window app net net_app"
declare -A allowed=([core]="core" [io]="core io" [scene]="core io scene" [render]="core render"
                    [capture]="core io capture" [window]="core render window"
                    [app]="core io scene render capture window app"
                    [net]="core io net"
                    [net_app]="core io scene render capture window app net net_app")
declare -A owner  # header path below fixstep/ -> component
for component in $components; do
  for h in engine/$component/include/fixstep/$component.hpp \
           engine/$component/include/fixstep/$component/*.hpp \
           engine/$component/include/fixstep/$component/detail/*.hpp; do
    [[ -e $h ]] && owner[${h#engine/$component/include/fixstep/}]=$component
  done
  # A header directly below fixstep/ other than the umbrella is the old, flat layout.
  for h in engine/$component/include/fixstep/*.hpp; do
    [[ $h == engine/$component/include/fixstep/$component.hpp ]] && continue
    echo "$h: a public header belongs in fixstep/$component/ (one folder a library)"
    status=1
  done
done

for component in $components; do
  while IFS=: read -r file line include; do
    header=$(sed -E 's/.*fixstep\/([a-z0-9_/]+\.hpp).*/\1/' <<<"$include")
    from=${owner[$header]:-}
    if [[ -z $from ]]; then
      echo "$file:$line: includes fixstep/$header, which no engine component provides"
      status=1
    elif [[ " ${allowed[$component]} " != *" $from "* ]]; then
      echo "$file:$line: $component includes fixstep/$header from $from (allowed: ${allowed[$component]})"
      status=1
    fi
  done < <(grep -HnE '^#include [<"]fixstep/' -r engine/$component || true)
done

io_headers='fstream|filesystem|cstdio|stdio\.h|csignal|signal\.h|fcntl\.h|unistd\.h|sys/[a-z]+\.h'
while IFS=: read -r file line include; do
  echo "$file:$line: core includes $include: core does no I/O (files, paths and signals are io's)"
  status=1
done < <(grep -HnE "^#include <($io_headers)>" -r engine/core || true)

# File-level include graph of engine/ and chart/: "includer included" pairs of paths, a public
# header named by its path below include/ (fixstep/core/world.hpp), a private one by its path.
node() {  # node FILE: the name a file has in the graph
  [[ $1 == */include/* ]] && echo "${1#*/include/}" || echo "$1"
}
edges=$(grep -rHE '^#include [<"][a-z0-9_/]+\.hpp[">]' engine chart |
        sed -E 's|^([^:]*):#include [<"]([a-z0-9_/]+\.hpp)[">].*|\1 \2|' |
        while read -r file header; do
          if [[ $header == fixstep/* ]]; then to=$header; else to=$(node "$(dirname "$file")/$header"); fi
          echo "$(node "$file") $to"
        done)
if ! tsort <<<"$edges" >/dev/null 2>/tmp/layering_tsort.$$; then
  echo "include cycle:"; cat /tmp/layering_tsort.$$
  status=1
fi
rm -f /tmp/layering_tsort.$$
[[ $status -eq 0 ]] && echo "layering: core <- io <- scene, capture; core <- render <- window; all <- app; core, io <- net; net, app <- net_app; no include cycle; core does no I/O"
exit $status
