#!/usr/bin/env bash
# End-to-end checks of the fixstep program and the hello_fixstep demo.
#   cli_test.sh FIXSTEP HELLO SOURCE_DIR
# Each check prints "ok - ..." or "FAIL - ..."; the script exits non-zero if any failed.
set -u
fixstep=$1 hello=$2 src=$3
scenes=$src/assets/scenes
. "$(dirname "$0")/lib.sh"

# --- run ---------------------------------------------------------------------------------
"$fixstep" run "$scenes/spring_damper.toml" --steps 1000 >"$work/run.out" 2>&1
[ $? -eq 0 ] && ok "run exits 0" || fail "run exits 0"
expect "run summary has ticks and a 16-digit hash" '^ticks=1000 t=10\.000000 state_hash=[0-9a-f]{16} ' "$work/run.out"

"$fixstep" run "$scenes/spring_damper.toml" --duration 10 >"$work/run_d.out" 2>&1
[ "$(hash_of "$work/run.out")" = "$(hash_of "$work/run_d.out")" ] \
  && ok "--duration 10 equals --steps 1000 at dt 0.01" || fail "--duration 10 equals --steps 1000"

"$fixstep" run "$scenes/projectile.toml" --steps 100 --every 10 --csv "$work/p.csv" >"$work/csv.out" 2>&1
head -1 "$work/p.csv" | grep -q '^tick,t,body,x,y,vx,vy,energy,world_energy,world_dissipated,balance,x_exact,y_exact,error$' \
  && ok "csv header (with the exact solution's columns)" || fail "csv header"
expect "run reports the error against the exact solution" '^exact_error=[0-9.e+-]+ m' "$work/csv.out"
# the vacuum body's semi-implicit error at t = 1 s is g t dt / 2 = 0.04905 m (see below)
awk -F, '$1 == 100 && $3 == "vacuum" { ok = ($14 - 0.04905 < 1e-9 && 0.04905 - $14 < 1e-9) } END { exit !ok }' \
  "$work/p.csv" && ok "csv error column: vacuum at t = 1 s is off by g t dt / 2" || fail "csv error column"
# A world whose bodies carry shapes adds angle,angular_velocity after vy (others: as above).
printf '[world]\ndt = 0.01\n[[body]]\nposition = [0.0, 0.0]\nangle = 0.5\nangular_velocity = 2.0\nshape = { box = [0.5, 0.25], density = 2.0 }\n' >"$work/shaped.toml"
"$fixstep" run "$work/shaped.toml" --steps 1 --csv "$work/shaped.csv" >/dev/null 2>&1
head -1 "$work/shaped.csv" | grep -q '^tick,t,body,x,y,vx,vy,angle,angular_velocity,energy,world_energy,world_dissipated,balance' \
  && awk -F, 'NR > 1 && NF != 16 { bad = 1 } END { exit bad }' "$work/shaped.csv" \
  && ok "csv of a world with shapes: angle and angular_velocity after vy" || fail "csv angle columns"
rows=$(($(wc -l <"$work/p.csv") - 1))
[ "$rows" -eq 55 ] && ok "csv has 5 bodies x 11 recorded ticks" || fail "csv rows: $rows, want 55"
grep -q '^0,0,vacuum,0,0,15,20,' "$work/p.csv" && ok "csv tick 0 is the initial state" || fail "csv tick 0"
# vacuum after 100 ticks: x = 15 m/s * 1 s (no x force; 100 additions of 0.15 m round a little),
# y_n = n dt vy0 - g dt^2 n (n+1) / 2 = 15.04595 m (semi-implicit Euler: below the exact 15.095 m
# by g t dt / 2), vx = 15.
awk -F, '$1 == 100 && $3 == "vacuum" { ok = ($4 - 15 < 1e-9 && 15 - $4 < 1e-9 && $5 - 15.04595 < 1e-9 && 15.04595 - $5 < 1e-9 && $6 == 15) }
         END { exit !ok }' "$work/p.csv" && ok "csv values: vacuum at t = 1 s matches the closed form" \
  || { fail "csv values"; grep '^100,1,vacuum' "$work/p.csv"; }

# --- no exact solution where a disc contact has touched a body ----------------------------
# A ball dropped from 3 m onto a static peg (both r = 0.5 m) touches it when it has fallen 2 m,
# at t = sqrt(4/9.81) = 0.639 s, tick 64 at dt = 0.01 s: its CSV exact columns are filled up to
# the tick before and empty from the first touch on, and the summary claims no exact_error.
peg=$(cat "$src/tests/scenes/static_peg.toml")  # a static peg; each scene adds a body
printf '%s\n[[body]]\nname = "ball"\nmass = 1.0\nposition = [0.0, 3.0]\nradius = 0.5\ngravity = [0.0, -9.81]\n' \
  "$peg" >"$work/drop.toml"
"$fixstep" run "$work/drop.toml" --steps 100 --csv "$work/drop.csv" >"$work/drop.out" 2>&1
touch_tick=$(awk -F, '$3 == "ball" && $12 == "" { print $1; exit }' "$work/drop.csv")
[ -n "$touch_tick" ] && [ "$touch_tick" -ge 63 ] && [ "$touch_tick" -le 65 ] \
  && awk -F, -v t="$touch_tick" '$3 == "ball" && (($1 < t) != ($12 != "")) { bad = 1 } END { exit bad }' "$work/drop.csv" \
  && ok "drop on a peg: the ball's exact columns up to tick $((touch_tick - 1)), empty from the touch on" \
  || { fail "drop on a peg: exact columns (touch at '$touch_tick')"; grep -E '^6[2-6],' "$work/drop.csv"; }
expect "drop on a peg: no exact_error, the contact and its tick named" \
  "^exact_error=none \\(a disc contact touched 1 of 2 bodies from tick $touch_tick on.*know no contacts\\)$" "$work/drop.out"
# The same tick when every tick is rolled back and stepped again (the events come from the
# re-simulated tick).
"$fixstep" run "$work/drop.toml" --steps 100 --sync-test 3 >"$work/drop_sync.out" 2>&1
expect "drop on a peg under --sync-test 3: the same touch tick" "from tick $touch_tick on" "$work/drop_sync.out"
# A ball resting on the peg from tick 0 (no impact: the resting contact begins in tick 1) and a
# body falling freely beside it: the ball has no exact state from tick 1, the free body keeps
# its own, and exact_error is the free body's alone (semi-implicit Euler: g t dt / 2 = 0.04905 m
# at t = 1 s), not the ball's distance from free fall (4.9 m).
printf '%s\n[[body]]\nname = "ball"\nmass = 1.0\nposition = [0.0, 1.0]\nradius = 0.5\ngravity = [0.0, -9.81]\n[[body]]\nname = "free"\nmass = 1.0\nposition = [5.0, 1.0]\ngravity = [0.0, -9.81]\n' \
  "$peg" >"$work/rest.toml"
