# tests/lib.sh: what the end-to-end test scripts share. Source it right after `set -u`:
#
#   . "$(dirname "$0")/lib.sh"
#
# It gives
#   $work                 a temporary directory, removed at exit (with any X server started);
#   ok NAME / fail NAME   one check's verdict, printed as "ok - NAME" or "FAIL - NAME";
#   expect NAME RE FILE   ok when FILE matches the extended regular expression RE;
#   expect_text NAME S F  ok when file F contains the text S;
#   hash_of FILE          the first state_hash in FILE (16 hex digits), or a text naming FILE
#                         when it has none, so that two outputs without a hash never compare equal;
#   have_xvfb             whether Xvfb is installed (bash .ci/install-deps installs it);
#   with_xvfb CMD...      CMD with DISPLAY set to a virtual X server (Xvfb, 1024x768x24) started on
#                         the first call and kept for the script; returns CMD's exit status;
#   wait_for FILE RE      the first match of the extended regular expression RE in FILE,
#                         waiting up to 10 s for it (status 1 if none came);
#   finish                prints "P passed, F failed" and exits non-zero if a check failed.
#
# with_xvfb starts Xvfb itself rather than through xvfb-run: xvfb-run's exit trap removes its
# temporary directory and kills the server under `set -e`, and when either step fails it exits 5
# or 1 in place of the command's status (CI saw "problem while cleaning up temporary directory"
# turn a `view` that exited 3 into 5). -displayfd lets Xvfb pick a free display itself.
# -noreset: by default Xvfb resets whenever its last client disconnects, and a client that
# connects during the reset is refused. The xdotool calls (each its own short-lived client) race
# the `view` they wait for: CI saw `view --record` fail with "could not connect to DISPLAY=:0",
# and 40 views each started beside eight xdotool calls failed 9 times without -noreset, 0 of 150
# with it.

work=$(mktemp -d)
xvfb_pid="" xvfb_display=""
trap 'stop_xvfb; rm -rf "$work"' EXIT
failures=0 passes=0

ok() {
  passes=$((passes + 1))
  echo "ok - $1"
}
fail() {
  failures=$((failures + 1))
  echo "FAIL - $1"
}
expect() { if grep -Eq -- "$2" "$3"; then ok "$1"; else fail "$1: no /$2/ in:"; cat "$3"; fi; }
expect_text() { if grep -Fq -- "$2" "$3"; then ok "$1"; else fail "$1: no '$2' in $3"; fi; }
hash_of() {
  local h
  h=$(grep -Eo 'state_hash=[0-9a-f]{16}' "$1" 2>/dev/null | head -1 | cut -d= -f2)
  echo "${h:-(no state_hash in $1)}"
}

# refused NAME EXIT PATTERN ARGS...: runs `fx ARGS` (the test defines fx); passes when it exits
# EXIT with a message matching PATTERN.
refused() {
  local name=$1 code=$2 pattern=$3
  shift 3
  fx "$@" >out.txt 2>&1
  local got=$?
  [ "$got" -eq "$code" ] && grep -Eq -- "$pattern" out.txt && ok "$name: exit $code" \
    || { fail "$name: exit $got"; cat out.txt; }
}
have_xvfb() { command -v Xvfb >/dev/null; }
start_xvfb() {
  [ -n "$xvfb_display" ] && return 0
  Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp -noreset 3>"$work/xvfb.display" \
    >"$work/xvfb.log" 2>&1 &
  xvfb_pid=$!
  local i
  for i in $(seq 200); do # Xvfb writes the display number and a newline once it is ready
    if [ "$(wc -l <"$work/xvfb.display")" -ge 1 ]; then
      xvfb_display=":$(head -1 "$work/xvfb.display")"
      return 0
    fi
    kill -0 "$xvfb_pid" 2>/dev/null || break
    sleep 0.05
  done
  echo "Xvfb did not start:" >&2
  cat "$work/xvfb.log" >&2
  return 1
}
stop_xvfb() {
  [ -n "$xvfb_pid" ] || return 0
  kill "$xvfb_pid" 2>/dev/null
  wait "$xvfb_pid" 2>/dev/null
  xvfb_pid="" xvfb_display=""
}
with_xvfb() {
  start_xvfb || return 125
  DISPLAY=$xvfb_display "$@"
}
# window_with_keys GAME TITLE FRAMES RECORDING OUTPUT KEYS: runs GAME --window --frames FRAMES
# --record RECORDING (its output into OUTPUT) under Xvfb, waits up to 5 s for its window
# (titled TITLE), then runs KEYS, xdotool steps in bash with $wid the window, and waits for the
# game to end; returns its exit status.
window_with_keys() {
  with_xvfb bash -c '
    "$1" --window --frames "$3" --record "$4" >"$5" 2>&1 &
    pid=$!
    for _ in $(seq 100); do
      wid=$(xdotool search --name "$2" 2>/dev/null | head -1); [ -n "$wid" ] && break; sleep 0.05
    done
    sleep 0.5
    eval "$6"
    wait "$pid"' _ "$@"
}

finish() {
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
  exit
}

wait_for() {
  local i v
  for i in $(seq 200); do
    v=$(grep -Eo "$2" "$1" 2>/dev/null | head -1)
    [ -n "$v" ] && { echo "$v"; return 0; }
    sleep 0.05
  done
  return 1
}
