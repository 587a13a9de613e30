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
game=$1
src=$2
out=$3
rec=$src/assets/recordings/stacker.rec
expected_hash=665a5478405fde13
expected_game="score=8 targets=2 shots_left=0 down=11111001110000000 phase=over"
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
# The last frame: a 1280x720 PNG.
[ "$(head -c 8 "$out/last.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  fail "last.png is not a PNG"
[ "$(od -An -tu1 -j16 -N8 "$out/last.png" | tr -s ' ')" = " 0 0 5 0 0 0 2 208" ] ||
  fail "last.png is not 1280x720"

# The autopilot's run under the sync test (every tick rolled back 4 ticks and re-simulated with
# the rules) plays the recorded game: the same final state and score. (The autopilot and the
# drag keep no state outside the rules', which the rollback restores.)
"$game" --frames 1300 --sync-test 4 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "state_hash=$expected_hash " "$out/sync.txt" || fail "sync test run: not $expected_hash"
grep -qx "$expected_game" "$out/sync.txt" || fail "sync test run: game state is not: $expected_game"

# Drop the input of tick N (0-based) in the middle of the first drag: tick N keeps the previous
# pointer, so the state after N + 1 ticks is the first that differs.
line=$(grep -n ' drag=1:1$' "$rec" | sed -n 5p | cut -d: -f1)
tick=$(sed -n "${line}p" "$rec" | cut -d' ' -f2)
sed "${line}d" "$rec" >"$out/tampered.rec"
status=0
"$game" --replay "$out/tampered.rec" --last-frame "$out/tampered.png" \
  >/dev/null 2>"$out/tampered.err" || status=$?
[ "$status" = 4 ] || fail "a tampered recording exited $status, not 4"
grep -Eq "tampered\.rec diverged at tick $((tick + 1)): state_hash [0-9a-f]{16} recorded, [0-9a-f]{16} replayed \(the states matched at tick $tick\)" \
  "$out/tampered.err" || fail "not diverged at tick $((tick + 1)) with both hashes: $(cat "$out/tampered.err")"
[ ! -e "$out/tampered.png" ] || fail "a diverging recording was drawn"
echo "stacker_replay: ok ($stored hashes + final verified; tampered copy: $(cat "$out/tampered.err"))"
