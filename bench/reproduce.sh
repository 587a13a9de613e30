#!/usr/bin/env bash
# Regenerates every table and figure of docs/PERFORMANCE.md on this machine, in one command:
#   bash bench/reproduce.sh            (about 17 minutes on 2 cores)
#   bash bench/reproduce.sh coupled    (only section 6, coupled systems against peers: ~3 min)
#   bash bench/reproduce.sh discs      (only section 7, disc contacts against peers, with
#                                       Box2D v3 where ../shared/peers has its source: ~6-9 min)
#   bash bench/reproduce.sh shapes     (only section 7.1, boxes against Box2D v3.1.1 and v3.2:
#                                       the 20-row pyramid, a 20-box tower and a settling
#                                       pile of 10^4 boxes,
#                                       with fixstep's: ~20 s after the build)
#   bash bench/reproduce.sh joints     (only section 7.2, joints against Box2D v3.1.1 and v3.2:
#                                       a chain of 100 revolute joints, 100 ragdolls and a
#                                       car on a terrain: ~1-2 min after the build)
#   bash bench/reproduce.sh network    (only section 6.1: integrator costs and the trade on
#                                       damped networks: ~3 min)
#   bash bench/reproduce.sh net        (only section 8, networking: bandwidth, stalls and
#                                       rollbacks through the link conditioner: ~4 min)
# Builds the optimised benchmark tree (build/bench), runs each study into docs/perf/, and
# splices the generated markdown into docs/PERFORMANCE.md between its
# "<!-- BEGIN name -->" / "<!-- END name -->" markers. Run on an otherwise idle machine:
# timings are medians, but other load still shifts them.
set -euo pipefail
cd "$(dirname "$0")/.."
only="${1:-}"
case "$only" in
  "" | coupled | discs | shapes | joints | network | net) ;;
  *) echo "usage: bash bench/reproduce.sh [coupled|discs|shapes|joints|network|net]" >&2; exit 2 ;;
esac
bash .ci/install-deps
cmake --workflow --preset bench

out=docs/perf
bin=build/bench/bin
mkdir -p "$out"
# The CPU as lscpu names it, with its family and model (a virtual machine may name only the
# vendor's line, which spans generations), and the SIMD level fixstep's sweeps run at on it.
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
cpu_family=$(lscpu | sed -n 's/^CPU family: *//p' | head -1)
cpu_model=$(lscpu | sed -n 's/^Model: *//p' | head -1)
simd_level=$("$bin/bench_throughput" --verify-only | sed -n 's/.*Timing at level \([a-z0-9]*\).*/\1/p')

# The machine the numbers come from (the full run's table).
if [ -z "$only" ]; then
  {
    echo "| | |"
    echo "|---|---|"
    echo "| CPU | $cpu (family ${cpu_family:-?}, model ${cpu_model:-?}) |"
    echo "| cores | $(nproc) |"
    echo "| caches | $(lscpu | sed -n 's/^L\([123][a-z]*\) cache: *\(.*\)/L\1 \2/p' | paste -sd ',' | sed 's/,/, /g') |"
    echo "| memory | $(free -g | awk '/^Mem:/ {print $2 " GiB"}') |"
    echo "| compiler | $(c++ --version | head -1) |"
    echo "| build | CMake preset \`bench\` (Release, -O3 on the sweep, -ffp-contract=off; sweeps at SIMD level $simd_level) |"
    echo "| date | $(date -u +%Y-%m-%d) |"
  } > "$out/machine.md"
fi

if [ -z "$only" ]; then
  "$bin/bench_throughput" --report="$out/throughput.md" > "$out/throughput.log"
  "$bin/work_precision" --out "$out" > "$out/work_precision.log"
  "$bin/integration_basics" --out "$out/article" > "$out/article.log"
  # Capture speed (render-only vs naive stb vs shipped, 4-6 min; SKIP_CAPTURE=1 skips it);
  # docs/perf/capture.md quotes its medians.
  [ -n "${SKIP_CAPTURE:-}" ] || "$bin/bench_capture" > "$out/capture.log"
fi
# Where a section's numbers were measured (sections 6 and 7 can be regenerated alone).
measured_on() {
  echo "Measured on $cpu (family ${cpu_family:-?}, model ${cpu_model:-?}; SIMD level ${simd_level:-?}), $(nproc) cores, $(date -u +%Y-%m-%d), by \`bash bench/reproduce.sh${only:+ $only}\`."
}
# Coupled systems against the edge-list loop, Chipmunk2D and Box2D: tables, targets and the
# work-precision plot, headed by the machine and date they come from.
if [ -z "$only" ] || [ "$only" = coupled ]; then
  "$bin/bench_coupled" --report "$out" > "$out/coupled.log"
  { measured_on; cat "$out/coupled.md"; } > "$out/coupled.section.md"
