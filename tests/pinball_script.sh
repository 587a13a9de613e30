#!/usr/bin/env bash
# The pinball played by an input script and by real keys, as a CI job and a player would:
#   - `pinball --frames 1200 --input assets/inputs/pinball_launch.toml` (app::run's --input: the
#     script presses the game's actions by name, the autopilot is off) scores what the script's
#     session scores, recorded, and the recording replays with every hash verified; the same
#     script under --sync-test;
#   - in the window under Xvfb on the real clock, the same script scores the same (the ticks the
#     window reaches differ, the input of each tick does not);
#   - real keys under Xvfb (xdotool): space held pulls the plunger, Z and M raise the flippers,
#     P pauses: the window's recording holds the plunger's and both flippers' actions.
#
#   pinball_script.sh PINBALL SOURCE_DIR OUT_DIR
set -uo pipefail
game=$1
src=$2
out=$3
script=$src/assets/inputs/pinball_launch.toml
expected="score=530 balls=1 bumpers=5 slingshots=3 phase=play"
source "$src/tests/lib.sh"
rm -rf "$out"
mkdir -p "$out"

"$game" --frames 1200 --input "$script" --record "$out/s.rec" >"$out/run.txt" 2>&1
[ $? -eq 0 ] && ok "scripted run exits 0" || { fail "scripted run"; cat "$out/run.txt"; }
grep -qx "$expected" "$out/run.txt" && ok "the script scores: $expected" ||
  { fail "score"; cat "$out/run.txt"; }
grep -q "pressed=8 " "$out/s.rec" && ok "the recording holds the plunger's press" ||
  fail "no plunger press recorded"
"$game" --replay "$out/s.rec" >"$out/replay.txt" 2>&1
[ $? -eq 0 ] && ok "its recording replays, every hash verified" ||
  { fail "replay"; cat "$out/replay.txt"; }
grep -qx "$expected" "$out/replay.txt" && ok "the replay scores the same" || fail "replay score"
"$game" --frames 600 --input "$script" --sync-test 6 >"$out/sync.txt" 2>&1
[ $? -eq 0 ] && ok "sync test with the script" || { fail "sync test"; cat "$out/sync.txt"; }
# A script naming an action the game does not have: refused, located, before anything runs.
printf '[[at]]\ntick = 3\npress = ["plungr"]\n' >"$out/bad.toml"
"$game" --frames 10 --input "$out/bad.toml" >"$out/bad.txt" 2>&1
[ $? -eq 1 ] && ok "an unknown action: exit 1" || fail "an unknown action: not exit 1"
grep -q 'bad.toml:3:10: at\[0\].press\[0\]: unknown action "plungr"; did you mean "plunger"' \
  "$out/bad.txt" && ok "the refusal names the file, line, key and action" ||
  { fail "message"; cat "$out/bad.txt"; }

if have_xvfb && command -v xdotool >/dev/null; then
  with_xvfb "$game" --window --frames 1300 --input "$script" >"$out/window.txt" 2>&1
  [ $? -eq 0 ] && ok "scripted window run exits 0" || { fail "window run"; cat "$out/window.txt"; }
  grep -q "^score=[1-9]" "$out/window.txt" && ok "the window's scripted session scores" ||
    { fail "window score"; cat "$out/window.txt"; }
  window_with_keys "$game" pinball 300 "$out/keys.rec" "$out/keys.txt" '
    xdotool keydown --window "$wid" space; sleep 0.6; xdotool keyup --window "$wid" space
    sleep 0.3
    xdotool keydown --window "$wid" z; sleep 0.3; xdotool keyup --window "$wid" z
    xdotool keydown --window "$wid" m; sleep 0.3; xdotool keyup --window "$wid" m'
  [ $? -eq 0 ] && ok "window with keys exits 0" || { fail "window keys"; cat "$out/keys.txt"; }
  for bit in 8 1 2; do  # plunger (space), left flipper (Z), right flipper (M)
    grep -q " pressed=$bit " "$out/keys.rec" && ok "a key pressed action bit $bit" ||
      fail "no press of action bit $bit in the window's recording"
  done
  "$game" --replay "$out/keys.rec" >/dev/null 2>&1 && ok "the keys' recording replays" ||
    fail "the keys' recording does not replay"
else
  echo "skip: no Xvfb or xdotool"
fi
finish
