#!/usr/bin/env bash
# The slingshot game's recorded session (assets/recordings/slingshot.rec, played with a real
# mouse: demos/slingshot/record_session.sh) replayed headless: every stored state hash
# verifies, the final state and the score are the ones below, and the last frame is rendered.
# The score comes only from the engine's disc-disc impacts (World::impacts()): the session knocks
# two targets off (0 and 3). (Recorded again when the slingshot's post stopped being three static
# bodies and became the game's drawing: the world, and so every state hash, changed.)
# Then a copy with one input line taken out must be reported as diverging, with nothing drawn.
#
#   slingshot_replay.sh SLINGSHOT SOURCE_DIR OUT_DIR
set -euo pipefail
game=$1
src=$2
out=$3
rec=$src/assets/recordings/slingshot.rec
expected_hash=b7cab41f8a0a3b87
expected_game="score=2 shots_left=0 knocked=1001 phase=over"
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

# The checker checks: drop one input line in the middle of the first drag (the input of tick
# N, 0-based): tick N keeps the previous pointer, so the state after N + 1 ticks is the first
# that differs, and the replay must name exactly that.
line=$(grep -n ' drag=1:1$' "$rec" | sed -n 5p | cut -d: -f1)
tick=$(sed -n "${line}p" "$rec" | cut -d' ' -f2)
sed "${line}d" "$rec" >"$out/tampered.rec"
status=0
"$game" --replay "$out/tampered.rec" --out "$out/tampered_frames" --last-frame "$out/tampered.png" \
  >/dev/null 2>"$out/tampered.err" || status=$?
[ "$status" = 4 ] || fail "a tampered recording exited $status, not 4"
grep -Eq "tampered\.rec diverged at tick $((tick + 1)): state_hash [0-9a-f]{16} recorded, [0-9a-f]{16} replayed \(the states matched at tick $tick\)" \
  "$out/tampered.err" || fail "not diverged at tick $((tick + 1)) with both hashes: $(cat "$out/tampered.err")"
# A diverging recording is not drawn: no frame, no last frame, not even the directory.
[ ! -e "$out/tampered_frames" ] && [ ! -e "$out/tampered.png" ] ||
  fail "frames of a diverging recording were written: $(ls "$out")"
grep -q "no frame was written" "$out/tampered.err" || fail "the error does not say what was written"
echo "slingshot_replay: ok ($stored hashes + final verified; tampered copy: $(cat "$out/tampered.err"))"
