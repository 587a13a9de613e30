#!/usr/bin/env bash
# The pinball demo's recorded session (assets/recordings/pinball.rec: 40 s of its autopilot,
# `pinball --frames 2400 --record FILE`: the flippers in play, two balls lost, 30 bumper
# hits) replayed headless with its rules: every stored state hash verifies (the
# flippers' motor speeds as joint inputs, the bumpers' kicks from contact events), the game is where it was, and
# the last frame is rendered; the sync test passes. Then the same recording through `fixstep
# replay`, which has no pinball rules, must be refused naming the program (exit 5).
#
#   pinball_replay.sh PINBALL FIXSTEP SOURCE_DIR OUT_DIR
set -euo pipefail
game=$1
cli=$2
src=$3
out=$4
rec=$src/assets/recordings/pinball.rec
expected_hash=e34bd12158f74ac8
expected_game="score=3030 balls=1 bumpers=30 slingshots=3 phase=play"
rm -rf "$out"
mkdir -p "$out"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

"$game" --replay "$rec" --last-frame "$out/last.png" >"$out/replay.txt" ||
  fail "replay exited $? ($(cat "$out/replay.txt"))"
cat "$out/replay.txt"
grep -q "state_hash=$expected_hash " "$out/replay.txt" || fail "final state hash is not $expected_hash"
grep -qx "$expected_game" "$out/replay.txt" || fail "game state is not: $expected_game"
stored=$(grep -c '^hash ' "$rec")
grep -qx "verified=$((stored + 1))" "$out/replay.txt" ||
  fail "not every hash verified ($stored stored + the final one)"
grep -q " joint.motor_speed=" "$rec" || fail "the recording holds no flipper input (joint.motor_speed)"
[ "$(head -c 8 "$out/last.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  fail "last.png is not a PNG"

# The sync test: every tick rolled back 8 ticks and stepped again with the rules (the flippers'
# angles and the shape solver's warm-start impulses in the snapshot, the game's state with it).
"$game" --frames 900 --sync-test 8 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "each rolled back 8 ticks and re-simulated" "$out/sync.txt" || fail "no sync test report"

status=0
"$cli" replay "$rec" >/dev/null 2>"$out/cli.err" || status=$?
[ "$status" = 5 ] || fail "fixstep replay of a rules recording exited $status, not 5"
grep -q "recorded by pinball with its game rules" "$out/cli.err" ||
  fail "fixstep replay did not name the program: $(cat "$out/cli.err")"
echo "pinball_replay: ok ($stored hashes + final verified; fixstep replay: $(cat "$out/cli.err"))"
