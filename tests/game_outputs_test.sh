#!/usr/bin/env bash
# The games' outputs get the fixstep command's checks, end to end (fixstep::app::run and
# fixstep::net::run, on peggle and airhockey):
#  (a) paths: --record and --last-frame naming one file, an output that is an input
#      (--replay), a --last-frame that is a directory, a --out DIR holding an earlier capture
#      (refused, or replaced with --overwrite), --scene for a game that builds its level in code
#      (its setup() would replace the scene): refused with exit 2 before anything runs, the old
#      files untouched;
#  (b) bounds: --frames 10^12 and --sync-test 10^9 refused before the first tick, naming the flag;
#  (c) a stop: SIGINT in a headless game with --record exits 130 and leaves a complete recording
#      of every tick run that replays with every hash verified; while it runs, the recording's
#      temporary file grows (streamed, not held in memory); SIGTERM stops a sync test and a game
#      in its window (on Xvfb, when installed), SIGINT a replay and a networked match (whose
#      recordings are written and replay; a match's is in its temporary file while it runs);
#  (d) results on standard output: every game mode and every fixstep command that prints a result
#      exits non-zero with a message on standard error when standard output is full
#      (>/dev/full) or closed (>&-).
#
#   game_outputs_test.sh PEGGLE AIRHOCKEY FIXSTEP SOURCE_DIR
set -uo pipefail
peggle=$1
airhockey=$2
fixstep=$3
src=$4
# shellcheck source=tests/lib.sh
. "$src/tests/lib.sh"
cd "$work" || exit 1

# A refusal comes before any work: the guard (124) only ends a run the checks missed.
fx() { timeout 20 "$peggle" "$@"; }

# --- (a) paths ---------------------------------------------------------------------------------
echo old >same.png
refused "--record and --last-frame one file" 2 "are the same file" \
  --frames 5 --record same.png --last-frame same.png
refused "--record and --last-frame one file through ./" 2 "are the same file" \
  --frames 5 --record ./same.png --last-frame same.png
[ "$(cat same.png)" = old ] && ok "the file named twice is untouched" || fail "same.png was written"
ln -s same.png link.png
refused "--last-frame a link to --record's file" 2 "are the same file" \
  --frames 5 --record same.png --last-frame link.png
"$peggle" --frames 30 --record small.rec >/dev/null 2>&1
cp small.rec small.before
refused "--last-frame is the --replay input" 2 "same file as --replay small.rec" \
  --replay small.rec --last-frame small.rec
cmp -s small.rec small.before && ok "the recording replayed is untouched" || fail "small.rec changed"
mkdir adir
refused "--last-frame a directory" 2 "--last-frame adir is a directory" --frames 5 --last-frame adir
"$peggle" --frames 3 --out cap >/dev/null 2>&1
refused "--out DIR holding an earlier capture" 2 \
  "--out cap already holds a capture \(3 frames, its frames.csv\)" --frames 5 --out cap
[ "$(ls cap | wc -l)" -eq 4 ] && ok "the earlier capture is untouched" || fail "cap: $(ls cap)"
refused "--replay --out DIR holding an earlier capture" 2 "already holds a capture" \
  --replay small.rec --out cap
refused "--last-frame a frame of the capture in --out" 2 "is a file the capture in --out" \
  --replay small.rec --out cap2 --last-frame cap2/frame_000001.png
refused "--last-frame the manifest of the capture in --out" 2 "is a file the capture in --out" \
  --frames 5 --out cap2 --last-frame cap2/frames.csv
if "$peggle" --frames 2 --out cap --overwrite >/dev/null 2>&1 &&
  [ "$(ls cap | tr '\n' ' ')" = "frame_000000.png frame_000001.png frames.csv " ]; then
  ok "--overwrite replaces the earlier capture"
else
  fail "--overwrite: $(ls cap)"
fi
printf '[world]\ndt = 0.01\n' >level.toml
refused "--scene for a game built in code" 2 "--scene level.toml: peggle builds its level in code" \
  --scene level.toml --frames 5
fx() { timeout 20 "$airhockey" "$@"; }
refused "a match's --scene for a game built in code" 2 "--scene level.toml: airhockey builds" \
  --join 127.0.0.1:9 --token 00112233445566778899aabbccddeeff --scene level.toml --bot --ticks 10
refused "a match's --record and --last-frame one file" 2 "are the same file" \
  --host 0 --bot --ticks 10 --record m.png --last-frame m.png
fx() { timeout 20 "$peggle" "$@"; }

# --record -: standard output carries the recording alone, the summary goes to standard error.
if "$peggle" --frames 30 --record - >piped.rec 2>piped.err && grep -q "^ticks=" piped.err &&
  "$peggle" --replay piped.rec >piped.out 2>&1; then
  ok "--record -: the recording alone on standard output (it replays), the summary on stderr"
