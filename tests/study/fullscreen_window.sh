#!/usr/bin/env bash
# Full screen on a bare X server (Xvfb, no window manager): the study window must cover the screen.
# usage: fullscreen_window.sh CROWDLAB SPEC STIMULI OUT SNAPDIR WIDTHxHEIGHT
#   SPEC must have instructions text (the first screen is what is measured).
# Writes OUT/geometry.txt (xdotool's X, Y, WIDTH, HEIGHT of the study window) and SNAPDIR/root.xwd
# (the whole X screen); quits the session with Esc, Y. Exit status 0 when every step succeeded.
set -euo pipefail
CROWDLAB=$1 SPEC=$2 STIMULI=$3 OUT=$4 SNAP=$5 SIZE=$6
source "$(dirname "$0")/xvfb_session.sh"
start_xvfb "$SIZE"
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
