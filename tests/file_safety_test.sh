#!/usr/bin/env bash
# File safety end to end: an output is never an input (by device and inode:
# links included), only regular files are read (a FIFO or device is refused, never waited on),
# a capture directory holds one capture (--overwrite), and stale ".NAME.tmp.PID" files of
# killed runs are removed. Every fixstep call has `timeout 20` as a hang guard only.
#   file_safety_test.sh FIXSTEP SOURCE_DIR
set -u
fixstep=$1 src=$2
. "$(dirname "$0")/lib.sh"
cd "$work" || exit 1
cp "$src/assets/scenes/default.toml" s.toml
cp s.toml s.orig
printf '[[at]]\ntick = 1\npush = [1.0, 0.0]\n' > in.toml
cp in.toml in.orig
fx() { env -u DISPLAY -u WAYLAND_DISPLAY timeout 20 "$fixstep" "$@"; }

intact() {  # intact NAME FILE ORIGINAL
  cmp -s "$2" "$3" && ok "$1: $2 is untouched" || fail "$1: $2 was changed"
}

# --- class 1: outputs that are inputs ---
refused "run --record SCENE" 2 "--record s.toml is the same file as SCENE s.toml" \
  run s.toml --steps 5 --record s.toml
intact "run --record SCENE" s.toml s.orig
refused "run --csv SCENE" 2 "--csv s.toml is the same file as SCENE s.toml" \
  run s.toml --steps 5 --csv s.toml
intact "run --csv SCENE" s.toml s.orig
refused "run --csv ./SCENE (another spelling)" 2 "same file as SCENE" \
  run s.toml --steps 5 --csv "./s.toml"
ln s.toml hard.csv
refused "run --csv a hard link of the scene" 2 "--csv hard.csv is the same file as SCENE s.toml" \
  run s.toml --steps 5 --csv hard.csv
intact "hard link" s.toml s.orig
ln -s s.toml soft.rec
refused "run --record a symlink to the scene" 2 "--record soft.rec is the same file as SCENE" \
  run s.toml --steps 5 --record soft.rec
intact "symlink" s.toml s.orig
[ -L soft.rec ] && ok "the symlink is still a symlink" || fail "soft.rec was replaced"
refused "run --csv the input script" 2 "--csv in.toml is the same file as --input in.toml" \
  run s.toml --steps 5 --input in.toml --csv in.toml
intact "run --csv --input" in.toml in.orig
refused "run --csv and --record one file" 2 "--csv o.out and --record ./o.out are the same file" \
  run s.toml --steps 5 --csv o.out --record ./o.out
[ ! -e o.out ] && ok "nothing written for two outputs in one file" || fail "o.out written"
refused "view --record SCENE (before the window)" 2 "--record s.toml is the same file as SCENE" \
  view s.toml --record s.toml
intact "view --record" s.toml s.orig
refused "compare --csv SCENE" 2 "--csv s.toml is the same file as SCENE s.toml" \
  compare s.toml --with rk4 --with semi_implicit_euler --out cmp --csv s.toml --frames 2
intact "compare --csv" s.toml s.orig
refused "compare --csv DIR/frames.csv" 2 "the same file" \
  compare s.toml --with rk4 --with semi_implicit_euler --out cmp2 --csv cmp2/frames.csv --frames 2
ln -s s.toml clip.mp4
refused "render --video a symlink to the scene" 2 "--video clip.mp4 is the same file as SCENE" \
  render s.toml --video clip.mp4 --frames 2 --size 64x64
intact "render --video" s.toml s.orig
fx run s.toml --steps 5 --record r.rec >/dev/null 2>&1
cp r.rec r.orig
ln r.rec r.mp4
refused "render --replay R --video a hard link of R" 2 "--video r.mp4 is the same file as --replay r.rec" \
  render --replay r.rec --video r.mp4 --frames 2 --size 64x64
intact "render --replay" r.rec r.orig
mkdir -p caught && cp s.toml caught/frames.csv
refused "render a scene named DIR/frames.csv into DIR" 2 "is the same file as SCENE caught/frames.csv" \
  render caught/frames.csv --out caught --frames 2 --size 64x64 --overwrite
intact "scene in --out" caught/frames.csv s.orig

# --- class 3: only regular files are read ---
mkfifo fifo.toml fifo.rec
refused "a FIFO as the scene (no hang)" 1 "fifo.toml: is a FIFO \(named pipe\), not a scene file" \
  run fifo.toml --steps 1
refused "a FIFO as the input script" 1 "is a FIFO \(named pipe\), not an input script" \
  run s.toml --steps 1 --input fifo.toml