fi
# Disc contacts against Chipmunk2D, Box2D 2.4 and Box2D v3 (pile, gas; N = 10^3 ... 10^5): cost
# per body-step, overlaps, energy, targets; its first line gives the load average during the
# run. Box2D v3.1.1 and v3.2 are in it where bench/box2d3.cmake found
# ../shared/peers/box2d-3.1.1.tar.gz and box2d-main-617d32a.tar.gz (the configure step above
# says "Box2D v3.x peer skipped: ..." otherwise).
if [ -z "$only" ] || [ "$only" = discs ]; then
  "$bin/bench_discs" --report "$out" > "$out/discs.log"
  { measured_on; cat "$out/discs.md"; } > "$out/discs.section.md"
fi

# Boxes (the rotating-shapes work) against Box2D v3.1.1 and v3.2: the 20-row pyramid and a
# settling pile of 10^4 boxes, ns per body-step and deepest overlap, 1 and 2 threads/workers.
# Should World stop colliding shapes, its first lines say "fixstep: shapes not yet supported
# (why)" and fixstep's rows are absent (bench/boxes_fixstep.cpp).
if [ -z "$only" ] || [ "$only" = shapes ]; then
  "$bin/bench_boxes" --report "$out" > "$out/boxes.log"
  { measured_on; cat "$out/boxes.md"; } > "$out/boxes.section.md"
fi

# Joints against Box2D v3.1.1 and v3.2: a chain of 100 boxes on revolute joints swinging down, a
# pile of 100 ragdolls (revolute joints with angle limits) and a car on wheel joints over a
# terrain; ns per body-step (median of 5 interleaved rounds), the joints' largest separation and
# limit error, overlaps and the car's distance, 1 and 2 threads/workers (bench/bench_joints.cpp).
if [ -z "$only" ] || [ "$only" = joints ]; then
  "$bin/bench_joints" --report "$out" > "$out/joints.log"
  { measured_on; cat "$out/joints.md"; } > "$out/joints.section.md"
fi

# Each integrator's cost per tick on damped networks (cloth.toml and a 10^4-body cloth, f64
# and f32, 1 and 2 threads), side by side in one run (docs/perf/network_integrators.md).
if [ -z "$only" ] || [ "$only" = network ]; then
  "$bin/bench_network_integrators" --out "$out" > "$out/network_integrators.log"
  { measured_on; cat "$out/network_integrators.md"; } > "$out/network_integrators.section.md"
  "$bin/network_trade" --out "$out" > "$out/network_trade.log"
  { measured_on; cat "$out/network_trade.md"; } > "$out/network_trade.section.md"
fi

# Networking: bandwidth per player (byte counts), lockstep stalls and rollbacks against latency
# and loss through the link conditioner, the longest rollback per 16.7 ms frame (bench_net).
if [ -z "$only" ] || [ "$only" = net ]; then
  "$bin/bench_net" --report "$out/net.md" > "$out/net.log"
  { measured_on; cat "$out/net.md"; } > "$out/net.section.md"
fi

splice() {  # splice NAME FILE: replace the text between the NAME markers with FILE
  local doc=docs/PERFORMANCE.md
  awk -v name="$1" -v src="$2" '
    $0 == "<!-- BEGIN " name " -->" { print; while ((getline line < src) > 0) print line; skip = 1; next }
    $0 == "<!-- END " name " -->" { skip = 0 }
    !skip { print }' "$doc" > "$doc.tmp"
  mv "$doc.tmp" "$doc"
}
if [ -z "$only" ]; then
  splice machine "$out/machine.md"
  splice throughput "$out/throughput.md"
  splice work_precision "$out/work_precision.md"
  splice constant_force "$out/article/constant_force.md"
fi
if [ -z "$only" ] || [ "$only" = coupled ]; then splice coupled "$out/coupled.section.md"; fi
if [ -z "$only" ] || [ "$only" = discs ]; then splice discs "$out/discs.section.md"; fi
if [ -z "$only" ] || [ "$only" = shapes ]; then splice shapes "$out/boxes.section.md"; fi
if [ -z "$only" ] || [ "$only" = joints ]; then splice joints "$out/joints.section.md"; fi
if [ -z "$only" ] || [ "$only" = network ]; then
  splice network_integrators "$out/network_integrators.section.md"
  splice network_trade "$out/network_trade.section.md"
fi
if [ -z "$only" ] || [ "$only" = net ]; then splice net "$out/net.section.md"; fi
echo "reproduce: docs/PERFORMANCE.md and $out/ regenerated"