"$fixstep" run "$work/rest.toml" --steps 100 --csv "$work/rest.csv" >"$work/rest.out" 2>&1
grep -q '^0,0,ball,0,1,0,0,.*,0,1,0$' "$work/rest.csv" && grep -q '^1,0.01,ball,.*,,,$' "$work/rest.csv" \
  && grep -Eq '^100,1,free,.*,5,[-0-9.e]+,0.0490[0-9]*$' "$work/rest.csv" \
  && ok "resting on a peg: exact at tick 0, none from tick 1; the free body keeps its own" \
  || { fail "resting on a peg: CSV"; grep -E '^(0|1|100),' "$work/rest.csv"; }
expect "resting on a peg: exact_error is the free body's, the touched ball left out and named" \
  '^exact_error=4\.90500[0-9]e-02 m \(.*a disc contact touched 1 of 3 bodies from tick 1 on' "$work/rest.out"
# A body linked to a touched one (a zero-rest-length spring: an exact network) loses its exact
# state with it: the contact acts on it through the link.
printf '%s\n[[body]]\nname = "ball"\nmass = 1.0\nposition = [0.0, 3.0]\nradius = 0.5\ngravity = [0.0, -9.81]\n[[body]]\nname = "tied"\nmass = 1.0\nposition = [3.0, 3.0]\ngravity = [0.0, -9.81]\n[[spring]]\nbodies = ["ball", "tied"]\nstiffness = 1.0\n' \
  "$peg" >"$work/tied.toml"
"$fixstep" run "$work/tied.toml" --steps 100 --csv "$work/tied.csv" >"$work/tied.out" 2>&1
tied_tick=$(awk -F, '$3 == "tied" && $12 == "" { print $1; exit }' "$work/tied.csv")
ball_tick=$(awk -F, '$3 == "ball" && $12 == "" { print $1; exit }' "$work/tied.csv")
[ -n "$tied_tick" ] && [ "$tied_tick" = "$ball_tick" ] \
  && expect "a linked body loses its exact state with the touched one (tick $tied_tick)" \
       "^exact_error=none \\(disc contacts touched 2 of 3 bodies from tick $tied_tick on" "$work/tied.out" \
  || { fail "linked body: ball from '$ball_tick', tied from '$tied_tick'"; cat "$work/tied.out"; }

# --- the stability guard -----------------------------------------------------------------
"$fixstep" run "$scenes/spring_damper.toml" --steps 10 --integrator explicit_euler >"$work/guard.out" 2>&1
[ $? -ne 0 ] && ok "guard refuses explicit Euler on the article's spring" || fail "guard exit code"
expect "guard names body, line, bound and substeps" \
  "spring_damper\.toml:[0-9]+: body\[0\]: body 'bob' is unstable .*ω·h = 0\.0387.*bound 0\.0258.*substeps = 2" "$work/guard.out"
"$fixstep" run "$scenes/spring_damper.toml" --steps 10 --integrator explicit_euler --substeps 2 >"$work/guard2.out" 2>&1
[ $? -eq 0 ] && ok "with the suggested --substeps 2 it runs" || { fail "--substeps 2"; cat "$work/guard2.out"; }
"$fixstep" run "$scenes/spring_damper.toml" --steps 10 --integrator explicit_euler --allow-unstable >"$work/guard3.out" 2>&1
[ $? -eq 0 ] && ok "--allow-unstable runs" || fail "--allow-unstable"
expect "--allow-unstable still warns" "warning: .*unstable.*allowed \(allow_unstable\), so the run may diverge; substeps = 2" "$work/guard3.out"

# --- the runtime guard: a diverging run stops, names body, tick and cause, keeps its output --
cp "$src/tests/scenes/diverging.toml" "$work/blow.toml"  # the guard stops it at tick 14
"$fixstep" run "$work/blow.toml" --steps 1000 --csv "$work/blow.csv" >"$work/blow.out" 2>&1
[ $? -eq 3 ] && ok "a diverging run exits 3" || fail "diverging run exit code"
expect "the guard names file, line, body, tick, value and cause" \
  'error: .*blow\.toml:14: body\[1\] "stiff": state left the finite range at tick 14 \(t = 1\.4 s\): vx = 6\.7755[0-9]*e\+12 m/s.*Likely cause: .*ω·h = 3 exceeds the stability bound 2.*substeps = 2' \
  "$work/blow.out"
[ "$(tail -1 "$work/blow.csv" | cut -d, -f1)" = 14 ] && ok "the csv keeps every row up to the diverging tick" \
  || fail "blow.csv last tick: $(tail -1 "$work/blow.csv" | cut -d, -f1)"
"$fixstep" render "$work/blow.toml" --out "$work/blow_frames" --frames 600 --size 160x90 >"$work/blow_r.out" 2>&1
[ $? -eq 3 ] && ok "a diverging render exits 3" || fail "diverging render exit code"
n=$(ls "$work/blow_frames" | grep -c '^frame_[0-9]\{6\}\.png$')
[ "$n" -eq 85 ] && ok "render keeps the 85 frames up to the divergence (tick 14 at 60 fps, dt 0.1 s)" \
  || fail "render wrote $n frames before stopping"

# --- render, and the same physics whatever the path --------------------------------------
"$fixstep" render "$scenes/default.toml" --out "$work/frames" --frames 30 --size 320x180 >"$work/render.out" 2>&1
[ $? -eq 0 ] && ok "render exits 0" || { fail "render exits 0"; cat "$work/render.out"; }
n=$(ls "$work/frames" | grep -c '^frame_[0-9]\{6\}\.png$')
[ "$n" -eq 30 ] && ok "render wrote 30 frames" || fail "render wrote $n frames"
[ "$(ls -A "$work/frames" | wc -l)" -eq 31 ] && ok "no temporary files left (30 frames and frames.csv)" \
  || fail "stray files in frames/"
# frames.csv: a header and a row per frame; its last hash is the summary's, its first row is
# frame 0 at tick 0 with alpha 0.
[ "$(wc -l <"$work/frames/frames.csv")" -eq 31 ] && ok "frames.csv has a row per frame" \
  || fail "frames.csv rows: $(wc -l <"$work/frames/frames.csv")"
[ "$(head -1 "$work/frames/frames.csv")" = "frame,tick,t,alpha,state_hash,energy,balance" ] \
  && ok "frames.csv header" || fail "frames.csv header: $(head -1 "$work/frames/frames.csv")"
[ "$(sed -n 2p "$work/frames/frames.csv" | cut -d, -f1-4)" = "0,0,0.000000,0.000000" ] \
  && ok "frames.csv starts at frame 0, tick 0" || fail "frames.csv row 0: $(sed -n 2p "$work/frames/frames.csv")"
[ "$(tail -1 "$work/frames/frames.csv" | cut -d, -f5)" = "$(hash_of "$work/render.out")" ] \
  && ok "frames.csv's last hash is the summary's" || fail "frames.csv last hash vs summary"
