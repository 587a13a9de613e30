#!/usr/bin/env bash
# Hot reload in `fixstep view` under Xvfb: the scene file is rewritten while the window runs.
#   view_reload_test.sh FIXSTEP [GRID]
# A good edit is reloaded (tick reset, the new body count and definition hash reported); a bad
# edit is reported with its file:line:column and the last good world keeps running; fixing the
# file reloads it; with --record the session keeps its world and the recording carries it (it
# replays with the edit on disk, or with the file gone); --no-watch turns reloading off. A save
# loads on a thread of its own: the world before it runs on, a newer save replaces the load, Esc
# drops it. Every wait is bounded (60 s) and waits for an outcome, not
# for a time; the program is quit with Esc (xdotool). Prints "ok - ..." / "FAIL - ...".
set -u
fixstep=$1
# The slow load's grid, GRID x GRID linked bodies: 600 (about 1.5 s to load in an optimised
# build); the sanitized Debug build passes 150 (about 5 s there: 600 took over a minute).
grid=${2:-600}
grid_bodies=$((grid * grid))
. "$(dirname "$0")/lib.sh"

if ! have_xvfb || ! command -v xdotool >/dev/null; then
  echo "skip - Xvfb or xdotool not installed (bash .ci/install-deps installs them)"
  finish
fi
start_xvfb || exit 1
export DISPLAY=$xvfb_display
unset WAYLAND_DISPLAY SDL_VIDEODRIVER

scene=$work/scene.toml
# scene_text N MASS: N bodies in a row on springs, the first of mass MASS (kg).
scene_text() {
  printf '[world]\ndt = 0.01\n[view]\ncenter = [0.0, 0.0]\nwidth = 12.0\n'
  local i
  for i in $(seq 0 $(($1 - 1))); do
    printf '[[body]]\nname = "b%d"\nmass = %s\nposition = [%d.0, 1.0]\n' "$i" \
      "$([ "$i" -eq 0 ] && echo "$2" || echo 1.0)" "$((2 * i - 2))"
    printf 'spring = { anchor = [%d.0, 0.0], stiffness = 10.0 }\nradius = 0.4\n' "$((2 * i - 2))"
  done
}
save_by_rename() { scene_text "$@" >"$scene.new" && mv "$scene.new" "$scene"; }  # a new inode
# The same inode, in one write: a poll between printf's many writes could load a valid half.
save_in_place() { local text; text=$(scene_text "$@") && printf '%s\n' "$text" >"$scene"; }

