#!/usr/bin/env bash
# The joint demos (assets/scenes/car.toml, ragdoll.toml) and their recordings
# (assets/recordings/car.rec, ragdoll.rec: `fixstep run SCENE --duration 10 --record FILE
# --hash-every 60`): each replays with every stored hash verified and the final state hash it
# was recorded with, its last frame renders as a PNG, and its sync test (8 ticks rolled back
# and stepped again, every tick) finds no difference.
#
#   joint_scenes_replay.sh FIXSTEP SOURCE_DIR OUT_DIR
set -euo pipefail
cli=$1
src=$2
out=$3
rm -rf "$out"
mkdir -p "$out"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
declare -A final=([car]=e0843dd27ebaa435 [ragdoll]=1b0e6f137eb01722)
for name in car ragdoll; do
  rec=$src/assets/recordings/$name.rec
  "$cli" replay "$rec" >"$out/$name.txt" 2>&1 || fail "$name: replay exited $? ($(cat "$out/$name.txt"))"
  grep -q "verified 21 hashes, ticks=1200 state_hash=${final[$name]}" "$out/$name.txt" ||
    fail "$name: not every hash verified, or the final state is not ${final[$name]}: $(cat "$out/$name.txt")"
  "$cli" render --replay "$rec" --out "$out/$name" --frames 11 --fps 1 >"$out/$name-render.txt" 2>&1 ||
    fail "$name: render exited $? ($(cat "$out/$name-render.txt"))"
  png=$(ls "$out/$name"/*.png | tail -1)
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$name: $png is not a PNG"
  "$cli" run "$src/assets/scenes/$name.toml" --steps 600 --sync-test 8 >"$out/$name-sync.txt" 2>&1 ||
    fail "$name: sync test exited $? ($(cat "$out/$name-sync.txt"))"
  echo "ok - $name: replayed (21 hashes, ${final[$name]}), last frame rendered, sync test passed"
done