expect "render says where the manifest is" "manifest=.*frames/frames\.csv" "$work/render.out"
# --- progress on a terminal only, and --quiet ---------------------------------------------
grep -q 'frames/s' "$work/render.out" && fail "progress printed when not on a terminal" \
  || ok "no progress line when standard error is not a terminal"
if command -v script >/dev/null; then  # util-linux `script` gives the command a terminal
  script -qec "'$fixstep' render '$scenes/default.toml' --out '$work/tty' --frames 20 --size 64x64" \
    /dev/null >"$work/tty.out" 2>&1
  grep -q $'\rrender: frame 20/20 (100 %)' "$work/tty.out" \
    && ok "render shows its progress on a terminal, one line rewritten in place" \
    || { fail "no progress line on a terminal"; cat -v "$work/tty.out"; }
  script -qec "'$fixstep' render '$scenes/default.toml' --out '$work/ttyq' --frames 20 --size 64x64 --quiet" \
    /dev/null >"$work/ttyq.out" 2>&1
  [ ! -s "$work/ttyq.out" ] && [ -s "$work/ttyq/frames.csv" ] \
    && ok "--quiet on a terminal: no progress, no summary, the frames still written" \
    || { fail "--quiet printed something"; cat -v "$work/ttyq.out"; }
fi
"$fixstep" run "$scenes/default.toml" --steps 100 --quiet >"$work/quiet.out" 2>"$work/quiet.err"
[ $? -eq 0 ] && [ ! -s "$work/quiet.out" ] && [ ! -s "$work/quiet.err" ] \
  && ok "run --quiet prints nothing and exits 0" || fail "run --quiet output"
"$fixstep" run "$work/blow.toml" --steps 100 --quiet >"$work/quiet_blow.out" 2>&1
[ $? -eq 3 ] && grep -q "^fixstep: error: .*state left the finite range" "$work/quiet_blow.out" \
  && ! grep -q "^warning\|^ticks=" "$work/quiet_blow.out" \
  && ok "run --quiet still reports the error (and only the error), exit 3" \
  || { fail "run --quiet error"; cat "$work/quiet_blow.out"; }
expect "render says where the frames are" "frames=30 .*frame_000000\.png \.\.\. .*frame_000029\.png" "$work/render.out"
ticks=$(grep -Eo '^ticks=[0-9]+' "$work/render.out" | cut -d= -f2)
"$fixstep" run "$scenes/default.toml" --steps "$ticks" >"$work/run_same.out" 2>&1
[ -n "$ticks" ] && [ "$(hash_of "$work/render.out")" = "$(hash_of "$work/run_same.out")" ] \
  && ok "render (60 fps) and run reach the same state after $ticks ticks" \
  || fail "render vs run state hash"
"$fixstep" render "$scenes/default.toml" --out "$work/f144" --frames 100 --fps 144 --size 64x64 >"$work/r144.out" 2>&1
t144=$(grep -Eo '^ticks=[0-9]+' "$work/r144.out" | cut -d= -f2)
"$fixstep" run "$scenes/default.toml" --steps "$t144" >"$work/run144.out" 2>&1
[ "$(hash_of "$work/r144.out")" = "$(hash_of "$work/run144.out")" ] \
  && ok "render at 144 fps and run agree after $t144 ticks" || fail "144 fps hash"

# --- bad input: clear message, non-zero exit ---------------------------------------------
printf '[world]\ndt = 0.01\n[[body]]\nmass = -2\nposition = [0, 0]\n' >"$work/bad.toml"
"$fixstep" run "$work/bad.toml" --steps 1 >"$work/bad.out" 2>&1
[ $? -ne 0 ] && ok "bad scene exits non-zero" || fail "bad scene exit code"
expect "bad scene names file:line:col and key" "bad\.toml:4:[0-9]+: body\[0\]\.mass: must be > 0 kg" "$work/bad.out"

"$fixstep" run "$work/missing.toml" --steps 1 >"$work/missing.out" 2>&1
[ $? -ne 0 ] && ok "missing scene exits non-zero" || fail "missing scene exit code"
expect "missing scene is named" "missing\.toml: no such scene file" "$work/missing.out"

for args in "--dt -1" "--dt nan" "--integrator rk5" "--precision f16" "--steps -3"; do
  # shellcheck disable=SC2086
  "$fixstep" run "$scenes/default.toml" --steps 1 $args >"$work/flag.out" 2>&1 </dev/null
  [ $? -ne 0 ] && ok "rejects run $args" || fail "accepted run $args"
done
"$fixstep" run "$scenes/default.toml" >"$work/nosteps.out" 2>&1
[ $? -ne 0 ] && ok "run without --steps/--duration exits non-zero" || fail "run without length"
"$fixstep" render "$scenes/default.toml" --out "$work/x" --size 10x10 >"$work/size.out" 2>&1
[ $? -ne 0 ] && ok "rejects --size 10x10" || fail "accepted --size 10x10"
"$fixstep" render "$scenes/default.toml" --out /proc/fixstep_frames --frames 1 >"$work/unwritable.out" 2>&1
[ $? -ne 0 ] && ok "unwritable --out exits non-zero" || fail "unwritable --out"
expect "unwritable --out is named" "/proc/fixstep_frames" "$work/unwritable.out"
"$fixstep" run "$scenes/default.toml" --steps 1 --csv /proc/nope/out.csv >"$work/csv_bad.out" 2>&1
[ $? -ne 0 ] && ok "unwritable --csv exits non-zero" || fail "unwritable --csv"

# command-line values get the scene's rules, and misspelt options a suggestion
"$fixstep" run "$scenes/default.toml" --steps 10 --dt 5 >"$work/dt5.out" 2>&1
[ $? -ne 0 ] && ok "--dt 5 exits non-zero" || fail "--dt 5 exit code"
expect "--dt names the allowed range" "--dt: must be a step length > 0 and <= 1 s" "$work/dt5.out"
"$fixstep" run "$scenes/default.toml" --steps 10 --intgrator rk4 >"$work/typo.out" 2>&1
[ $? -ne 0 ] && ok "a misspelt option exits non-zero" || fail "misspelt option exit code"
expect "a misspelt option gets a suggestion" "unknown option --intgrator: did you mean --integrator\?" "$work/typo.out"
"$fixstep" run "$scenes/default.toml" --duration 1e300 >"$work/dur.out" 2>&1
[ $? -ne 0 ] && ok "an absurd --duration exits non-zero" || fail "--duration 1e300 exit code"
expect "an absurd --duration says why" "--duration 1e\+300 s at dt = 0.01 s is 1e\+302 ticks" "$work/dur.out"
# A dt too short for one frame (the loop's 0.25 s clamp, or 1/fps when longer) is named by what
# set it (--dt, the scene's [world] dt, a --with), with the smallest dt that would do: the frame
# cap is ceil(0.25 s / dt) + 1 <= 2^30 ticks, so dt >= 0.25 / (2^30 - 1) = 2.33e-10 s.
dt_refused() {  # dt_refused NAME PATTERN ARGS...: exit 1, a message matching PATTERN, no Session
  local name=$1 pattern=$2
  shift 2
  "$fixstep" "$@" >"$work/dt_frame.out" 2>&1
  local got=$?
  [ "$got" -eq 1 ] && grep -Eq -- "$pattern" "$work/dt_frame.out" && ! grep -q Session "$work/dt_frame.out" \
    && ok "$name: names what set dt" || { fail "$name: exit $got"; cat "$work/dt_frame.out"; }
}
dt_refused "render --dt 1e-10 (one frame)" \
  "^fixstep: error: --dt 1e-10: a frame of up to 0.25 s \(the loop's frame-time clamp\) is 2.5e\+09 ticks .*: give --dt 2.33e-10 s or more$" \
  render "$scenes/default.toml" --out "$work/dtf" --frames 1 --dt 1e-10
