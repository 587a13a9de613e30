#!/usr/bin/env bash
# What each kind of output path gets, end to end (docs/ROBUSTNESS.md, "What each output path
# gets"): a symbolic link is followed and its target replaced atomically (the link stays); a
# FIFO, a character device and standard output are streamed to (no temporary, no rename); a
# directory, block device or socket is refused before any work; a write past `ulimit -f` is a
# located error with no temporary left; `fixstep new` is whole or nothing.
# Every fixstep call has `timeout 20` as a hang guard only.
#   output_paths_test.sh FIXSTEP STATE_HASHES SOURCE_DIR
#
# CI runs as root, where a regression could rename a file over /dev/null or /dev/stdout: the
# cases that name a real device run only after the same case on a private one (a node made
# with mknod, /proc/self/fd/1) has shown that the device is streamed to, not replaced.
set -u
fixstep=$(realpath "$1") state_hashes=$(realpath "$2") src=$(realpath "$3")
. "$(dirname "$0")/lib.sh"
cd "$work" || exit 1
cp "$src/assets/scenes/default.toml" s.toml
fx() { env -u DISPLAY -u WAYLAND_DISPLAY timeout 20 "$fixstep" "$@"; }
fx run s.toml --steps 20 --csv ref.csv -q || fail "the reference run"
no_temporaries() {  # no_temporaries NAME DIR: no ".NAME.tmp.PID" file or directory in DIR
  if ls -A "$2" | grep -q '\.tmp\.[0-9]*$'; then fail "$1: temporaries left: $(ls -A "$2")"
  else ok "$1: no temporary left"; fi
}

# --- symbolic links: followed, the final target replaced atomically, the link kept ---
echo old > t.csv && chmod 640 t.csv && ln -s t.csv l.csv
fx run s.toml --steps 20 --csv l.csv -q
[ -L l.csv ] && cmp -s t.csv ref.csv && [ "$(stat -c %a t.csv)" = 640 ] \
  && ok "a link to a file: the link stays, its target has the CSV and its mode 640" \
  || fail "link: $(ls -l l.csv t.csv)"
mkdir -p sub && ln -s sub/new.csv dangling.csv
fx run s.toml --steps 20 --csv dangling.csv -q
[ -L dangling.csv ] && cmp -s sub/new.csv ref.csv \
  && ok "a dangling link: its target is created, the link stays" || fail "dangling: $(ls -l . sub)"
ln -s l.csv chain.csv
fx run s.toml --steps 20 --record chain.csv -q
[ -L chain.csv ] && [ -L l.csv ] && head -1 t.csv | grep -q fixstep \
  && ok "a chain of links: the last target holds the recording, both links stay" \
  || fail "chain: $(ls -l chain.csv l.csv t.csv); $(head -1 t.csv)"
no_temporaries "links" . && no_temporaries "links (sub)" sub
ln -s loop_b loop_a && ln -s loop_a loop_b
refused "a loop of links" 2 "--csv loop_a is a loop of symbolic links" \
  run s.toml --steps 5 --csv loop_a

# --- streams: written in place ---
mkfifo p.csv
timeout 20 cat p.csv > from_fifo.csv &
reader=$!
fx run s.toml --steps 20 --csv p.csv -q
wait $reader
[ -p p.csv ] && cmp -s from_fifo.csv ref.csv \
  && ok "a FIFO: still a FIFO, its reader got the whole CSV" || fail "fifo: $(ls -l p.csv)"
no_temporaries "a FIFO" .
fx run s.toml --steps 20 --csv - >dash.csv 2>dash.err
cmp -s dash.csv ref.csv && ! grep -q scene= dash.csv && grep -q '^csv=-$' dash.err \
  && ok "--csv -: standard output holds the CSV alone, the summary went to standard error" \
  || { fail "--csv -"; head -3 dash.csv dash.err; }
fx run s.toml --steps 20 --csv /proc/self/fd/1 2>/dev/null | cat >proc.csv
stdout_streams=0
cmp -s proc.csv ref.csv && stdout_streams=1
[ $stdout_streams = 1 ] && ok "--csv /proc/self/fd/1 into a pipe: the CSV" || fail "/proc/self/fd/1"
if [ $stdout_streams = 1 ]; then  # a build that renamed over it would replace /dev/stdout
  fx run s.toml --steps 20 --csv /dev/stdout 2>/dev/null | cat >devstdout.csv
  cmp -s devstdout.csv ref.csv && [ -L /dev/stdout ] \
    && ok "--csv /dev/stdout piped: the CSV; /dev/stdout is still a link" || fail "/dev/stdout"
fi
fx run s.toml --steps 200000 --csv - 2>head.err | head -2 >head.out
status=${PIPESTATUS[0]}
[ "$status" -eq 1 ] && grep -q -- "--csv: cannot write -: Broken pipe" head.err \
  && [ "$(wc -l <head.out)" -eq 2 ] \
  && ok "--csv - | head: exit 1, 'Broken pipe' named, no death by SIGPIPE" \
  || { fail "--csv - | head: exit $status"; cat head.err; }
refused "--csv - --record /proc/self/fd/1" 2 "both write into standard output" \
  run s.toml --steps 5 --csv - --record /proc/self/fd/1
device_streams=0
if [ "$(id -u)" -ne 0 ]; then
  device_streams=1  # /dev/null cannot be replaced without root
elif mknod nul c 1 3 2>/dev/null && echo probe >nul 2>/dev/null; then
  fx run s.toml --steps 20 --csv nul --record nul >out.txt 2>&1
  status=$?
  [ $status -eq 0 ] && [ -c nul ] && device_streams=1
  [ $device_streams = 1 ] && ok "a private character device for --csv and --record: still one" \
    || { fail "a private character device: exit $status, $(ls -l nul)"; cat out.txt; }
