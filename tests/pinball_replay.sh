#!/usr/bin/env bash
# The pinball demo's recorded session (assets/recordings/pinball.rec: 40 s of its autopilot,
# `pinball --frames 2400 --record FILE`: the flippers in play, 6 bumper hits, all three balls
# lost and the game over) replayed headless with its rules: every stored state hash verifies (the
# flippers' motor speeds as joint inputs, the bumpers' kicks from contact events), the game is where it was, and
# the last frame is rendered; the sync test passes. Then the same recording through `fixstep
# replay`, which has no pinball rules, must be refused naming the program (exit 5).
#
#   pinball_replay.sh PINBALL FIXSTEP SOURCE_DIR OUT_DIR
set -euo pipefail
source "$(dirname "$0")/game_replay.sh"
game=$1
cli=$2
src=$3
out=$4
rec=$src/assets/recordings/pinball.rec
expected_hash=fd7f15705767c2fe
expected_game="score=630 balls=0 bumpers=6 slingshots=3 phase=over"
fresh_out "$out"

replay_verified "$game" "$rec" "$out" "$expected_hash" "$expected_game"
grep -q " joint.motor_speed=" "$rec" || fail "the recording holds no flipper input (joint.motor_speed)"

# The sync test: every tick rolled back 8 ticks and stepped again with the rules (the flippers'
# angles and the shape solver's warm-start impulses in the snapshot, the game's state with it).
"$game" --frames 900 --sync-test 8 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "each rolled back 8 ticks and re-simulated" "$out/sync.txt" || fail "no sync test report"

refused_by_fixstep "$cli" "$rec" "$out" pinball
echo "pinball_replay: ok ($stored hashes + final verified; fixstep replay: $(cat "$out/cli.err"))"
