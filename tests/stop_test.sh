#!/usr/bin/env bash
# Stop requests end to end: SIGINT inside one long tick (run, render, compare) exits
# 130 within the hang guard with consistent outputs; a long load shows progress on a terminal
# and SIGINT ends it; virtual frames exactly 1/fps apart at
# --fps 1; RFC 4180 quoting in run --csv and compare --csv; warnings for a duplicate link and a
# repeated --with.
#   stop_test.sh FIXSTEP
set -u
fixstep=$1
. "$(dirname "$0")/lib.sh"

# A 10 x 10 net of rest-length springs under implicit Euler at 15 000 substeps: a Newton solve
# with a sparse LU per iteration in every substep, so one tick takes ~6 s here (~60 s under
# ASan), just inside the work limit (limits.hpp: 9.6e8 of 1e9 body-substeps). Without the polls
# inside the tick, SIGINT waits for the tick's end and the hang guard kills the command 3 s
# after the signal (137); with them it exits at the next substep (~0.4 ms).
cp "$(dirname "$0")/scenes/long_tick.toml" "$work/long.toml"

# interrupt NAME CMD...: runs CMD, sends it SIGINT 2 s later (inside the first tick: loading takes
# milliseconds) and SIGKILL 3 s after that (the hang guard: status 137); the status is in $status.
interrupt() {
  local name=$1
  shift
  timeout --preserve-status -k 3 -s INT 2 "$@" >"$work/$name.out" 2>"$work/$name.err"
  status=$?
}

# --- class 5: run --csv --record, stopped inside tick 1 ---------------------------------------
interrupt run "$fixstep" run "$work/long.toml" --steps 3 --csv "$work/run.csv" \
  --record "$work/run.rec"
[ "$status" -eq 130 ] && ok "run: SIGINT inside a tick exits 130" \
  || { fail "run exit $status (137: the tick ignored the signal)"; cat "$work/run.err"; }
expect_text "run: the tick in progress is discarded" "(the tick in progress discarded)" \
  "$work/run.err"
# The CSV holds the header and tick 0 (100 bodies): the only tick completed.
[ "$(wc -l <"$work/run.csv")" -eq 101 ] && [ "$(cut -d, -f1 "$work/run.csv" | sort -u | head -2 |
  tr '\n' ' ')" = "0 tick " ] && ok "run: the CSV holds tick 0 only" \
  || fail "run CSV: $(wc -l <"$work/run.csv") lines"
"$fixstep" replay "$work/run.rec" --scene "$work/long.toml" >"$work/replay.out" 2>&1
[ $? -eq 0 ] && ok "run: the recording of the completed ticks replays" \
  || { fail "replay of the stopped recording"; cat "$work/replay.out"; }

# --- class 5: render, stopped inside frame 1's tick ------------------------------------------
interrupt render "$fixstep" render "$work/long.toml" --out "$work/frames" --frames 3 \
  --size 160x120
[ "$status" -eq 130 ] && ok "render: SIGINT inside a tick exits 130" \
  || { fail "render exit $status"; cat "$work/render.err"; }
[ -f "$work/frames/frame_000000.png" ] && [ ! -e "$work/frames/frame_000001.png" ] \
  && [ "$(wc -l <"$work/frames/frames.csv")" -eq 2 ] \
  && ok "render: frame 0 and its manifest row written, the torn frame not" \
  || fail "render frames: $(ls "$work/frames")"

# --- class 5: compare, stopped inside a tile's tick ------------------------------------------
interrupt compare "$fixstep" compare "$work/long.toml" --with implicit_euler@1/100 \
  --with implicit_euler@1/200 --out "$work/cmp" --frames 3 --size 320x120
[ "$status" -eq 130 ] && ok "compare: SIGINT inside a tick exits 130" \
  || { fail "compare exit $status"; cat "$work/compare.err"; }
# compare times each configuration's step (step_cost) before its first frame, so the signal
# lands in that timing tick: nothing is written, and no temporary is left behind.
[ ! -e "$work/cmp/frame_000001.png" ] && [ -z "$(find "$work" -name '.*.tmp.*')" ] \
  && ok "compare: no torn frame, no temporary left" \
  || fail "compare frames: $(ls -a "$work/cmp" 2>&1)"

# --- a long load: progress on a terminal, and SIGINT ends it --------------------------------
# A 600 x 600 grid of linked bodies (360 000 bodies, 718 800 links): ~1.5 s to load here, most of
# it generating the bodies and links and the stability guard (a 1000 x 1000 grid takes ~4 s).
printf '[world]\ndt = 0.01\n[[grid]]\nname = "g"\ncolumns = 600\nrows = 600\norigin = [0.0, 0.0]\nspacing = [0.1, -0.1]\nbody = { mass = 1.0 }\nlink = { stiffness = 10.0, damping = 0.1 }\n' \
  >"$work/grid600.toml"
