#!/usr/bin/env bash
# Networked air hockey as a player feels it: two bots paced at 60 frames a second (--paced: the
# game's clock, as the window), 120 ticks a second, through the link conditioner (link_relay):
#  (a) a perfect link, lockstep and rollback: the game runs at real time (1200 ticks of 1/120 s
#      in 10 s, within 5 %: the game's ticks over the real time from its first tick to its
#      last, which each peer prints);
#  (b) rollback at 50 ms each way and 2 % loss, 30 s: no freeze over 100 ms (a freeze: frames in
#      a row that played no tick owed; time sync never waits two in a row, so one lasts a
#      frame or two: the margin is in its length);
#  (c) rollback at 75 ± 5 ms each way and 5 % loss, 30 s: no freeze over 250 ms;
#  (d) lockstep at 1 s each way and 25 % loss from the first datagram (the handshake too), 600
#      ticks: it connects (at the default timeouts: 10 s, then 8 round trips once the cookie
#      exchange has measured one), completes, both exit 0 and both recordings are equal.
# Every match: both peers exit 0 with the same final state.
#
#   net_latency.sh AIRHOCKEY LINK_RELAY SOURCE_DIR
set -uo pipefail
game=$1
relay=$2
src=$3
# shellcheck source=tests/lib.sh
. "$src/tests/lib.sh"
cd "$work" || exit 1

wait_port() { wait_for "$1" 'hosting on [0-9.]+:[0-9]+' | grep -Eo '[0-9]+$'; }
wait_token() { wait_for "$1" 'token [0-9a-f]{32}' | grep -Eo '[0-9a-f]{32}$'; }
# field FILE NAME: the number after "NAME=" on the frames: line.
field() { grep -E '^frames:' "$1" | grep -Eo "$2=[0-9.]+" | head -1 | cut -d= -f2; }

# play NAME KIND TICKS RELAY-FLAGS... : a paced bot match through the relay; 0 when both exit 0
# with the same final state.
play() {
  local name=$1 kind=$2 ticks=$3 hp tok rp host_pid relay_pid hs js
  shift 3
  "$game" --host 0 --session "$kind" --bot --paced --ticks "$ticks" \
    --record "$name.host.rec" >"$name.host.out" 2>&1 &
  host_pid=$!
  # (a host that never printed its port or token is stopped, not left to wait for a joiner)
  hp=$(wait_port "$name.host.out") ||
    { kill "$host_pid" 2>/dev/null; fail "$name: no port"; cat "$name.host.out"; return 1; }
  tok=$(wait_token "$name.host.out") ||
    { kill "$host_pid" 2>/dev/null; fail "$name: no token"; return 1; }
  "$relay" --upstream "127.0.0.1:$hp" "$@" --port-file "$name.relay.port" --seconds 120 \
    >"$name.relay.out" 2>&1 &
  relay_pid=$!
  for _ in $(seq 100); do [ -s "$name.relay.port" ] && break; sleep 0.05; done
  rp=$(cat "$name.relay.port" 2>/dev/null)
  if [ -z "$rp" ]; then  # the host would wait for its joiner until ctest's timeout
    kill "$host_pid" "$relay_pid" 2>/dev/null
    fail "$name: the relay gave no port"
    cat "$name.relay.out"
    return 1
  fi
  "$game" --join "127.0.0.1:$rp" --token "$tok" --session "$kind" --bot --paced --ticks "$ticks" \
    --record "$name.join.rec" >"$name.join.out" 2>&1
  js=$?
  [ "$js" = 0 ] || kill "$host_pid" 2>/dev/null  # a host whose joiner failed would wait on
  wait "$host_pid"
  hs=$?
  kill "$relay_pid" 2>/dev/null
  wait "$relay_pid" 2>/dev/null
  if [ "$hs" != 0 ] || [ "$js" != 0 ]; then
    fail "$name: host exited $hs, joiner $js"
    cat "$name.host.out" "$name.join.out"
    return 1
  fi
  [ "$(hash_of "$name.host.out")" = "$(hash_of "$name.join.out")" ] ||
    { fail "$name: the final states differ"; return 1; }
  ok "$name: both finished, the same state; $(grep -h '^frames:' "$name.host.out" "$name.join.out" | tr '\n' ' ')"
}

# (a) real time on a perfect link
# perfect KIND: a lockstep or rollback match on a perfect link runs at real time.
perfect() {
  local kind=$1 side secs
  play "perfect-$kind" "$kind" 1200 --latency-ms 0 || return
  for side in host join; do
    secs=$(field "perfect-$kind.$side.out" played)
    awk -v p="$secs" 'BEGIN { r = 1200 / 120 / p; exit !(r > 0.95 && r < 1.05) }' &&
      ok "perfect-$kind $side: 1200 ticks in ${secs} s of real time" ||
      fail "perfect-$kind $side: 1200 ticks took ${secs} s, not 10 s"
  done
}
perfect_lockstep() { perfect lockstep; }
perfect_rollback() { perfect rollback; }

# (b), (c) freezes under latency and loss, rollback
check_freezes() {
  local name=$1 key=$2 most=$3 side n
  for side in host join; do
    n=$(field "$name.$side.out" "$key")
    [ -n "$n" ] && [ "$n" -le "$most" ] && ok "$name $side: $n freezes $key" ||
      fail "$name $side: $n freezes $key (at most $most)"
  done
}
rtt100() {
  play rtt100 rollback 3600 --latency-ms 50 --loss 0.02 --lossless-ms 1000 --seed 3 &&
    check_freezes rtt100 "over 100 ms" 0
}
rtt150() {
  play rtt150 rollback 3600 --latency-ms 75 --jitter-ms 5 --loss 0.05 --lossless-ms 1000 \
    --seed 5 && check_freezes rtt150 "over 250 ms" 0
}
# (d) lockstep at 2 s round trip and 25 % loss, the handshake included
rtt2000() {
  play rtt2000 lockstep 600 --latency-ms 1000 --loss 0.25 --seed 11 &&
    { cmp -s rtt2000.host.rec rtt2000.join.rec && ok "rtt2000: the recordings are equal" ||
      fail "rtt2000: the recordings differ"; }
}

# The five matches side by side, each with its own ports and files. A match spends most of its
# time waiting for its next frame, so together they take about the longest one's 30 s rather
# than the sum's 100 s, and each plays beside the others as a game beside other programs does.
# Each match's lines are printed when it ends, in this order, and counted here.
matches=(perfect_lockstep perfect_rollback rtt100 rtt150 rtt2000)
declare -A pids
for m in "${matches[@]}"; do
  ( "$m"; [ "$failures" -eq 0 ] ) >"$m.log" 2>&1 &
  pids[$m]=$!
done
for m in "${matches[@]}"; do
  wait "${pids[$m]}"
  status=$?
  cat "$m.log"
  passes=$((passes + $(grep -c '^ok - ' "$m.log")))
  failures=$((failures + $(grep -c '^FAIL - ' "$m.log")))
  [ "$status" -eq 0 ] || grep -q '^FAIL - ' "$m.log" || fail "$m: exited $status"
done

finish