else
  fail "--record -: mixed with the summary"
  head -3 piped.rec piped.err piped.out
fi

# --- (b) bounds, before the first tick ---------------------------------------------------------
refused "--frames 10^12" 1 "--frames 1000000000000 .*a command may step at most" \
  --frames 1000000000000
refused "--sync-test 10^9" 1 "--sync-test 1000000000" --frames 10 --sync-test 1000000000
refused "--sync-test 10^6 on 10 frames: the snapshots' memory" 1 \
  "--sync-test 1000000: 1000001 snapshots .* GiB allowed" --frames 10 --sync-test 1000000
refused "--frames 10^8 --record: more hashes than a recording may hold" 1 \
  "--record big.rec: --frames 100000000 .* record at most [0-9]+ frames" \
  --frames 100000000 --record big.rec
fx() { timeout 20 "$airhockey" "$@"; }
refused "a match's --ticks 10^8 --record: more hashes than a recording may hold" 1 \
  "--record big.rec: --ticks 100000000, .* record at most [0-9]+ ticks" \
  --host 0 --bot --ticks 100000000 --record big.rec
fx() { timeout 20 "$peggle" "$@"; }

# --- (c) a stop --------------------------------------------------------------------------------
# size_of FILE: its size in bytes, or 0.
size_of() { stat -c %s "$1" 2>/dev/null || echo 0; }
# grows PID GLOB: waits (up to 10 s) until the file GLOB names has grown twice while PID runs,
# to more than 4 MB.
grows() {
  local pid=$1 glob=$2 last=0 seen=0 size f
  for _ in $(seq 200); do
    kill -0 "$pid" 2>/dev/null || return 1
    for f in $glob; do size=$(size_of "$f"); done
    if [ "${size:-0}" -gt "$last" ]; then
      [ "$last" -gt 0 ] && seen=$((seen + 1))
      last=$size
      [ "$seen" -ge 2 ] && [ "$last" -gt 4000000 ] && return 0
    fi
    sleep 0.05
  done
  return 1
}
# ended PID: PID's exit status once it has ended, waiting up to 10 s (a process that ignores the
# signal, as one without a handler does in a background job of a script, is then killed: 137).
ended() {
  timeout 10 tail --pid="$1" -f /dev/null || kill -KILL "$1" 2>/dev/null
  wait "$1"
}
"$peggle" --frames 4000000 --record long.rec >long.out 2>long.err &
pid=$!
if grows "$pid" ".long.rec.tmp.$pid"; then
  ok "headless --record: the recording's temporary file grows while the game runs"
else
  fail "headless --record: no growing .long.rec.tmp.$pid"
fi
kill -INT "$pid"
ended "$pid"
status=$?
[ "$status" -eq 130 ] && ok "SIGINT: a headless game exits 130" || { fail "exit $status"; cat long.err; }
expect "SIGINT: says so, the recording written" "stopped by SIGINT after tick [0-9]+.*recording written" long.err
[ -z "$(find . -name '.*.tmp.*')" ] && ok "SIGINT: no temporary left" || fail "$(find . -name '.*.tmp.*')"
ticks=$(grep -Eo 'recorded [0-9]+ ticks' long.out | grep -Eo '[0-9]+')
# The replay writes every frame, so that it is still running when the signal comes however
# fast the engine replays the recording's ticks (without frames: about 0.2 s here).
"$peggle" --replay long.rec --out replay_frames >replay.out 2>&1 &
rpid=$!
sleep 0.3
kill -INT "$rpid"
ended "$rpid"
status=$?
[ "$status" -eq 130 ] && ok "SIGINT: a replay exits 130" || { fail "replay exit $status"; cat replay.out; }
if "$peggle" --replay long.rec >replay.out 2>&1 && grep -q "^ticks=${ticks:-x} " replay.out &&
  grep -Eq "^verified=[1-9]" replay.out; then
  ok "SIGINT: the recording of the $ticks ticks run replays, every hash verified"
else
  fail "the stopped recording does not replay"
  cat replay.out long.out
