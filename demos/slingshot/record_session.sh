#!/usr/bin/env bash
# How assets/recordings/slingshot.rec was made: the game played in a window on a virtual X
# display (Xvfb), the mouse driven by xdotool: three shots, each a real press on the ball, a
# drag back, a release. Not run by CI (it replays the file); needs xvfb and xdotool, and
# imagemagick for the screenshots. Real time on a real clock: each run records a slightly
# different game; replay it (slingshot --replay) to see its score before keeping it.
#
#   bash demos/slingshot/record_session.sh build/ci/bin/slingshot OUT.rec [SCREENSHOT_DIR]
set -euo pipefail
game=$1
out=$2
shots=${3:-}
display=:97
# -noreset: a client that connects while Xvfb resets (after its last client left) is refused;
# xdotool's short-lived connections would race the game's (tests/lib.sh says more).
Xvfb "$display" -screen 0 1280x720x24 -noreset >/dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2>/dev/null || true' EXIT
export DISPLAY=$display
sleep 1
"$game" --record "$out" &
pid=$!
win=$(xdotool search --sync --name "^slingshot$" | head -n 1)
sleep 1

# World metres to window pixels: the game's camera is centred on (0, 9) m, 46 m wide, in a
# 1280x720 window (27.83 px/m, y up).
px() { awk -v x="$1" 'BEGIN { printf "%d", 640 + x * 1280 / 46 }'; }
py() { awk -v y="$1" 'BEGIN { printf "%d", 360 - (y - 9) * 1280 / 46 }'; }

# shot X Y NAME: press on the ball (resting at (-12, 2.83) m), drag it to (X, Y) m in 20
# moves, hold, let go, and wait for the flight to end (a screenshot half-way if asked).
shot() {
  local x0 y0 x1 y1
  x0=$(px -12) y0=$(py 2.83) x1=$(px "$1") y1=$(py "$2")
  xdotool mousemove --window "$win" "$x0" "$y0"
  sleep 0.3
  xdotool mousedown 1
  for i in $(seq 1 20); do
    xdotool mousemove --window "$win" $((x0 + (x1 - x0) * i / 20)) $((y0 + (y1 - y0) * i / 20))
    sleep 0.03
  done
  sleep 0.6
  if [ -n "$shots" ]; then import -window root "$shots/$3_pulled.png"; fi
  xdotool mouseup 1
  sleep 1.2
  if [ -n "$shots" ]; then import -window root "$shots/$3_flying.png"; fi
  sleep 7
}

[ -n "$shots" ] && mkdir -p "$shots"
shot -14.4 1.2 shot1
shot -14.8 1.0 shot2
shot -14.2 0.8 shot3
if [ -n "$shots" ]; then import -window root "$shots/over.png"; fi
xdotool key --window "$win" Escape
wait "$pid"
