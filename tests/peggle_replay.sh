#!/usr/bin/env bash
# The peggle demo's recorded session (assets/recordings/peggle.rec: 40 s of its autopilot,
# `peggle --frames 2400 --record FILE`) replayed headless with its rules: every stored state
# hash verifies, the game ends where it did (a ball caught by the bucket's sensor, pegs lit by
# contacts and cleared), and the last frame is rendered; the sync test passes. Then the same recording through
# `fixstep replay`, which has no peggle rules, must be refused naming the program (exit 5).
#
#   peggle_replay.sh PEGGLE FIXSTEP SOURCE_DIR OUT_DIR
set -euo pipefail
source "$(dirname "$0")/game_replay.sh"
game=$1
cli=$2
src=$3
out=$4
rec=$src/assets/recordings/peggle.rec
expected_hash=ce2e1ae11a91643e
expected_game="score=880 balls=3 caught=1 pegs=19 phase=flying"
fresh_out "$out"

replay_verified "$game" "$rec" "$out" "$expected_hash" "$expected_game"

# The sync test: every tick rolled back 8 ticks and stepped again with the rules (sensor and
# contact events, the world's random generator and the game's state all in the snapshot).
"$game" --frames 900 --sync-test 8 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "each rolled back 8 ticks and re-simulated" "$out/sync.txt" || fail "no sync test report"

refused_by_fixstep "$cli" "$rec" "$out" peggle
echo "peggle_replay: ok ($stored hashes + final verified; fixstep replay: $(cat "$out/cli.err"))"
