#!/usr/bin/env bash
# End-to-end checks of video capture from the command line: `render --video` and
# `compare --video` write the file, its manifest beside it with the summary's hashes, and
# refuse what they cannot write. (tests/capture/test_video.cpp decodes the files and checks frames,
# size, rate and PSNR.)
#   video_cli_test.sh FIXSTEP SOURCE_DIR
set -u
fixstep=$1 src=$2
scenes=$src/assets/scenes
. "$(dirname "$0")/lib.sh"

for ext in mp4 gif; do
  "$fixstep" render "$scenes/default.toml" --video "$work/d.$ext" --frames 30 --size 320x180 \
    >"$work/$ext.out" 2>&1
  [ $? -eq 0 ] && [ -s "$work/d.$ext" ] && ok "render --video d.$ext writes it" \
    || { fail "render --video d.$ext"; cat "$work/$ext.out"; }
  m="$work/d.$ext.frames.csv"
  [ -f "$m" ] && [ "$(($(wc -l <"$m") - 1))" -eq 30 ] \
    && [ "$(tail -1 "$m" | cut -d, -f5)" = "$(hash_of "$work/$ext.out")" ] \
    && ok "d.$ext.frames.csv: 30 rows, the last hash the summary's" || fail "manifest of d.$ext"
  grep -q "^video=.*d\.$ext frames=30 fps=60 size=320x180$" "$work/$ext.out" \
    && ok "render says where the $ext is" || { fail "video= line"; cat "$work/$ext.out"; }
done
magic=$(head -c 6 "$work/d.gif")
[ "$magic" = "GIF89a" ] && ok "the .gif is a GIF89a" || fail "gif magic: $magic"
[ "$(head -c 8 "$work/d.mp4" | tail -c 4)" = "ftyp" ] && ok "the .mp4 starts with its ftyp box" \
  || fail "mp4 ftyp"
# PNG frames and a video of the same run at once: one manifest each, equal
"$fixstep" render "$scenes/default.toml" --out "$work/both" --video "$work/both.mp4" --frames 10 \
  --size 64x64 >"$work/both.out" 2>&1
[ -f "$work/both/frame_000009.png" ] && [ -s "$work/both.mp4" ] \
  && cmp -s "$work/both/frames.csv" "$work/both.mp4.frames.csv" \
  && ok "--out and --video together: the frames, the video and equal manifests" \
  || { fail "--out with --video"; cat "$work/both.out"; }
# compare into a video: its manifest and summary beside it
"$fixstep" compare "$scenes/default.toml" --with rk4@1/30 --with semi_implicit_euler \
  --video "$work/c.mp4" --frames 20 --size 320x180 >"$work/c.out" 2>&1
[ $? -eq 0 ] && [ -s "$work/c.mp4" ] && [ "$(($(wc -l <"$work/c.mp4.frames.csv") - 1))" -eq 40 ] \
  && [ "$(wc -l <"$work/c.mp4.compare.csv")" -eq 3 ] \
  && ok "compare --video: the video, 20 x 2 manifest rows and the summary" \
  || { fail "compare --video"; cat "$work/c.out"; ls "$work"; }

bad() {  # bad NAME EXIT PATTERN ARGS...
  local name=$1 code=$2 pattern=$3
  shift 3
  "$fixstep" "$@" >"$work/bad.out" 2>&1
  local got=$?
  [ "$got" -eq "$code" ] && grep -Eq -- "$pattern" "$work/bad.out" && ok "$name: exit $code" \
    || { fail "$name: exit $got"; cat "$work/bad.out"; }
}
bad "a video that is neither .mp4 nor .gif" 2 "must end in \.mp4 \(H\.264\) or \.gif" \
  render "$scenes/default.toml" --video "$work/x.avi"
bad "compare into a .avi" 2 "must end in \.mp4 \(H\.264\) or \.gif" \
  compare "$scenes/default.toml" --with rk4 --with semi_implicit_euler --video "$work/x.avi"
bad "neither --out nor --video" 2 "give --out DIR \(PNG frames\) or --video FILE" \
  render "$scenes/default.toml"
bad "an odd size for H.264 (refused before any work)" 2 "--size 321x180 is odd.*even" \
  render "$scenes/default.toml" --video "$work/odd.mp4" --size 321x180
[ ! -e "$work/odd.mp4" ] && ! ls -a "$work" | grep -q '^\.odd\.mp4\.tmp' \
  && ok "nothing is left of the refused video" || fail "leftovers of odd.mp4: $(ls -a "$work")"
bad "a video in a missing directory" 1 "nodir" render "$scenes/default.toml" --video "$work/nodir/v.mp4"

finish