if command -v script >/dev/null; then  # a terminal for standard error (util-linux)
  script -qfec "$fixstep run $work/grid600.toml --steps 1" "$work/load_tty.txt" >/dev/null 2>&1
  expect_text "loading shows the generators' progress on a terminal" \
    "generating the scene: body " "$work/load_tty.txt"
  expect_text "and the stability guard's" "stability guard: iteration " "$work/load_tty.txt"
fi
"$fixstep" run "$work/grid600.toml" --steps 1 >"$work/load_pipe.out" 2>&1
grep -q "generating the scene" "$work/load_pipe.out" && fail "progress written to a pipe" \
  || ok "no progress when standard error is not a terminal"
# SIGINT 0.5 s into the load (before any tick): the command ends at once, 130 as a shell reports
# it, where a load that did not stop would run on to the hang guard's SIGKILL (137).
for cmd in run render; do
  case $cmd in
    run) args=(run "$work/grid600.toml" --steps 1 --csv "$work/load.csv") ;;
    render) args=(render "$work/grid600.toml" --out "$work/load_frames" --frames 1 --size 160x120) ;;
  esac
  timeout --preserve-status -k 3 -s INT 0.5 "$fixstep" "${args[@]}" >"$work/load_$cmd.out" 2>&1
  status=$?
  [ "$status" -eq 130 ] && ok "$cmd: SIGINT during a load exits 130" \
    || { fail "$cmd: SIGINT during a load: exit $status"; cat "$work/load_$cmd.out"; }
done
[ ! -e "$work/load.csv" ] && [ -z "$(find "$work" -name '.*.tmp.*')" ] \
  && ok "a load stopped by SIGINT leaves no output and no temporary" \
  || fail "left after a stopped load: $(ls -a "$work")"

# --- class 9: a virtual clock is not clamped: --fps 1 puts frames 1 s apart ------------------
"$fixstep" render "$(dirname "$0")/../assets/scenes/projectile.toml" --out "$work/fps1" \
  --frames 3 --fps 1 --size 160x120 >"$work/fps1.out" 2>&1
times=$(cut -d, -f3 "$work/fps1/frames.csv" | tail -n +2 | tr '\n' ' ')
[ "$times" = "0.000000 1.000000 2.000000 " ] && ok "render --fps 1: frames at t = 0, 1, 2 s" \
  || fail "render --fps 1 frame times: $times"
"$fixstep" compare "$(dirname "$0")/../assets/scenes/projectile.toml" --with rk4@1/100 \
  --with semi_implicit_euler@1/100 --out "$work/cfps1" --frames 3 --fps 1 --size 320x120 \
  >"$work/cfps1.out" 2>&1
times=$(awk -F, 'NR > 1 && $2 == 1 { printf "%s ", $4 }' "$work/cfps1/frames.csv")
[ "$times" = "0.000000 1.000000 2.000000 " ] && ok "compare --fps 1: frames at t = 0, 1, 2 s" \
  || fail "compare --fps 1 frame times: $times"

# --- class 9: RFC 4180 quoting of names with a comma, a quote, a newline ---------------------
cat >"$work/names.toml" <<'EOF'
[world]
dt = 0.01

[[body]]
name = "a,b"
mass = 1.0
position = [0.0, 0.0]

[[body]]
name = "say \"hi\""
mass = 1.0
position = [1.0, 0.0]

[[body]]
name = "two\nlines"
mass = 1.0
position = [2.0, 0.0]
EOF
"$fixstep" run "$work/names.toml" --steps 1 --csv "$work/names.csv" >"$work/names.out" 2>&1
python3 - "$work/names.csv" <<'EOF' && ok "run --csv quotes names (RFC 4180)" || fail "run --csv quoting"
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
names = [r[2] for r in rows[1:]]
assert all(len(r) == len(rows[0]) for r in rows), rows
assert names == ["a,b", 'say "hi"', "two\nlines"] * 2, names
EOF

# --- class 9: warnings for a duplicate link and a repeated --with ----------------------------
cat >"$work/dup.toml" <<'EOF'
[world]
dt = 0.01

[[body]]
name = "a"
mass = 1.0
position = [0.0, 0.0]

[[body]]
name = "b"
mass = 1.0
position = [1.0, 0.0]

[[spring]]
bodies = ["a", "b"]
stiffness = 10.0

[[spring]]
bodies = ["b", "a"]
stiffness = 10.0
EOF
"$fixstep" run "$work/dup.toml" --steps 1 >"$work/dup.out" 2>&1
expect "a duplicate link (either order) warns at file:line:col" \
  'warning: .*dup.toml:19:[0-9]+: spring\[1\]\.bodies: "b" and "a" are already joined by spring\[0\] \(line 1[45]\)' \
  "$work/dup.out"
"$fixstep" compare "$(dirname "$0")/../assets/scenes/projectile.toml" --with rk4@1/100 \
  --with rk4@0.01 --out "$work/rep" --frames 1 --size 320x120 >"$work/rep.out" 2>&1
expect "a repeated --with warns" \
  "warning: --with 'rk4@0.01' \(tile 2\) configures the same run as --with 'rk4@1/100'" \
  "$work/rep.out"

finish