dt_refused "render --dt 1e-9 --frames 100 (the command's ticks)" \
  "^fixstep: error: --frames 100 at --fps 60 with --dt 1e-09: 1650000000 ticks; a command may step at most 1e\+09 ticks$" \
  render "$scenes/default.toml" --out "$work/dtf" --frames 100 --dt 1e-9
dt_refused "render --fps 0.0001 --dt 1e-6" \
  "^fixstep: error: --dt 1e-06: a frame of 10000 s \(--fps 0.0001\) is 1e\+10 ticks .*give --dt 9.32e-06 s or more, or a larger --fps$" \
  render "$scenes/default.toml" --out "$work/dtf" --frames 2 --fps 0.0001 --dt 1e-6
sed 's/^dt = .*/dt = 1e-10/' "$scenes/default.toml" >"$work/tiny_dt.toml"
dt_refused "render of a scene with dt = 1e-10" \
  "^fixstep: error: \[world\] dt = 1e-10 s in .*tiny_dt.toml: .*set \[world\] dt \(or --dt\) to 2.33e-10 s or more$" \
  render "$work/tiny_dt.toml" --out "$work/dtf" --frames 2
dt_refused "view --dt 1e-10 (before any window)" "^fixstep: error: --dt 1e-10: a frame of up to 0.25 s" \
  view "$scenes/default.toml" --dt 1e-10 --frames 1
[ ! -e "$work/dtf" ] && ok "a refused dt writes nothing" || fail "a refused dt wrote $work/dtf"

# --png-level: 0..12; anything else exits non-zero naming the flag, the range and the value
for level in 13 -1 abc 2.5 99999999999; do
  "$fixstep" render "$scenes/default.toml" --out "$work/lvl" --frames 1 --size 64x64 --png-level "$level" \
    >"$work/level.out" 2>&1
  [ $? -ne 0 ] && ok "rejects --png-level $level" || fail "accepted --png-level $level"
  expect "--png-level $level: message names flag, range and value" \
    "^--png-level: (.*0\.\.12.*'?$level|.*level $level .*0\.\.12)" "$work/level.out"
done
[ ! -e "$work/lvl" ] && ok "a rejected --png-level writes nothing" || fail "--png-level wrote $work/lvl"
for level in 0 12; do
  "$fixstep" render "$scenes/default.toml" --out "$work/lvl$level" --frames 3 --size 64x64 --png-level "$level" \
    >"$work/level$level.out" 2>&1
  [ $? -eq 0 ] && [ "$(ls "$work/lvl$level" | grep -c '\.png$')" -eq 3 ] && ok "--png-level $level renders" \
    || { fail "--png-level $level"; cat "$work/level$level.out"; }
done
# same pixels whatever the level: level 0 stores them, so its files are the largest
[ "$(stat -c %s "$work/lvl0/frame_000002.png")" -gt "$(stat -c %s "$work/lvl12/frame_000002.png")" ] \
  && ok "--png-level reaches the encoder (level 0 files are larger than level 12)" || fail "level sizes"

# a frame the encoder thread cannot write: render fails naming it and keeps the frames before
mkdir -p "$work/blocked/frame_000005.png"
"$fixstep" render "$scenes/default.toml" --out "$work/blocked" --frames 12 --size 64x64 >"$work/blocked.out" 2>&1
[ $? -ne 0 ] && ok "render exits non-zero when a frame cannot be written" || fail "blocked frame exit code"
expect "the unwritable frame is named" "error: --out: cannot write .*/blocked/frame_000005\.png: is a directory" \
  "$work/blocked.out"
[ "$(ls -A "$work/blocked" | tr '\n' ' ')" = "frame_000000.png frame_000001.png frame_000002.png frame_000003.png frame_000004.png frame_000005.png " ] \
  && ok "frames 0-4 kept, nothing after the failure, no temporaries" || { fail "blocked dir contents"; ls -A "$work/blocked"; }
# the same for the last frame, whose failure can only show when render waits for the writer
mkdir -p "$work/blocked_last/frame_000005.png"
"$fixstep" render "$scenes/default.toml" --out "$work/blocked_last" --frames 6 --size 64x64 >"$work/blocked_last.out" 2>&1
[ $? -ne 0 ] && ok "render exits non-zero when the last frame cannot be written" || fail "blocked last frame exit code"
expect "the unwritable last frame is named" "error: --out: cannot write .*/blocked_last/frame_000005\.png: is a directory" \
  "$work/blocked_last.out"

# --- SIGINT / SIGTERM: stop after the current frame, keep every frame complete -------------
for sig in INT TERM; do
  "$fixstep" render "$scenes/default.toml" --out "$work/sig_$sig" --frames 1000000 --size 160x90 \
    >"$work/sig_$sig.out" 2>&1 &
  pid=$!
  for _ in $(seq 200); do [ -e "$work/sig_$sig/frame_000002.png" ] && break; sleep 0.1; done
  kill -s "$sig" "$pid"
  wait "$pid"
  code=$?
  want=$([ "$sig" = INT ] && echo 130 || echo 143)
  [ "$code" -eq "$want" ] && ok "SIG$sig stops render with exit $want" || fail "SIG$sig exit $code"
  expect "SIG$sig is reported" "stopped by SIG$sig after [0-9]+ frames" "$work/sig_$sig.out"
  stray=$(ls -A "$work/sig_$sig" | grep -v '^frames\.csv$' | grep -vc '^frame_[0-9]\{6\}\.png$')
  broken=0
  for f in "$work/sig_$sig"/frame_*.png; do
    [ "$(tail -c 8 "$f" | head -c 4)" = IEND ] || broken=$((broken + 1))
  done
  n=$(ls "$work/sig_$sig" | grep -c '\.png$')
  rows=$(($(wc -l <"$work/sig_$sig/frames.csv") - 1))
  [ "$rows" -eq "$n" ] && ok "after SIG$sig frames.csv lists the $n frames written" \
    || fail "after SIG$sig frames.csv has $rows rows for $n frames"
  [ "$stray" -eq 0 ] && [ "$broken" -eq 0 ] && [ "$n" -ge 3 ] \
    && ok "after SIG$sig: $n complete frames, no temporary files" \
    || fail "after SIG$sig: $n frames, $broken truncated, $stray stray files"
