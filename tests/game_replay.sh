#!/usr/bin/env bash
# What the demos' replay tests share (sourced by peggle_replay.sh, pinball_replay.sh,
# slingshot_replay.sh and stacker_replay.sh): a fresh output folder, the recorded session replayed
# by its program with every stored state hash and the final one verified, a PNG's signature and
# size, a copy with one input line taken out that must be reported as diverging, and `fixstep
# replay` refusing a recording made with a program's own rules.

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# fresh_out OUT: OUT made anew, empty.
fresh_out() {
  rm -rf "$1"
  mkdir -p "$1"
}

# is_png FILE [1280x720]: FILE has a PNG's signature (and, when asked, is 1280x720).
is_png() {
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    fail "$(basename "$1") is not a PNG"
  if [ "${2:-}" = 1280x720 ]; then
    [ "$(od -An -tu1 -j16 -N8 "$1" | tr -s ' ')" = " 0 0 5 0 0 0 2 208" ] ||
      fail "$(basename "$1") is not 1280x720"
  fi
}

# replay_verified GAME REC OUT HASH STATE: `GAME --replay REC` (its last frame drawn into
# OUT/last.png, its report into OUT/replay.txt, which is printed) verified every stored hash and
# the final one, ends in state hash HASH with the game's line STATE, and drew a PNG. Sets
# `stored`, the number of hashes REC stores.
replay_verified() {
  local game=$1 rec=$2 out=$3 hash=$4 state=$5
  "$game" --replay "$rec" --last-frame "$out/last.png" >"$out/replay.txt" ||
    fail "replay exited $? ($(cat "$out/replay.txt"))"
  cat "$out/replay.txt"
  grep -q "state_hash=$hash " "$out/replay.txt" || fail "final state hash is not $hash"
  grep -qx "$state" "$out/replay.txt" || fail "game state is not: $state"
  stored=$(grep -c '^hash ' "$rec")
  grep -qx "verified=$((stored + 1))" "$out/replay.txt" ||
    fail "not every hash verified ($stored stored + the final one)"
  is_png "$out/last.png"
}

# tampered_diverges GAME REC OUT [ARG...]: REC without the input of tick N (0-based; the fifth
# line of its first drag) into OUT/tampered.rec, replayed by GAME with ARG... (where it would
# draw): tick N keeps the previous pointer, so the state after N + 1 ticks is the first that
# differs, and the replay must exit 4 naming exactly that tick and both hashes (its message in
# OUT/tampered.err).
tampered_diverges() {
  local game=$1 rec=$2 out=$3
  shift 3
  local line tick status=0
  line=$(grep -n ' drag=1:1$' "$rec" | sed -n 5p | cut -d: -f1)
  tick=$(sed -n "${line}p" "$rec" | cut -d' ' -f2)
  sed "${line}d" "$rec" >"$out/tampered.rec"
  "$game" --replay "$out/tampered.rec" "$@" >/dev/null 2>"$out/tampered.err" || status=$?
  [ "$status" = 4 ] || fail "a tampered recording exited $status, not 4"
  grep -Eq "tampered\.rec diverged at tick $((tick + 1)): state_hash [0-9a-f]{16} recorded, [0-9a-f]{16} replayed \(the states matched at tick $tick\)" \
    "$out/tampered.err" ||
    fail "not diverged at tick $((tick + 1)) with both hashes: $(cat "$out/tampered.err")"
}

# refused_by_fixstep FIXSTEP REC OUT PROGRAM: `fixstep replay REC`, which has none of PROGRAM's
# rules, refuses the recording with exit 5, naming PROGRAM (its message in OUT/cli.err).
refused_by_fixstep() {
  local cli=$1 rec=$2 out=$3 program=$4 status=0
  "$cli" replay "$rec" >/dev/null 2>"$out/cli.err" || status=$?
  [ "$status" = 5 ] || fail "fixstep replay of a rules recording exited $status, not 5"
  grep -q "recorded by $program with its game rules" "$out/cli.err" ||
    fail "fixstep replay did not name the program: $(cat "$out/cli.err")"
}
