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
source "$(dirname "$0")/game_replay.sh"
game=$1
src=$2
out=$3
rec=$src/assets/recordings/slingshot.rec
expected_hash=b7cab41f8a0a3b87
expected_game="score=2 shots_left=0 knocked=1001 phase=over"
fresh_out "$out"

replay_verified "$game" "$rec" "$out" "$expected_hash" "$expected_game"
is_png "$out/last.png" 1280x720  # the last frame

# The checker checks: a copy with one input line taken out (tampered_diverges).
tampered_diverges "$game" "$rec" "$out" --out "$out/tampered_frames" --last-frame "$out/tampered.png"
# A diverging recording is not drawn: no frame, no last frame, not even the directory.
[ ! -e "$out/tampered_frames" ] && [ ! -e "$out/tampered.png" ] ||
  fail "frames of a diverging recording were written: $(ls "$out")"
grep -q "no frame was written" "$out/tampered.err" || fail "the error does not say what was written"
echo "slingshot_replay: ok ($stored hashes + final verified; tampered copy: $(cat "$out/tampered.err"))"
