#!/usr/bin/env bash
# The stacker game's recorded session (assets/recordings/stacker.rec: `stacker --frames 1300
# --record`, the autopilot's three shots, demos/stacker/stacker_app.hpp) replayed headless:
# every stored state hash verifies, the final state and the score are the ones below, and the
# last frame is rendered; the autopilot's run under --sync-test 4 ends the same. Then a copy
# with one input line taken out (in the first drag) must be reported as diverging at the tick
# after it, with nothing drawn.
#
#   stacker_replay.sh STACKER SOURCE_DIR OUT_DIR
set -euo pipefail
source "$(dirname "$0")/game_replay.sh"
game=$1
src=$2
out=$3
rec=$src/assets/recordings/stacker.rec
expected_hash=1b2ded91ca809a2f
expected_game="score=12 targets=2 shots_left=0 down=11111000001111111 phase=over"
fresh_out "$out"

replay_verified "$game" "$rec" "$out" "$expected_hash" "$expected_game"
is_png "$out/last.png" 1280x720  # the last frame

# The autopilot's run under the sync test (every tick rolled back 4 ticks and re-simulated with
# the rules) plays the recorded game: the same final state and score. (The autopilot and the
# drag keep no state outside the rules', which the rollback restores.)
"$game" --frames 1300 --sync-test 4 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "state_hash=$expected_hash " "$out/sync.txt" || fail "sync test run: not $expected_hash"
grep -qx "$expected_game" "$out/sync.txt" || fail "sync test run: game state is not: $expected_game"

# A copy with one input line taken out (tampered_diverges) must diverge.
tampered_diverges "$game" "$rec" "$out" --last-frame "$out/tampered.png"
[ ! -e "$out/tampered.png" ] || fail "a diverging recording was drawn"
echo "stacker_replay: ok ($stored hashes + final verified; tampered copy: $(cat "$out/tampered.err"))"
