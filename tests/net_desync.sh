#!/usr/bin/env bash
# A desync from the command line, located on both peers (tests/net/desync_game.cpp: its rules
# nudge the puck's vx by 1e-9 m/s after tick 95 on the peer started with DESYNC_GAME_NUDGE):
# a lockstep match of 300 ticks (a hash every 60) on loopback. Both peers exit 4 naming tick 96
# (the first whose states differ, not the hash tick 120), body 1 ("puck") and vx; each writes
# its recording and its state of tick 96 (desync_game-desync-pSLOT-t96.rec and .state) in its
# working directory; the two state files differ in the puck's line only; and `fixstep diff`
# and the game's --diff name tick 96 from the two recordings and the puck's vx from the state
# files beside them (a state file that is not one is named with its line).
#
#   net_desync.sh DESYNC_GAME FIXSTEP SOURCE_DIR
set -uo pipefail
game=$1
fixstep=$2
src=$3
# shellcheck source=tests/lib.sh
. "$src/tests/lib.sh"
cd "$work" || exit 1
mkdir host join

(cd host && "$game" --host 0 --bot --ticks 300 >out 2>err) &
host_pid=$!
port=$(wait_for host/out 'hosting on [0-9.]+:[0-9]+' | grep -Eo '[0-9]+$')
token=$(wait_for host/out 'token [0-9a-f]{32}' | grep -Eo '[0-9a-f]{32}$')
(cd join && DESYNC_GAME_NUDGE=1 "$game" --join "127.0.0.1:$port" --token "$token" --bot \
  --ticks 300 >out 2>err)
join_status=$?
wait "$host_pid"
host_status=$?
[ "$host_status" = 4 ] && [ "$join_status" = 4 ] && ok "both peers exit 4 (a desync)" ||
  { fail "host exited $host_status, joiner $join_status"; cat host/err join/err; }
for side in host join; do
  grep -q 'desync at tick 96 (the first tick whose states differ; tick 95 matched)' "$side/err" &&
    grep -q 'body 1 ("puck") vx' "$side/err" &&
    ok "$side: names tick 96, the puck and vx" || { fail "$side: the report"; cat "$side/err"; }
done
slot_of() { [ "$1" = host ] && echo 0 || echo 1; }
for side in host join; do
  s=$(slot_of "$side")
  [ -f "$side/desync_game-desync-p$s-t96.rec" ] && [ -f "$side/desync_game-desync-p$s-t96.state" ] &&
    ok "$side: its recording and its state of tick 96 are written" ||
    { fail "$side: files: $(ls "$side")"; }
done
# The state files: the same bodies, only the puck's line differs.
diff <(grep '^body' host/desync_game-desync-p0-t96.state) \
  <(grep '^body' join/desync_game-desync-p1-t96.state) >states.diff
differing=$(grep -c '^<' states.diff)
[ "$differing" = 1 ] && grep -q '^< body 1 "puck"' states.diff &&
  ok "the state files differ in the puck's line alone" ||
  fail "the state files differ in $differing lines"
# Offline, from the two recordings: the stored hashes first differ at tick 96; replayed here
# without the environment both step alike, so the joiner's peer diverged (not its inputs).
# The peers' state files beside the recordings name the puck.
"$game" --diff host/desync_game-desync-p0-t96.rec join/desync_game-desync-p1-t96.rec >diff.out 2>&1
[ $? = 4 ] && grep -q 'stored hashes: first differ at tick 96 (exact' diff.out &&
  grep -q 'first differ at body 1 ("puck") vx: 1 against 1.000000001 m/s' diff.out &&
  ok "the game's --diff names tick 96, the puck and vx" || { fail "--diff"; cat diff.out; }
"$fixstep" diff host/desync_game-desync-p0-t96.rec join/desync_game-desync-p1-t96.rec >fdiff.out 2>&1
[ $? = 4 ] && grep -q 'stored hashes: first differ at tick 96 (exact' fdiff.out &&
  grep -q 'first differ at body 1 ("puck") vx' fdiff.out &&
  ok "fixstep diff names tick 96, the puck and vx" || { fail "fixstep diff"; cat fdiff.out; }
# A state file that is not one: named, with its line; the recordings' verdict stands (exit 4).
cp host/desync_game-desync-p0-t96.rec bad.rec
sed 's/^body 1 "puck" \([^ ]*\)/body 1 "puck" nope/' host/desync_game-desync-p0-t96.state >bad.state
"$fixstep" diff bad.rec join/desync_game-desync-p1-t96.rec >bad.out 2>&1
[ $? = 4 ] && grep -q 'were not compared: bad.state:6: body 1: x is not a number' bad.out &&
  ok "a bad state file is named with its line" || { fail "a bad state file"; cat bad.out; }

finish
