#!/usr/bin/env bash
# The cross-architecture match (.ci/cross): two net_peer programs (tests/cross/net_peer.cpp)
# play one scripted two-player lockstep match over loopback, each way round (the first program
# hosting, then the second); the final state hashes they print and the recordings they write
# must be equal, and neither may report a desync.
#   bash tests/cross/net_match.sh "NATIVE_PEER" "EMULATED_PEER" [TICKS]
# e.g. "build/ci/bin/net_peer" "qemu-aarch64 -L / build/aarch64-net/bin/net_peer".
set -euo pipefail
first=$1
second=$2
ticks=${3:-600}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

play() {  # play NAME HOST_COMMAND JOIN_COMMAND
  local name=$1 port=$((20000 + RANDOM % 20000)) token
  token=$(od -An -N16 -tx1 /dev/urandom | tr -d ' \n')  # the match's (docs/NETWORK.md)
  # shellcheck disable=SC2086  # the commands are words (an emulator and its options)
  $2 --host "$port" --token "$token" --ticks "$ticks" --record "$dir/$name.host.rec" >"$dir/$name.host.out" &
  local host=$!
  sleep 1  # an emulated host binds its port a little later
  # shellcheck disable=SC2086
  if ! $3 --join "$port" --token "$token" --ticks "$ticks" --record "$dir/$name.join.rec" >"$dir/$name.join.out"; then
    kill "$host" 2>/dev/null || true
    echo "net_match: $name: the joiner failed" >&2
    exit 1
  fi
  wait "$host" || { echo "net_match: $name: the host failed" >&2; exit 1; }
  local h j
  h=$(sed -n 's/.*state hash \([0-9a-f]*\).*/\1/p' "$dir/$name.host.out")
  j=$(sed -n 's/.*state hash \([0-9a-f]*\).*/\1/p' "$dir/$name.join.out")
  cat "$dir/$name.host.out" "$dir/$name.join.out"
  if [ -z "$h" ] || [ "$h" != "$j" ]; then
    echo "net_match: $name: the state hashes differ (host $h, joiner $j)" >&2
    exit 1
  fi
  cmp "$dir/$name.host.rec" "$dir/$name.join.rec" ||
    { echo "net_match: $name: the recordings differ" >&2; exit 1; }
  echo "net_match: $name: $ticks ticks, equal state hashes ($h) and recordings"
}

play first-hosts "$first" "$second"
play second-hosts "$second" "$first"