done

# a hard kill (SIGKILL, no cleanup at all): no partial file may stand under a final name
"$fixstep" render "$scenes/default.toml" --out "$work/sig_KILL" --frames 1000000 --size 160x90 \
  >"$work/sig_KILL.out" 2>&1 &
pid=$!
for _ in $(seq 200); do [ -e "$work/sig_KILL/frame_000002.png" ] && break; sleep 0.1; done
kill -s KILL "$pid"
wait "$pid" 2>/dev/null
broken=0
for f in "$work/sig_KILL"/frame_*.png; do
  [ "$(tail -c 8 "$f" | head -c 4)" = IEND ] || broken=$((broken + 1))
done
n=$(ls "$work/sig_KILL" | grep -c '^frame_[0-9]\{6\}\.png$')
[ "$broken" -eq 0 ] && [ "$n" -ge 3 ] && ok "after SIGKILL: all $n frames under final names are complete" \
  || fail "after SIGKILL: $broken of $n final-named frames truncated"

# --- view --------------------------------------------------------------------------------
env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$fixstep" view "$scenes/default.toml" --frames 1 >"$work/nodisp.out" 2>&1
[ $? -ne 0 ] && ok "view without a display exits non-zero" || fail "view without display"
expect "view without a display points at render" "no display.*fixstep render" "$work/nodisp.out"

# a DISPLAY that leads nowhere: SDL would fall back to a driver that shows nothing
env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER DISPLAY=:97 "$fixstep" view "$scenes/default.toml" --frames 1 >"$work/baddisp.out" 2>&1
[ $? -ne 0 ] && ok "view with an unreachable DISPLAY exits non-zero" || fail "view with DISPLAY=:97"
expect "view names the unreachable display" "no display: could not connect to DISPLAY=:97" "$work/baddisp.out"
env -u DISPLAY -u WAYLAND_DISPLAY SDL_VIDEODRIVER=nonexistent "$fixstep" view "$scenes/default.toml" --frames 1 >"$work/sdlfail.out" 2>&1
[ $? -ne 0 ] && ok "view exits non-zero when SDL cannot initialise" || fail "SDL init failure exit"
expect "SDL's reason is shown" "SDL could not initialise video \(nonexistent not available\)" "$work/sdlfail.out"
# OSMesa unable to give a GL 3.3 core context
MESA_GL_VERSION_OVERRIDE=2.1 "$fixstep" render "$scenes/default.toml" --out "$work/gl21" --frames 2 --size 64x64 >"$work/gl21.out" 2>&1
[ $? -ne 0 ] && ok "render exits non-zero without a GL 3.3 context" || fail "GL 2.1 exit code"
expect "the context failure is explained" "OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core context" "$work/gl21.out"

GALLIUM_DRIVER=foo "$fixstep" render "$scenes/default.toml" --out "$work/gd" --frames 2 --size 64x64 >"$work/gd.out" 2>&1
[ $? -eq 1 ] && ok "render refuses an unusable GALLIUM_DRIVER (Mesa would crash)" || fail "GALLIUM_DRIVER=foo exit code"
expect "the driver is named" "GALLIUM_DRIVER=foo is not a driver OSMesa can use" "$work/gd.out"

if have_xvfb; then
  with_xvfb "$fixstep" view "$scenes/default.toml" --frames 30 --fps 60 \
    --size 320x180 >"$work/view.out" 2>&1
  [ $? -eq 0 ] && ok "view runs under Xvfb" || { fail "view under Xvfb"; cat "$work/view.out"; }
  [ "$(hash_of "$work/view.out")" = "$(hash_of "$work/render.out")" ] \
    && ok "window and headless reach the same state after 30 frames" || fail "view vs render hash"
  # Sprites, a tiled background and styled segments in the window (the same renderer's pixels,
  # presented): it runs, and reaches the headless run's state.
  sprites_scene=$scenes/sprites.toml
  with_xvfb "$fixstep" view "$sprites_scene" --frames 30 --fps 60 --size 320x180 \
    >"$work/view_sprites.out" 2>&1
  [ $? -eq 0 ] && ok "view of the sprites scene runs under Xvfb" \
    || { fail "view of sprites under Xvfb"; cat "$work/view_sprites.out"; }
  "$fixstep" render "$sprites_scene" --out "$work/sprite_frames" --frames 30 --size 320x180 \
    >"$work/render_sprites.out" 2>&1
  [ "$(hash_of "$work/view_sprites.out")" = "$(hash_of "$work/render_sprites.out")" ] \
    && ok "window and headless draw the sprites scene to the same state" \
    || fail "view vs render hash (sprites)"
  # the runtime guard in the window: it pauses, says why, and view exits 3
  with_xvfb "$fixstep" view "$work/blow.toml" --frames 120 --fps 60 \
    --size 320x180 >"$work/view_blow.out" 2>&1
  code=$?
  [ "$code" -eq 3 ] && ok "view exits 3 after the guard stopped the simulation" \
    || { fail "view guard exit $code"; cat "$work/view_blow.out"; }
  expect "view reports the guard's message once" "error: .*body\[1\] \"stiff\": state left the finite range at tick 14" \
    "$work/view_blow.out"
  expect "view stays at the diverging tick (paused)" "ticks=14 " "$work/view_blow.out"
  # Rewind keeps 10 s of states within 512 MiB: a 200 x 200 grid (20 MiB a state) keeps less.
  grep -q "note: rewind" "$work/view.out" && fail "a small scene's rewind is capped" \
    || ok "a small scene keeps 10 s of rewind (no note)"
  cat >"$work/big.toml" <<'EOF_SCENE'
[world]
dt = 0.01
[[grid]]
name = "g"
columns = 200
rows = 200
origin = [0.0, 0.0]
spacing = [0.25, -0.25]
body = { mass = 0.01, gravity = [0.0, -9.81] }
link = { frequency = 2.0, damping_ratio = 0.2 }
EOF_SCENE
  with_xvfb "$fixstep" view "$work/big.toml" --frames 2 --fps 60 --size 320x180 >"$work/view_big.out" 2>&1
  [ $? -eq 0 ] && ok "view of 40 000 linked bodies runs" || { fail "view of a big grid"; cat "$work/view_big.out"; }
  expect "a big world's rewind is capped at 512 MiB, and said so" \
    "note: rewind keeps the last 0\.[0-9]+ s \([0-9]+ ticks\), not 10 s: a state of this world takes [0-9.]+ MiB and rewind at most 512 MiB" \
    "$work/view_big.out"
