#!/usr/bin/env bash
# A match of eight players and two spectators from a game's command line (net::run), for each
# session kind (lockstep, rollback): examples/11_networked_game hosts with --players 8, seven
# bots join and two spectators watch, every one of them through the link conditioner
# (link_relay: latency, jitter, 5 % loss after the first second, duplicates, reordering).
# Checks: all ten exit 0 (no desync, no timeout), every player slot 0-7 taken once and two
# spectator slots, the same final state and score on all ten, byte-identical recordings, and
# the host's recording replays with the rules to the same state, every hash verified.
#
#   net_cli_match.sh GAME LINK_RELAY SOURCE_DIR
set -uo pipefail
game=$1
relay=$2
src=$3
# shellcheck source=tests/lib.sh
. "$src/tests/lib.sh"
cd "$work" || exit 1
ticks=300

# match KIND: the match of eight and two spectators; checks all of the above.
match() {
  local kind=$1 hp rp tok pids=() names=() i status failed=0
  "$game" --host 0 --players 8 --session "$kind" --bot --ticks $ticks \
    --record "$kind.p0.rec" >"$kind.p0.out" 2>&1 &
  pids+=($!) names+=(p0)
  hp=$(wait_for "$kind.p0.out" 'hosting on [0-9.]+:[0-9]+' | grep -Eo '[0-9]+$') ||
    { fail "$kind: the host printed no port"; cat "$kind.p0.out"; return; }
  # The match's token, which the host made and printed: every joiner and spectator gives it.
  tok=$(wait_for "$kind.p0.out" 'token [0-9a-f]{32}' | grep -Eo '[0-9a-f]{32}$') ||
    { fail "$kind: the host printed no token"; cat "$kind.p0.out"; return; }
  "$relay" --upstream "127.0.0.1:$hp" --latency-ms 5 --jitter-ms 3 --loss 0.05 --lossless-ms 1000 --duplicate 0.02 \
    --reorder 0.02 --seed 11 --port-file "$kind.relay.port" --seconds 90 >"$kind.relay.out" 2>&1 &
  local relay_pid=$!
  for _ in $(seq 100); do [ -s "$kind.relay.port" ] && break; sleep 0.05; done
  rp=$(cat "$kind.relay.port")
  for i in 1 2 3 4 5 6 7; do
    "$game" --join "127.0.0.1:$rp" --token "$tok" --session "$kind" --bot --ticks $ticks \
      --record "$kind.p$i.rec" >"$kind.p$i.out" 2>&1 &
    pids+=($!) names+=("p$i")
  done
  for i in 1 2; do
    "$game" --spectate "127.0.0.1:$rp" --token "$tok" --session "$kind" --bot --ticks $ticks \
      --record "$kind.s$i.rec" >"$kind.s$i.out" 2>&1 &
    pids+=($!) names+=("s$i")
  done
  for i in "${!pids[@]}"; do
    wait "${pids[$i]}"
    status=$?
    [ "$status" = 0 ] || { failed=1; echo "${names[$i]} exited $status:"; cat "$kind.${names[$i]}.out"; }
  done
  kill "$relay_pid" 2>/dev/null
  wait "$relay_pid" 2>/dev/null
  [ "$failed" = 0 ] && ok "$kind: eight players and two spectators finished (no desync)" ||
    { fail "$kind: a peer failed"; return; }
  grep -Eq 'dropped=[1-9]' "$kind.relay.out" && ok "$kind: the link dropped datagrams" ||
    { fail "$kind: the link dropped nothing"; cat "$kind.relay.out"; }
  local slots
  slots=$(cat "$kind".*.out | grep -Eo '^match: (player|spectator)=[0-9]+' | cut -d' ' -f2 |
    sort | tr '\n' ' ')
  [ "$slots" = "player=0 player=1 player=2 player=3 player=4 player=5 player=6 player=7 spectator=0 spectator=1 " ] &&
    ok "$kind: slots 0-7 and two spectators" ||
    fail "$kind: slots taken: $slots"
  local hash score same=1
  hash=$(hash_of "$kind.p0.out")
  score=$(grep -E '^red=' "$kind.p0.out")
  for i in "${names[@]}"; do
    [ "$(hash_of "$kind.$i.out")" = "$hash" ] && grep -qx "$score" "$kind.$i.out" &&
      cmp -s "$kind.p0.rec" "$kind.$i.rec" || { same=0; echo "$i differs"; }
  done
  [ -n "$score" ] && [ "$same" = 1 ] &&
    ok "$kind: the same state ($hash), score ($score) and recording on all ten" ||
    fail "$kind: the peers differ"
  "$game" --replay "$kind.p0.rec" >"$kind.replay.out" 2>&1 &&
    grep -qx "verified=$((ticks + 1))" "$kind.replay.out" &&
    [ "$(hash_of "$kind.replay.out")" = "$hash" ] && grep -qx "$score" "$kind.replay.out" &&
    ok "$kind: the recording replays with the rules, every hash verified" ||
    { fail "$kind: the replay"; cat "$kind.replay.out"; }
}

match lockstep
match rollback
finish