else
  ok "a private character device: skipped (mknod is not allowed here)"
fi
if [ $device_streams = 1 ]; then
  fx run s.toml --steps 20 --csv /dev/null --record /dev/null -q
  status=$?
  [ $status -eq 0 ] && [ -c /dev/null ] && ok "--csv /dev/null --record /dev/null: exit 0, still a device" \
    || fail "/dev/null: exit $status"
fi

# --- refused before any work ---
mkdir adir
refused "a directory" 2 "--csv adir is a directory \(an output is a regular file" \
  run s.toml --steps 5 --csv adir
python3 -c 'import socket; socket.socket(socket.AF_UNIX).bind("sock")'
refused "a socket" 2 "--record sock is a socket" run s.toml --steps 5 --record sock
[ -S sock ] && ok "the socket is still a socket" || fail "sock: $(ls -l sock)"
if [ "$(id -u)" -eq 0 ] && mknod blk b 7 200 2>/dev/null; then
  refused "a block device" 2 "--csv blk is a block device" run s.toml --steps 5 --csv blk
  [ -b blk ] && ok "the block device is still one" || fail "blk: $(ls -l blk)"
fi
refused "a descriptor not open" 2 "--csv /dev/fd/9 names descriptor 9, which is not open" \
  run s.toml --steps 5 --csv /dev/fd/9

# --- videos into a FIFO: streamed (MP4 fragmented), no manifest beside them ---
mkfifo clip.mp4 clip.gif
for v in clip.mp4 clip.gif; do
  timeout 20 cat $v > "got_$v" &
  reader=$!
  fx render s.toml --video $v --frames 12 --size 64x64 -q
  status=$?
  wait $reader
  [ $status -eq 0 ] && [ -p $v ] && [ ! -e $v.frames.csv ] \
    && ok "render --video $v (a FIFO): exit 0, still a FIFO, no manifest beside it" \
    || fail "render --video $v: exit $status, $(ls -l $v*)"
done
grep -q ftyp got_clip.mp4 && grep -q moof got_clip.mp4 \
  && ok "the streamed MP4 is fragmented (ftyp, moof)" || fail "got_clip.mp4: $(head -c 64 got_clip.mp4 | od -c | head -2)"
[ "$(head -c 6 got_clip.gif)" = GIF89a ] && [ "$(tail -c 1 got_clip.gif | od -An -tx1 | tr -d ' ')" = 3b ] \
  && ok "the streamed GIF is whole (GIF89a ... trailer 0x3b)" || fail "got_clip.gif"

# --- a file-size limit: a located error, exit 1, no temporary, no signal death ---
over_limit() {  # over_limit NAME PATTERN ARGS...: under `ulimit -f 8` (8 KiB)
  local name=$1 pattern=$2
  shift 2
  (ulimit -f 8; fx "$@" -q) >out.txt 2>&1
  local got=$?
  [ $got -eq 1 ] && grep -Eq -- "$pattern" out.txt && ok "ulimit -f: $name: exit 1, named" \
    || { fail "ulimit -f: $name: exit $got"; cat out.txt; }
}
mkdir -p lim && cd lim || exit 1
cp ../s.toml .
over_limit "--csv" "error: --csv: cannot write big.csv: File too large" \
  run s.toml --steps 2000 --csv big.csv
over_limit "--record" "error: --record: cannot write big.rec: File too large" \
  run s.toml --steps 20000 --record big.rec
over_limit "--video" "error: --video.*: cannot write big.mp4.*: File too large" \
  render s.toml --video big.mp4 --frames 600 --size 256x256
over_limit "--out" "error: --out: cannot write fr/frame_000000.png: File too large" \
  render s.toml --out fr --frames 3 --size 512x512
[ ! -e big.csv ] && [ ! -e big.rec ] && [ ! -e big.mp4 ] \
  && ok "ulimit -f: no output appeared under its name" || fail "ulimit -f left $(ls)"
no_temporaries "ulimit -f" . && no_temporaries "ulimit -f (fr)" fr
(ulimit -f 8; timeout 20 "$state_hashes" s.toml --ticks 100000 >hashes.txt) 2>sh.err
status=$?
[ $status -eq 1 ] && grep -q "state_hashes: cannot write standard output: File too large" sh.err \
  && ok "ulimit -f: state_hashes > FILE: exit 1, named" || { fail "state_hashes: exit $status"; cat sh.err; }
cd .. || exit 1

# --- fixstep new: whole or nothing, its cd line quoted, an unusable DIR named ---
(ulimit -f 2; fx new deep/er/game) >out.txt 2>&1
status=$?
[ $status -eq 1 ] && grep -q "cannot write deep/er/game/main.cpp: File too large" out.txt \
  && [ ! -e deep ] && ! ls -A | grep -q "\.tmp\." \
  && ok "new on a full disk (ulimit -f 2): exit 1, no project, no parents, no temporary" \
  || { fail "new on a full disk: exit $status, $(ls -A)"; cat out.txt; }
name="my game's \$HOME"
fx new "$name" >new.txt 2>&1 || fail "new '$name': $(cat new.txt)"
line=$(grep -m1 '^  cd ' new.txt)
(eval "${line#  }" && [ "$(basename "$PWD")" = "$name" ] && [ -f main.cpp ]) \
  && ok "new: the printed cd line goes into '$name'" || fail "new: cd line: $line"
refused "new \"\"" 2 'fixstep new: DIR is empty \(""\)' new ""
refused "new /" 2 "fixstep new: DIR / has no name of its own" new /
finish