else
  echo "skip - Xvfb not installed (bash .ci/install-deps installs it)"
fi

# --- the window, recorded: real mouse drags (xdotool) under Xvfb, then replayed headless -----
cat >"$work/dragme.toml" <<'EOF_SCENE'
[world]
dt = 0.01
[view]
center = [0.0, 0.0]
width = 20.0
[[body]]
name = "ball"
mass = 1.0
position = [0.0, 0.0]
spring = { anchor = [0.0, 0.0], stiffness = 8.0 }
radius = 0.5
EOF_SCENE
if have_xvfb && command -v xdotool >/dev/null; then
  # The ball rests at the centre of the 320x180 window (pixel 160,90); the left button picks it
  # there, drags it up and right, lets go, then drags it again. Real clock, about 4 s.
  with_xvfb bash -c '
    "$1" view "$2" --size 320x180 --frames 240 --record "$3" >"$4" 2>&1 &
    view=$!
    for _ in $(seq 100); do
      wid=$(xdotool search --name "fixstep - " 2>/dev/null | head -1); [ -n "$wid" ] && break; sleep 0.05
    done
    sleep 0.3
    xdotool mousemove --window "$wid" 160 90 mousedown 1; sleep 0.4
    xdotool mousemove --window "$wid" 260 40; sleep 0.4; xdotool mouseup 1; sleep 0.3
    xdotool mousemove --window "$wid" 160 90 mousedown 1; sleep 0.2
    xdotool mousemove --window "$wid" 60 140; sleep 0.3; xdotool mouseup 1
    wait "$view"' _ "$fixstep" "$work/dragme.toml" "$work/drag.rec" "$work/drag_view.out"
  [ $? -eq 0 ] && ok "view --record under Xvfb exits 0" || { fail "view --record"; cat "$work/drag_view.out"; }
  grep -q ' drag=1:1$' "$work/drag.rec" && ok "the recording holds the mouse drag of body 0" \
    || fail "no drag in the window's recording"
  "$fixstep" replay "$work/drag.rec" >"$work/drag_replay.out" 2>&1
  [ $? -eq 0 ] && ok "the window's recording replays headless with every hash verified" \
    || { fail "replay of the window's recording"; cat "$work/drag_replay.out"; }
  [ "$(hash_of "$work/drag_replay.out")" = "$(hash_of "$work/drag_view.out")" ] \
    && ok "the replay ends at the window's final state" || fail "window vs replay hash"
  # A stop request (SIGINT) ends view as it ends run: exit 130, its recording written and
  # verified by a replay. Between ticks (SDL's own handler made it a quit: exit 0), and inside a
  # 1.2 s tick (long_tick.toml at 3000 substeps), which is discarded (SDL's quit waited for the
  # frame's ticks to end).
  # view_stopped WAIT SCENE OUT REC ARGS...: view in the background, SIGINT WAIT seconds after
  # its window appears; its exit status. A job started with & by a shell without job control
  # ignores SIGINT until view installs its own handler, just before its window, so the signal
  # must wait for the window: up to 60 s (long_tick.toml's load took 24 s under
  # AddressSanitizer on a slow 2-core machine).
  view_stopped() {
    with_xvfb bash -c '
      "$1" view "$2" --size 320x180 --frames 100000 --fps 60 --record "$4" "${@:6}" >"$3" 2>&1 &
      view=$!
      for _ in $(seq 1200); do
        wid=$(xdotool search --name "fixstep - " 2>/dev/null | head -1); [ -n "$wid" ] && break; sleep 0.05
      done
      sleep "$5"
      kill -INT "$view"
      for _ in $(seq 600); do kill -0 "$view" 2>/dev/null || break; sleep 0.05; done
      kill -0 "$view" 2>/dev/null && kill -9 "$view"
      wait "$view"' _ "$fixstep" "$2" "$3" "$4" "$1" "${@:5}"
  }
  # Inside a tick: the first tick begins only after the first frame is drawn, which on a loaded
  # machine can take longer than the wait; a signal that came before any tick (the output says
  # "after tick 0" and no tick discarded) is sent again to a new view after a longer wait. Once
  # ticks run (about 1.2 s each here, a frame between them a few ms) the signal lands in one.
  for stop in between:"$scenes/default.toml" inside:"$src/tests/scenes/long_tick.toml"; do
    where=${stop%%:*} scene=${stop#*:}
    extra=()
    [ "$where" = inside ] && extra=(--substeps 3000)
    for wait_s in 0.6 2 5; do
      view_stopped "$wait_s" "$scene" "$work/stop_$where.out" "$work/stop_$where.rec" "${extra[@]}"
      code=$?
      [ "$where" = inside ] && grep -q 'after tick 0;' "$work/stop_$where.out" || break
      echo "# view stopped before its first tick after a ${wait_s} s wait: again, waiting longer"
    done
    [ "$code" -eq 130 ] && ok "SIGINT $where ticks ends view with exit 130" \
      || { fail "view SIGINT $where ticks: exit $code"; cat "$work/stop_$where.out"; }
    expect "view says it was stopped ($where ticks)" \
      '^fixstep: stopped by SIGINT after tick [0-9]+.*; recording written$' "$work/stop_$where.out"
    "$fixstep" replay "$work/stop_$where.rec" >"$work/stop_${where}_replay.out" 2>&1 \
      && ok "the recording of a view stopped $where ticks replays, every hash verified" \
      || { fail "replay of the stopped view ($where)"; cat "$work/stop_${where}_replay.out"; }
  done
  expect "a tick stopped half-way is discarded" 'after tick [0-9]+ \(the tick in progress discarded\)' \
    "$work/stop_inside.out"
else
  echo "skip - Xvfb or xdotool not installed (bash .ci/install-deps installs them)"
fi

# --- the sync test: rollbacks of K ticks every tick, on a scripted run --------------------
"$fixstep" run "$scenes/default.toml" --steps 200 --input "$src/assets/inputs/default_push.toml" \
  --sync-test 8 >"$work/sync.out" 2>&1
[ $? -eq 0 ] && ok "run --sync-test 8 exits 0" || { fail "sync test"; cat "$work/sync.out"; }
expect "the sync test says what it checked" '^sync_test: rolled back 8 ticks at every tick, 1572 ticks re-simulated, every state equal$' "$work/sync.out"
"$fixstep" run "$scenes/default.toml" --steps 200 --input "$src/assets/inputs/default_push.toml" >"$work/nosync.out" 2>&1
[ "$(hash_of "$work/sync.out")" = "$(hash_of "$work/nosync.out")" ] \
  && ok "the sync test ends at the plain run's state" || fail "sync vs plain hash"
grep -q exact_error "$work/sync.out" && fail "exact_error printed for a scripted run" \
  || ok "no exact error for a run with scripted input (the exact solutions are of the scene alone)"

# --- record and replay -----------------------------------------------
# A scripted session recorded with a hash every tick, replayed from another directory (the
# scene path is found beside the recording), a flipped input bit, and every bad recording.
mkdir -p "$work/rec/scenes" "$work/elsewhere"
cp "$scenes/default.toml" "$work/rec/scenes/default.toml"
(cd "$work/rec" && "$fixstep" run scenes/default.toml --steps 300 --input "$src/assets/inputs/default_push.toml" \
  --record session.rec --hash-every 1 >"$work/rec_run.out" 2>&1)
[ $? -eq 0 ] && ok "run --input --record exits 0" || { fail "run --input --record"; cat "$work/rec_run.out"; }
expect "run says where the recording is" '^recording=session\.rec$' "$work/rec_run.out"
head -1 "$work/rec/session.rec" | grep -qx 'fixstep-recording 3' && ok "the recording starts with its magic and version" \
  || fail "recording magic"
"$fixstep" run "$scenes/default.toml" --steps 300 >"$work/rec_plain.out" 2>&1
h_rec=$(hash_of "$work/rec_run.out")
[ -n "$h_rec" ] && [ "$h_rec" != "$(hash_of "$work/rec_plain.out")" ] && ok "the scripted pushes change the state" \
  || fail "the script changed nothing"
(cd "$work/elsewhere" && "$fixstep" replay ../rec/session.rec >"$work/replay.out" 2>&1)
[ $? -eq 0 ] && ok "replay verifies (exit 0)" || { fail "replay exit"; cat "$work/replay.out"; }
expect "replay verified every tick's hash and the end" '^verified 301 hashes, ticks=300 state_hash=' "$work/replay.out"
[ -n "$h_rec" ] && [ "$(hash_of "$work/replay.out")" = "$h_rec" ] && ok "replay ends at the run's state" \
  || fail "replay final hash"
# one bit of the push at tick 60 flipped (15 -> 7.5: 0x402e... -> 0x401e...): the state after 61 ticks differs
sed 's/^tick 60 push=0,15 /tick 60 push=0,7.5 /' "$work/rec/session.rec" >"$work/rec/flipped.rec"
cmp -s "$work/rec/session.rec" "$work/rec/flipped.rec" && fail "flipped.rec unchanged"
"$fixstep" replay "$work/rec/flipped.rec" >"$work/flip.out" 2>&1
[ $? -eq 4 ] && ok "a flipped input bit: replay exits 4" || { fail "flipped exit"; cat "$work/flip.out"; }
expect "replay names the first diverging tick" 'replay diverged at tick 61: state_hash [0-9a-f]{16} recorded, [0-9a-f]{16} replayed \(the states matched at tick 60\)' "$work/flip.out"
head -c 2000 "$work/rec/session.rec" >"$work/rec/cut.rec"
"$fixstep" replay "$work/rec/cut.rec" >"$work/cut.out" 2>&1
[ $? -eq 5 ] && ok "a truncated recording exits 5" || fail "truncated exit"
expect "truncation is named with the line" 'cut\.rec:[0-9]+: .*cut short' "$work/cut.out"
"$fixstep" replay "$scenes/default.toml" >"$work/foreign.out" 2>&1
[ $? -eq 5 ] && ok "a foreign file exits 5" || fail "foreign exit"
expect "a foreign file is named as such" 'default\.toml:1: not a fixstep recording' "$work/foreign.out"
sed '1s/.*/fixstep-recording 9/' "$work/rec/session.rec" >"$work/rec/v9.rec"
"$fixstep" replay "$work/rec/v9.rec" >"$work/v9.out" 2>&1
[ $? -eq 7 ] && ok "an unsupported version exits 7" || fail "version exit"
sed 's/^tick 60 push=0,15 held=4 /tick 60 push=0,15 held=4000 /' "$work/rec/session.rec" >"$work/rec/bits.rec"
"$fixstep" replay "$work/rec/bits.rec" >"$work/bits.out" 2>&1
[ $? -eq 5 ] && ok "a corrupt recording exits 5" || fail "corrupt exit"
expect "the corrupt field is named" 'bits\.rec:[0-9]+: held: bits 4000 are not buttons' "$work/bits.out"
sed 's/^mass = 1.0 /mass = 1.5 /' "$work/rec/scenes/default.toml" >"$work/rec/changed.toml"
"$fixstep" replay "$work/rec/session.rec" --scene "$work/rec/changed.toml" >"$work/mismatch.out" 2>&1
[ $? -eq 6 ] && ok "a scene that changed exits 6" || { fail "mismatch exit"; cat "$work/mismatch.out"; }
expect "the mismatch names both hashes" 'no longer matches the recording .*definition hash [0-9a-f]{16}, recorded [0-9a-f]{16}' "$work/mismatch.out"
# render --replay: the frames follow the recorded ticks; every frames.csv hash is the recording's
"$fixstep" render "$work/rec/scenes/default.toml" --replay "$work/rec/session.rec" --out "$work/rec_frames" \
  --frames 200 --size 160x90 >"$work/rec_render.out" 2>&1
[ $? -eq 0 ] && ok "render --replay exits 0" || { fail "render --replay"; cat "$work/rec_render.out"; }
awk 'NR == FNR { if ($1 == "hash") h[$2] = $3; next }
     FNR > 1 { split($0, f, ","); if (f[2] > 0 && f[2] <= 300) { n++; if (h[f[2]] != f[5]) bad++ } }
     END { exit !(n > 100 && bad == 0) }' "$work/rec/session.rec" FS=, "$work/rec_frames/frames.csv" \
  && ok "render --replay: every frame's state_hash is the recording's at its tick" || fail "render --replay hashes"
# without SCENE, render --replay draws the recording's own scene (found beside the recording)
(cd "$work/elsewhere" && "$fixstep" render --replay ../rec/session.rec --out "$work/rec_frames2" \
  --frames 200 --size 160x90 >"$work/rec_render2.out" 2>&1)
[ $? -eq 0 ] && ok "render --replay FILE without SCENE exits 0" || { fail "render --replay without scene"; cat "$work/rec_render2.out"; }
cmp -s "$work/rec_frames/frames.csv" "$work/rec_frames2/frames.csv" \
  && ok "render --replay without SCENE makes the same frames.csv" || fail "render --replay scene default"
"$fixstep" render --out "$work/noscene" >"$work/noscene.out" 2>&1
[ $? -eq 2 ] && ok "render without SCENE or --replay exits 2" || fail "render without scene"
expect "render without SCENE says what to give" 'give SCENE \(or --replay FILE' "$work/noscene.out"

# --- fixstep new: the real cause of a write that fails -----------------------------------
# Past `ulimit -f 0` every file's first flush fails with EFBIG; the small files are written at
# fclose, and the message said "No such file or directory" (a stale errno) instead. Output goes
# through a pipe: a file written under the limit would fail too.
(cd "$work" && ulimit -f 0 && "$fixstep" new sized_out 2>&1; echo "exit=$?") | cat >"$work/new_efbig.out"
expect "new past the file-size limit exits 1" '^exit=1$' "$work/new_efbig.out"
expect "new past the file-size limit reports EFBIG, not a stale errno" \
  'cannot write sized_out/[A-Za-z.]+: File too large \(fixstep new left nothing behind\)' "$work/new_efbig.out"
[ ! -e "$work/sized_out" ] && ok "new past the file-size limit leaves nothing" || fail "new left sized_out"

# --- the exact reference of a network is bounded: a dense eigen-decomposition --------------
# A 100 x 100 grid of zero-rest-length links (linear, proportional damping) had an exact
# solution: an eigen-decomposition of a dense 10^4 x 10^4 system, over a minute and 1.7 GB
# (9*10^4 bodies would ask for 65 GB). Past max_exact_network_bodies (1000) it has none.
printf '[world]\ndt = 0.01\n[[grid]]\ncolumns = 100\nrows = 100\norigin = [0.0, 0.0]\nspacing = [0.1, 0.1]\nbody = { mass = 1.0 }\nlink = { stiffness = 10.0, damping = 0.1, rest_length = 0.0 }\n' \
  >"$work/net_1e4.toml"
timeout 60 "$fixstep" run "$work/net_1e4.toml" --steps 2 >"$work/net_1e4.out" 2>&1
code=$?
[ "$code" -eq 0 ] && ok "run of a 10^4-body linear network exits 0 (no dense exact solve; 60 s guard)" \
  || { fail "run of a 10^4-body network: exit $code"; cat "$work/net_1e4.out"; }
grep -q '^exact_error=' "$work/net_1e4.out" && fail "an exact error for a network past 1000 bodies" \
  || ok "no exact error past max_exact_network_bodies"
"$fixstep" run "$scenes/spring_damper.toml" --steps 10 >"$work/small_exact.out" 2>&1
expect "a small scene keeps its exact error" '^exact_error=' "$work/small_exact.out"

# --- text drawn is bounded: a body name of 2 MB in the guard's message --------------------
# The renderer's glyph scratch took 1 kB a character of a HUD line: the runtime guard's message
# naming a body of a 2 MB name asked for 6.4 GB. Within 2 GB of address space the render ends
# with the guard's located error (exit 3), not an allocation failure. Not under ASan.
if ! grep -qa __asan_init "$fixstep"; then
  { printf '[world]\ndt = 0.5\n[[body]]\nname = "'; head -c 2000000 /dev/zero | tr '\0' x
    printf '"\ntype = "kinematic"\nposition = [0.0, 0.0]\nvelocity = [9e11, 0.0]\n'; } >"$work/long_name.toml"
  (ulimit -v 2000000 && "$fixstep" render "$work/long_name.toml" --out "$work/long_name" --frames 120 \
    --size 320x180 2>&1 >/dev/null; echo "exit=$?") | cut -c1-200 | cat >"$work/long_name.out"
  expect "a 2 MB body name in the guard's HUD message: the located error, exit 3, within 2 GB" \
    '^exit=3$' "$work/long_name.out"
fi

# --- memory: a std::bad_alloc past the estimate's check is located ---------------------------
# With less address space than the 10^5-body grid needs (ulimit -v 80 MB, far under the estimate's
# 4 GiB bound), the allocation fails inside the command: the message names the command and the
# phase (it said only "std::bad_alloc"). Not under AddressSanitizer, which needs terabytes of
# address space.
if grep -qa __asan_init "$fixstep"; then
  echo "skip - ulimit -v under AddressSanitizer"
else
  printf '[world]\ndt = 0.01\n[[grid]]\ncolumns = 100\nrows = 1000\norigin = [0.0, 0.0]\nspacing = [0.1, 0.1]\nbody = { mass = 1.0 }\n' \
    >"$work/grid_1e5.toml"
  (ulimit -v 80000 && "$fixstep" run "$work/grid_1e5.toml" --steps 2 2>&1; echo "exit=$?") | cat >"$work/oom.out"
  expect "an allocation that fails exits 1" '^exit=1$' "$work/oom.out"
  expect "an allocation that fails names the command and its phase" \
    '^fixstep: error: run: out of memory \(std::bad_alloc\) while (loading the scene|building the world|stepping the world): ' \
    "$work/oom.out"
  # Beyond the 4 GiB bound, compare and view are refused from their estimate before they
  # allocate: within 1 GB of address space the LimitError comes, not a std::bad_alloc (the
  # scene's own load takes 0.15 and 0.4 GB; without the estimate the tiles would take ~5 GB).
  printf '[world]\ndt = 0.01\n[[grid]]\ncolumns = 300\nrows = 1000\norigin = [0.0, 0.0]\nspacing = [0.1, 0.1]\nbody = { mass = 1.0 }\n' \
    >"$work/grid_3e5.toml"
  (ulimit -v 1000000 && "$fixstep" compare "$work/grid_3e5.toml" --with rk4 --with semi_implicit_euler \
    --with velocity_verlet --with rk4@0.005 --with semi_implicit_euler@0.005 \
    --with velocity_verlet@0.005 --out "$work/tiles_3e5" --frames 2 2>&1; echo "exit=$?") | cat >"$work/mem_compare.out"
  expect "compare of six tiles of 3*10^5 bodies is refused before it allocates" \
    '^fixstep: error: compare .*grid_3e5\.toml: would need about [0-9.]+ GiB of memory .*a command may use at most 4 GiB .*dominates: fewer --with tiles' \
    "$work/mem_compare.out"
  expect "the refused compare exits 1" '^exit=1$' "$work/mem_compare.out"
  printf '[world]\ndt = 0.01\n[contacts]\n[[grid]]\ncolumns = 750\nrows = 1000\norigin = [0.0, 0.0]\nspacing = [0.1, 0.1]\nbody = { mass = 1.0, radius = 0.05 }\n' \
    >"$work/discs_75e4.toml"
  (ulimit -v 1000000 && env -u DISPLAY "$fixstep" view "$work/discs_75e4.toml" --frames 1 2>&1; echo "exit=$?") | cat >"$work/mem_view.out"
  expect "view of 7.5*10^5 touching discs is refused before it allocates (or opens a window)" \
    '^fixstep: error: view .*discs_75e4\.toml: would need about [0-9.]+ GiB of memory .*rewind buffer' \
    "$work/mem_view.out"
  expect "the refused view exits 1" '^exit=1$' "$work/mem_view.out"
fi

# --- the demo ----------------------------------------------------------------------------
(cd "$work" && "$hello" demo_frames >"$work/hello.out" 2>&1)
[ "$(ls "$work/demo_frames" | wc -l)" -eq 90 ] && ok "hello_fixstep writes 90 frames" || fail "hello_fixstep"

finish
