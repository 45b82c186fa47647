#!/usr/bin/env bash
# Full screen on a bare X server (Xvfb, no window manager): the study window must cover the screen.
# usage: fullscreen_window.sh CROWDLAB SPEC STIMULI OUT SNAPDIR WIDTHxHEIGHT
#   SPEC must have instructions text (the first screen is what is measured).
# Writes OUT/geometry.txt (xdotool's X, Y, WIDTH, HEIGHT of the study window) and SNAPDIR/root.xwd
# (the whole X screen); quits the session with Esc, Y. Exit status 0 when every step succeeded.
set -euo pipefail
CROWDLAB=$1 SPEC=$2 STIMULI=$3 OUT=$4 SNAP=$5 SIZE=$6
XLOG=$(mktemp) DFILE=$(mktemp)
Xvfb -displayfd 3 -screen 0 "${SIZE}x24" -nolisten tcp 3>"$DFILE" >"$XLOG" 2>&1 &
XVFB_PID=$!
APP_PID=""
cleanup() {
  [[ -n "$APP_PID" ]] && kill "$APP_PID" 2>/dev/null || true
  kill "$XVFB_PID" 2>/dev/null || true
  rm -f "$XLOG" "$DFILE"
}
trap cleanup EXIT
for _ in $(seq 300); do [[ -s "$DFILE" ]] && break; sleep 0.1; done
export DISPLAY=:$(head -1 "$DFILE" | tr -d '[:space:]')
for _ in $(seq 300); do xdotool getdisplaygeometry >/dev/null 2>&1 && break; sleep 0.1; done
mkdir -p "$OUT" "$SNAP"
"$CROWDLAB" -q study "$SPEC" --participant F01 --stimuli "$STIMULI" --out "$OUT" --require-fullscreen \
  --snapshot-dir "$SNAP" &
APP_PID=$!
for _ in $(seq 400); do [[ -s "$SNAP/screen_instructions.png" ]] && break; sleep 0.1; done
[[ -s "$SNAP/screen_instructions.png" ]] || { echo "[fullscreen] no instructions screen" >&2; exit 1; }
sleep 0.5
WID=$(xdotool search --name "crowdlab study" | head -1)
xdotool getwindowgeometry --shell "$WID" >"$OUT/geometry.txt"
xwd -root -silent -out "$SNAP/root.xwd"
xdotool key --delay 200 Escape y
wait "$APP_PID" || true  # a quit session exits 1
APP_PID=""