fi
"$peggle" --frames 100000000 --sync-test 4 >sync.out 2>&1 &
pid=$!
sleep 0.5
kill -TERM "$pid"
ended "$pid"
status=$?
[ "$status" -eq 143 ] && ok "SIGTERM: a sync test exits 143" || { fail "sync test exit $status"; cat sync.out; }
expect "SIGTERM: the sync test says so" "stopped by SIGTERM after tick" sync.out
# In the window (on a virtual X server): the recording streamed, and SIGTERM ends the game with
# it written whole.
if have_xvfb && start_xvfb; then
  DISPLAY=$xvfb_display "$peggle" --record window.rec >window.out 2>&1 &
  pid=$!
  # (It buffers 64 kB, half a minute of a window's hash lines, before its first write.)
  for _ in $(seq 100); do [ -e ".window.rec.tmp.$pid" ] && break; sleep 0.05; done
  sleep 1  # a second of play
  [ -e ".window.rec.tmp.$pid" ] && [ ! -e window.rec ] &&
    ok "window --record: the recording's temporary file is open while the game plays" ||
    fail "window --record: no .window.rec.tmp.$pid"
  kill -TERM "$pid"
  ended "$pid"
  status=$?
  [ "$status" -eq 143 ] && ok "SIGTERM: a game in its window exits 143" ||
    { fail "window exit $status"; cat window.out; }
  "$peggle" --replay window.rec >wreplay.out 2>&1 && ok "SIGTERM: the window's recording replays" ||
    { fail "the window's recording"; cat wreplay.out; }
else
  echo "skip - the window (no Xvfb)"
fi
"$airhockey" --host 0 --bot --ticks 5000000 --record match.rec >host.out 2>&1 &
hpid=$!
port=$(wait_for host.out 'hosting on [0-9.]+:[0-9]+' | grep -Eo '[0-9]+$')
token=$(wait_for host.out 'token [0-9a-f]{32}' | grep -Eo '[0-9a-f]{32}$')
"$airhockey" --join "127.0.0.1:${port:-9}" --token "${token:-0}" --bot --ticks 5000000 \
  >join.out 2>&1 &
jpid=$!
sleep 2  # the match under way (a bot match of 5·10^6 ticks runs for minutes)
# Streamed: the host's recording is in its temporary file, not yet under its name; the joiner
# (no --record) streams its desync recording beside ./.airhockey-desync.PID.rec.
[ -e ".match.rec.tmp.$hpid" ] && [ ! -e match.rec ] && [ -e "..airhockey-desync.$jpid.rec.tmp.$jpid" ] &&
  ok "a match streams its recording into a temporary file while it runs" ||
  fail "a match's temporary files: $(ls -a)"
kill -INT "$hpid"
ended "$hpid"
status=$?
kill -INT "$jpid" 2>/dev/null
ended "$jpid" >/dev/null
[ "$status" -eq 130 ] && ok "SIGINT: a match's host exits 130" || { fail "host exit $status"; cat host.out; }
[ -z "$(find . -name '.*.tmp.*')" ] && [ -z "$(find . -name '*desync*')" ] &&
  ok "SIGINT: a match leaves no temporary (and no desync recording)" ||
  fail "$(find . -name '.*.tmp.*' -o -name '*desync*')"
if [ -f match.rec ] && "$airhockey" --replay match.rec >mreplay.out 2>&1; then
  ok "SIGINT: the match's recording is written and replays"
else
  fail "the match's recording"
  cat host.out mreplay.out 2>/dev/null
fi

# --- (d) results on standard output ------------------------------------------------------------
# lost NAME CMD...: CMD with standard output full, then closed: non-zero, a message on stderr.
lost() {
  local name=$1 status
  shift
  "$@" >/dev/full 2>err.txt
  status=$?
  [ "$status" -ne 0 ] && grep -q "cannot write the results to standard output" err.txt &&
    ok "$name >/dev/full: exit $status" || { fail "$name >/dev/full: exit $status"; cat err.txt; }
  "$@" >&- 2>err.txt
  status=$?
  [ "$status" -ne 0 ] && grep -q "standard output is closed" err.txt &&
    ok "$name >&-: exit $status" || { fail "$name >&-: exit $status"; cat err.txt; }
}
rm -rf cap3 cap4
lost "peggle --frames" "$peggle" --frames 10
lost "peggle --frames --record" "$peggle" --frames 10 --record out1.rec
lost "peggle --replay" "$peggle" --replay small.rec
lost "peggle --sync-test" "$peggle" --frames 10 --sync-test 2
lost "peggle --help" "$peggle" --help
lost "airhockey --frames" "$airhockey" --frames 10
lost "airhockey --host --help" "$airhockey" --host 0 --help
scene=$src/assets/scenes/projectile.toml
"$fixstep" run "$scene" --steps 10 --record run.rec -q
lost "fixstep run" "$fixstep" run "$scene" --steps 10
lost "fixstep replay" "$fixstep" replay run.rec
lost "fixstep render" "$fixstep" render "$scene" --frames 1 --size 64x48 --out cap3 --overwrite
lost "fixstep compare" "$fixstep" compare "$scene" --with rk4 --with semi_implicit_euler \
  --frames 1 --size 64x48 --out cap4 --overwrite
lost "fixstep --help" "$fixstep" --help
"$fixstep" run "$scene" --steps 10 -q >&- && ok "fixstep run -q with standard output closed: 0" ||
  fail "fixstep run -q >&-"
finish