refused "a FIFO as the recording" 5 "is a FIFO \(named pipe\), not a recording" replay fifo.rec
refused "a FIFO as replay --scene" 1 "is a FIFO" replay r.rec --scene fifo.toml
refused "/dev/zero as the recording (not read)" 5 "/dev/zero: is a character device, not a recording" \
  replay /dev/zero
refused "/dev/urandom for render --replay" 5 "is a character device, not a recording" \
  render --replay /dev/urandom --out never --frames 1
refused "/dev/null as the scene" 1 "is a character device, not a scene file" run /dev/null --steps 1
refused "compare of a FIFO" 1 "is a FIFO" compare fifo.toml --with rk4 --with semi_implicit_euler --out c3

# --- class 7: one capture per directory ---
fx render s.toml --out d --frames 5 --size 64x64 >/dev/null 2>&1
echo "notes" > d/notes.txt
refused "a second render into a used --out" 2 "--out d already holds a capture \(5 frames, its frames.csv\)" \
  render s.toml --out d --frames 2 --size 64x64
[ "$(ls d | grep -c '^frame_')" -eq 5 ] && ok "the refused run wrote nothing" || fail "d: $(ls d)"
fx render s.toml --out d --frames 2 --size 64x64 --overwrite >out.txt 2>&1
[ "$(ls d | grep -c '^frame_')" -eq 2 ] && [ "$(($(wc -l <d/frames.csv) - 1))" -eq 2 ] \
  && [ -f d/notes.txt ] && ok "--overwrite: 2 frames, 2 rows, no frame of the longer run, notes kept" \
  || { fail "--overwrite left $(ls d)"; cat out.txt; }
fx compare s.toml --with rk4 --with semi_implicit_euler --out c --frames 4 --size 64x64 >/dev/null 2>&1
refused "compare into a used --out" 2 "--out c already holds a capture" \
  compare s.toml --with rk4 --with semi_implicit_euler --out c --frames 2 --size 64x64
fx compare s.toml --with rk4 --with semi_implicit_euler --out c --frames 2 --size 64x64 --overwrite \
  --csv elsewhere.csv >/dev/null 2>&1
[ "$(ls c | tr '\n' ' ')" = "frame_000000.png frame_000001.png frames.csv " ] \
  && ok "compare --overwrite --csv elsewhere: no old compare.csv or frames left" || fail "c: $(ls c)"

# stale temporaries: a dead process's are removed, a live one's and another program's kept
sh -c 'exit 0' & dead=$!
wait $dead
mkdir -p t
touch "t/.frame_000003.png.tmp.$dead" "t/.frames.csv.tmp.$dead" "t/.frames.csv.tmp.$$" \
  "t/.notes.txt.tmp.$dead" ".o.csv.tmp.$dead" ".other.csv.tmp.$dead"
fx render s.toml --out t --frames 1 --size 64x64 >/dev/null 2>&1
fx run s.toml --steps 3 --csv o.csv >/dev/null 2>&1
[ ! -e "t/.frame_000003.png.tmp.$dead" ] && [ ! -e "t/.frames.csv.tmp.$dead" ] && [ ! -e ".o.csv.tmp.$dead" ] \
  && ok "stale temporaries of dead PID $dead removed" || fail "stale left: $(ls -a t) $(ls -a)"
[ -e "t/.frames.csv.tmp.$$" ] && [ -e "t/.notes.txt.tmp.$dead" ] && [ -e ".other.csv.tmp.$dead" ] \
  && ok "a live process's and another file's temporaries kept" || fail "removed too much: $(ls -a t)"

# kill -9 of a PNG render: frames, no frames.csv; the next run says so; --overwrite cleans it
# (fixstep itself in the background, not under `timeout`, so that $! is its PID; the wait for
# its third frame is bounded: 400 looks, 50 ms apart)
"$fixstep" render s.toml --out k --frames 100000 --size 64x64 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 400); do [ -e k/frame_000002.png ] && break; sleep 0.05; done
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
[ -e k/frame_000000.png ] && [ ! -e k/frames.csv ] && ok "kill -9 leaves frames and no frames.csv" \
  || fail "after kill -9: $(ls k | head)"
refused "a killed run's directory" 2 "no frames.csv: an unfinished or killed run" \
  render s.toml --out k --frames 1 --size 64x64
fx render s.toml --out k --frames 1 --size 64x64 --overwrite >/dev/null 2>&1
[ "$(ls -A k | tr '\n' ' ')" = "frame_000000.png frames.csv " ] \
  && ok "--overwrite after kill -9: one frame, its manifest, no temporaries" || fail "k: $(ls -A k)"
finish