# wait_for RE FILE: until FILE matches RE (60 s at most); false if it never does.
wait_for() {
  local _
  for _ in $(seq 600); do
    grep -Eq -- "$1" "$2" 2>/dev/null && return 0
    sleep 0.1
  done
  return 1
}
# start_view OUT ERR ARGS...: `fixstep view SCENE ARGS` in the background (pid in $view), once
# its window is up. --frames bounds it to about 2 minutes at 60 Hz should Esc never arrive.
start_view() {
  local out=$1 err=$2 _
  shift 2
  "$fixstep" view "$scene" --size 800x600 --frames 7200 "$@" >"$out" 2>"$err" &
  view=$! wid=""
  for _ in $(seq 600); do
    wid=$(xdotool search --name "fixstep - " 2>/dev/null | head -1)
    [ -n "$wid" ] && return 0
    kill -0 "$view" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
# quit_view: Esc to the window, then its exit status (killed after 60 s: 124).
quit_view() {
  timeout 10 xdotool windowfocus --sync "$wid" key Escape 2>/dev/null ||
    xdotool key --window "$wid" Escape
  local _
  for _ in $(seq 600); do
    kill -0 "$view" 2>/dev/null || break
    sleep 0.1
  done
  kill -0 "$view" 2>/dev/null && { kill "$view"; wait "$view"; return 124; }
  wait "$view"
}
tick_in() { grep -Eo "$1" "$2" | head -1 | grep -Eo '[0-9]+$'; }

# --- a good edit, a bad edit, the fix --------------------------------------------------------
save_by_rename 1 1.0
start_view "$work/view.out" "$work/view.err" || { fail "view did not open a window"; cat "$work/view.err"; finish; }
save_by_rename 2 1.0
wait_for '^reloaded .*scene\.toml: 2 bodies, definition hash [0-9a-f]{16}; tick reset to 0 \(was [0-9]+\)$' \
  "$work/view.out" && ok "a file saved by rename is reloaded (2 bodies, tick reset)" \
  || { fail "no reload after the first edit"; cat "$work/view.out" "$work/view.err"; }
# the bad edit, in place (as an editor writing over the file): body[1]'s mass is on line 14
scene_text 2 1.0 | sed '14s/mass = 1.0/mass = -1.0/' >"$scene"
wait_for 'reload failed: .*scene\.toml:14:8: body\[1\]\.mass: must be > 0 kg \(got -1\); the last good world keeps running \(tick [0-9]+\)$' \
  "$work/view.err" && ok "a bad edit is reported with file:line:column" \
  || { fail "no located error for the bad edit"; cat "$work/view.err"; }
kill -0 "$view" 2>/dev/null && ok "view keeps running after a bad edit" || fail "view exited on a bad edit"
bad_tick=$(tick_in 'keeps running \(tick [0-9]+' "$work/view.err")
save_in_place 3 2.0
wait_for '^reloaded .*: 3 bodies, .*\(was [0-9]+\)$' "$work/view.out" \
  && ok "fixing the file reloads it (3 bodies)" || { fail "no reload after the fix"; cat "$work/view.out"; }
fixed_from=$(tick_in '3 bodies, .*\(was [0-9]+' "$work/view.out")
[ -n "$bad_tick" ] && [ -n "$fixed_from" ] && [ "$fixed_from" -gt "$bad_tick" ] \
  && ok "the last good world ran on after the bad edit (tick $bad_tick -> $fixed_from)" \
  || fail "the last good world did not run on (ticks '$bad_tick' -> '$fixed_from')"
hash_two=$(grep -E ': 2 bodies, ' "$work/view.out" | grep -Eo 'definition hash [0-9a-f]{16}' | head -1)
hash_three=$(grep -E ': 3 bodies, ' "$work/view.out" | grep -Eo 'definition hash [0-9a-f]{16}' | tail -1)
[ -n "$hash_two" ] && [ -n "$hash_three" ] && [ "$hash_two" != "$hash_three" ] \
  && ok "each reloaded world has its own definition hash" \
  || fail "definition hashes: '$hash_two' and '$hash_three'"
quit_view
[ $? -eq 0 ] && ok "view exits 0 after reloads" || { fail "view exit"; cat "$work/view.err"; }
expect "the summary is of the last world" '^scene=.*scene\.toml integrator=.* driver=' "$work/view.out"
expect "the summary's ticks count from the last reload" '^ticks=[0-9]+ ' "$work/view.out"

# The reloaded world was built on the load's thread: with no input it steps as `run` does.
last_ticks=$(grep -Eo '^ticks=[0-9]+' "$work/view.out" | cut -d= -f2)
"$fixstep" run "$scene" --steps "${last_ticks:-0}" >"$work/run_same.out" 2>&1
[ -n "$last_ticks" ] && [ "$(hash_of "$work/view.out")" = "$(hash_of "$work/run_same.out")" ] \
  && ok "the reloaded world's state after $last_ticks ticks is run's" \
  || { fail "reloaded world vs run: $(cat "$work/view.out" "$work/run_same.out")"; }

# --- a slow load: the window keeps showing the world before the save ------------------------
# grid_text COLUMNS ROWS: a grid of linked bodies. 1000 x 1000 (10^6 bodies, 2*10^6 links, the
# largest legal grid) takes ~5 s to load and build here, GRID x GRID (600) about 1.5 s. Its unknown key
# world.mark is warned of when the loaded world is shown.
grid_text() {
  printf '[world]\ndt = 0.01\nmark = %d\n[[grid]]\nname = "g"\ncolumns = %d\nrows = %d\n' "$1" "$1" "$2"
  printf 'origin = [0.0, 0.0]\nspacing = [0.1, -0.1]\nbody = { mass = 1.0 }\n'
  printf 'link = { stiffness = 10.0, damping = 0.1 }\n'
}
save_grid() { grid_text "$@" >"$scene.new" && mv "$scene.new" "$scene"; }
loading_re='^loading .*scene\.toml \(at tick [0-9]+\): the window shows the world before the save'
save_by_rename 1 1.0
start_view "$work/slow.out" "$work/slow.err" || { fail "view did not open a window"; finish; }
save_grid "$grid" "$grid"
wait_for "$loading_re" "$work/slow.out" && ok "a save is announced as loading" \
  || { fail "no loading line"; cat "$work/slow.out" "$work/slow.err"; }
wait_for "^reloaded .*: $grid_bodies bodies, .*\\(was [0-9]+\\)\$" "$work/slow.out" \
  && ok "the slow load is shown when ready" || { fail "no reload of the grid"; cat "$work/slow.err"; }
expect "the shown load's warnings are printed" 'world\.mark: unknown key' "$work/slow.err"
from=$(tick_in 'at tick [0-9]+' "$work/slow.out")
to=$(tick_in "$grid_bodies bodies, .*\\(was [0-9]+" "$work/slow.out")
# A load on the window's thread froze the world: it would be at the same tick.
[ -n "$from" ] && [ -n "$to" ] && [ "$to" -gt "$from" ] \
  && ok "the world before the save ran on while the grid loaded (tick $from -> $to)" \
  || fail "the world did not run during the load (ticks '$from' -> '$to')"
quit_view
[ $? -eq 0 ] && ok "view exits 0 after the slow reload" || fail "view exit after the slow reload"

# A newer save while a load runs stops that load: the newer file is what is shown.
save_by_rename 1 1.0
start_view "$work/newer.out" "$work/newer.err" || { fail "view did not open a window"; finish; }
save_grid 1000 1000
wait_for "$loading_re" "$work/newer.out" || fail "no loading line for the large grid"
save_by_rename 2 1.0
wait_for '^reloaded .*: 2 bodies, ' "$work/newer.out" \
  && ok "a save during a load is loaded in its place" || { fail "no reload of the newer save"; cat "$work/newer.out" "$work/newer.err"; }
grep -q '1000000 bodies' "$work/newer.out" && fail "the stale load was shown" \
  || ok "the stale load of 10^6 bodies is not shown"
expect "the stale load was stopped, not run to its end" \
  'scene\.toml was saved again while it loaded: that load was stopped$' "$work/newer.err"
quit_view
[ $? -eq 0 ] && ok "view exits 0 after a dropped load" || fail "view exit after a dropped load"

# Esc while the largest legal grid loads: the window answers and the load is dropped, where a
# load on the window's thread would first finish (and print "reloaded") and only then quit.
save_by_rename 1 1.0
start_view "$work/quit.out" "$work/quit.err" || { fail "view did not open a window"; finish; }
save_grid 1000 1000
wait_for "$loading_re" "$work/quit.out" || fail "no loading line before quitting"
quit_view
[ $? -eq 0 ] && ok "Esc during a load exits 0" || { fail "view exit on Esc during a load"; cat "$work/quit.err"; }
grep -q '^reloaded' "$work/quit.out" && fail "the load was shown before quitting" \
  || ok "Esc during a load: no reload"
expect "Esc during a load stops it, not waiting for its end" \
  'quit while .*scene\.toml loaded: the load was stopped$' "$work/quit.err"
expect "the summary is of the world before the save" '^ticks=[0-9]+ .*state_hash=' "$work/quit.out"

# --- while recording, a save is not reloaded: the recording keeps one world ------------------
save_by_rename 1 1.0
cp "$scene" "$work/recorded.toml"
start_view "$work/rec.out" "$work/rec.err" --record "$work/session.rec" \
  || { fail "view --record did not open a window"; finish; }
save_by_rename 2 1.0
wait_for 'scene\.toml changed: not reloaded while recording \(--record\)' "$work/rec.err" \
  && ok "a save while recording is reported, not reloaded" || { fail "no note while recording"; cat "$work/rec.err"; }
quit_view
[ $? -eq 0 ] && ok "view --record exits 0" || fail "view --record exit"
grep -q '^reloaded' "$work/rec.out" && fail "reloaded while recording" || ok "no reload while recording"
# The recording carries the scene it started with: it replays with the edit still on disk, and
# with the file gone (before format 3 it named the file only, and the edit broke it: exit 6).
cmp -s "$work/recorded.toml" "$scene" && fail "the scene file was not edited"
"$fixstep" replay "$work/session.rec" >"$work/replay.out" 2>&1 \
  && ok "the recording replays after the scene file was edited mid-session" \
  || { fail "replay of the recording after the edit"; cat "$work/replay.out"; }
grep -Eq '^verified [0-9]+ hashes, ticks=[0-9]+ ' "$work/replay.out" \
  && ok "every stored hash verified" || fail "replay output: $(cat "$work/replay.out")"
mv "$scene" "$work/edited.toml"
"$fixstep" replay "$work/session.rec" >"$work/replay_gone.out" 2>&1 \
  && ok "the recording replays with its scene file gone" \
  || { fail "replay of the recording without its file"; cat "$work/replay_gone.out"; }
"$fixstep" replay "$work/session.rec" --scene "$work/recorded.toml" >"$work/replay_at.out" 2>&1 \
  && ok "and against the scene it started with, given explicitly" \
  || { fail "replay of the recording with --scene"; cat "$work/replay_at.out"; }
mv "$work/edited.toml" "$scene"

# --- --no-watch ------------------------------------------------------------------------------
# A negative check can only wait for a time: 1 s is 5 polls of the watch. It cannot fail
# wrongly; a slow machine could only let a reload through unseen.
start_view "$work/nowatch.out" "$work/nowatch.err" --no-watch || { fail "view --no-watch"; finish; }
save_by_rename 3 1.0
sleep 1
quit_view
[ $? -eq 0 ] && ok "view --no-watch exits 0" || fail "view --no-watch exit"
grep -q '^reloaded' "$work/nowatch.out" && fail "--no-watch reloaded" || ok "--no-watch does not reload"

finish
