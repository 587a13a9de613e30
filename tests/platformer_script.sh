#!/usr/bin/env bash
# The platformer played by an input script, as a CI job and a player would: walk with the walk
# axis, jump through the one-way platforms from below and land on them, push the crate, ride
# the moving platform, collect the coins (assets/inputs/platformer_run.toml):
#   - headless: the script collects the coins it is written to collect; recorded, the recording
#     replays with every hash verified; the sync test passes with the script;
#   - in the window under Xvfb on the real clock: the same script collects the same coins;
#   - real keys under Xvfb (xdotool): D walks right, space jumps (the recording holds the walk
#     axis and the jump action).
#
#   platformer_script.sh PLATFORMER SOURCE_DIR OUT_DIR
set -uo pipefail
game=$1
src=$2
out=$3
script=$src/assets/inputs/platformer_run.toml
source "$src/tests/lib.sh"
rm -rf "$out"
mkdir -p "$out"
expected=$(grep -m1 '^# expect: ' "$script" | sed 's/^# expect: //')
frames=$(grep -m1 '^# frames: ' "$script" | sed 's/^# frames: //')

"$game" --frames "$frames" --input "$script" --record "$out/s.rec" \
  --last-frame "$out/last.png" >"$out/run.txt" 2>&1
[ $? -eq 0 ] && ok "scripted run exits 0" || { fail "scripted run"; cat "$out/run.txt"; }
grep -q "^$expected" "$out/run.txt" && ok "the script collects: $expected" ||
  { fail "coins"; cat "$out/run.txt"; }
grep -q " axis.0=1" "$out/s.rec" && ok "the recording holds the walk axis" || fail "no walk axis"
"$game" --replay "$out/s.rec" >"$out/replay.txt" 2>&1
[ $? -eq 0 ] && ok "its recording replays, every hash verified" ||
  { fail "replay"; cat "$out/replay.txt"; }
grep -q "^$expected" "$out/replay.txt" && ok "the replay collects the same" || fail "replay coins"
"$game" --frames "$frames" --input "$script" --sync-test 6 >"$out/sync.txt" 2>&1
[ $? -eq 0 ] && ok "sync test with the script" || { fail "sync test"; cat "$out/sync.txt"; }

if have_xvfb && command -v xdotool >/dev/null; then
  with_xvfb "$game" --window --frames "$((frames + 60))" --input "$script" >"$out/window.txt" 2>&1
  [ $? -eq 0 ] && ok "scripted window run exits 0" || { fail "window run"; cat "$out/window.txt"; }
  grep -q "^$expected" "$out/window.txt" && ok "the window's scripted run collects the same" ||
    { fail "window coins"; cat "$out/window.txt"; }
  window_with_keys "$game" platformer 240 "$out/keys.rec" "$out/keys.txt" '
    xdotool keydown --window "$wid" d; sleep 0.8
    xdotool keydown --window "$wid" space; sleep 0.2; xdotool keyup --window "$wid" space
    sleep 0.5; xdotool keyup --window "$wid" d'
  [ $? -eq 0 ] && ok "window with keys exits 0" || { fail "window keys"; cat "$out/keys.txt"; }
  grep -q " axis.0=1" "$out/keys.rec" && ok "D walked right (the walk axis at 1)" ||
    fail "no walk axis from D in the window's recording"
  grep -q " pressed=1 " "$out/keys.rec" && ok "space pressed jump" || fail "no jump from space"
  grep -q "jumps=[1-9]" "$out/keys.txt" && ok "the player jumped" || { fail "no jump"; cat "$out/keys.txt"; }
  "$game" --replay "$out/keys.rec" >/dev/null 2>&1 && ok "the keys' recording replays" ||
    fail "the keys' recording does not replay"
else
  echo "skip: no Xvfb or xdotool"
fi
finish
