#!/usr/bin/env bash
# The engine's layering, checked from the #include lines (run by ctest as `layering`):
#   core  <- scene, render  <- window  <- programs
# 1. each component's files include only fixstep headers of the components it may use;
# 2. the include graph of engine/ and chart/ files has no cycle (tsort finds loops).
# Usage: tools/check_layering.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

declare -A allowed=([core]="core" [scene]="core scene" [render]="core render"
                    [window]="core render window")
declare -A owner  # header name -> component
for component in core scene render window; do
  for h in engine/$component/include/fixstep/*.hpp; do owner[$(basename "$h")]=$component; done
done

status=0
for component in core scene render window; do
  while IFS=: read -r file line include; do
    header=$(sed -E 's/.*fixstep\/([a-z0-9_]+\.hpp).*/\1/' <<<"$include")
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

# File-level include graph: "includer included" pairs, by base name within engine/ and chart/.
edges=$(grep -rHE '^#include [<"](fixstep/)?[a-z0-9_]+\.hpp[">]' engine chart |
        sed -E 's|^([^:]*):#include [<"](fixstep/)?([a-z0-9_]+\.hpp)[">].*|\1 \3|' |
        while read -r file header; do
          base=$(basename "$file")
          [[ $base == "$header" ]] || echo "$base $header"
        done)
if ! tsort <<<"$edges" >/dev/null 2>/tmp/layering_tsort.$$; then
  echo "include cycle:"; cat /tmp/layering_tsort.$$
  status=1
fi
rm -f /tmp/layering_tsort.$$
[[ $status -eq 0 ]] && echo "layering: core <- scene, render <- window; no include cycle"
exit $status
