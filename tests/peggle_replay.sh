#!/usr/bin/env bash
# The peggle demo's recorded session (assets/recordings/peggle.rec: 40 s of its autopilot,
# `peggle --frames 2400 --record FILE`) replayed headless with its rules: every stored state
# hash verifies, the game ends where it did (a ball caught by the bucket's sensor, pegs lit by
# contacts and cleared), and the last frame is rendered; the sync test passes. Then the same recording through
# `fixstep replay`, which has no peggle rules, must be refused naming the program (exit 5).
#
#   peggle_replay.sh PEGGLE FIXSTEP SOURCE_DIR OUT_DIR
set -euo pipefail
game=$1
cli=$2
src=$3
out=$4
rec=$src/assets/recordings/peggle.rec
expected_hash=ce2e1ae11a91643e
expected_game="score=880 balls=3 caught=1 pegs=19 phase=flying"
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
[ "$(head -c 8 "$out/last.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  fail "last.png is not a PNG"

# The sync test: every tick rolled back 8 ticks and stepped again with the rules (sensor and
# contact events, the world's random generator and the game's state all in the snapshot).
"$game" --frames 900 --sync-test 8 >"$out/sync.txt" || fail "sync test exited $? ($(cat "$out/sync.txt"))"
grep -q "each rolled back 8 ticks and re-simulated" "$out/sync.txt" || fail "no sync test report"

status=0
"$cli" replay "$rec" >/dev/null 2>"$out/cli.err" || status=$?
[ "$status" = 5 ] || fail "fixstep replay of a rules recording exited $status, not 5"
grep -q "recorded by peggle with its game rules" "$out/cli.err" ||
  fail "fixstep replay did not name the program: $(cat "$out/cli.err")"
echo "peggle_replay: ok ($stored hashes + final verified; fixstep replay: $(cat "$out/cli.err"))"
