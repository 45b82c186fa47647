#!/usr/bin/env bash
# Drives a real study window as a participant would: Xvfb + xdotool, keys and mouse clicks, a SIGKILL
# in the middle of a trial, a --resume, and a second (2AFC) session for screenshots.
#
# usage: drive_window_session.sh CROWDLAB LIKERT_SPEC LIKERT_STIMULI AFC_SPEC AFC_STIMULI OUT SNAPDIR TARGETS [DISPLAY_NUMBER]
#   LIKERT_SPEC: a 6-question Likert spec with instructions text; LIKERT_STIMULI: 4 test stimuli
#   AFC_SPEC:    a 2AFC spec (yes/no + 1..7); AFC_STIMULI: 1 stimulus
#   TARGETS:     lines "question value x y" of the Likert screen's click targets (window pixels), as
#                layout_trial_screen() places them for a 1280x720 canvas
# The window's own rendered screens are saved to SNAPDIR (the script uses their appearance to
# synchronise with the window). Exit status 0 when every step succeeded.
set -euo pipefail
CROWDLAB=$1 LIKERT=$2 STIMULI=$3 AFC=$4 AFC_STIMULI=$5 OUT=$6 SNAP=$7 TARGETS=$8 DNUM=${9:-}
source "$(dirname "$0")/xvfb_session.sh"
start_xvfb 1280x720 "$DNUM"

log() { echo "[drive] $*"; }
wait_file() {  # wait_file PATH [seconds]
  for _ in $(seq $(( ${2:-20} * 10 ))); do [[ -s "$1" ]] && { sleep 0.4; return 0; }; sleep 0.1; done
  echo "[drive] timeout waiting for $1" >&2; return 1
}
window() {
  local wid=""
  for _ in $(seq 100); do wid=$(xdotool search --name "crowdlab study" 2>/dev/null | head -1) && [[ -n "$wid" ]] && break; sleep 0.1; done
  [[ -n "$wid" ]] || { echo "[drive] no study window" >&2; return 1; }
  xdotool windowfocus --sync "$wid" 2>/dev/null || true
  echo "$wid"
}
key() { xdotool key --delay 150 "$@"; sleep 0.15; }
click_target() {  # click_target QUESTION VALUE
  local x y
  read -r x y < <(awk -v q="$1" -v v="$2" '$1==q && $2==v {print $3, $4}' "$TARGETS")
  xdotool mousemove --window "$WID" "$x" "$y" click 1
  sleep 0.12
}
start() {  # start SPEC STIMULI PARTICIPANT [--resume]
  "$CROWDLAB" -q study "$1" --participant "$3" --stimuli "$2" --out "$OUT" --windowed 1280x720 \
    --snapshot-dir "$SNAP/$3" ${4:-} &
  APP_PID=$!
}

log "Likert session W01: instructions, trial 1 by keys, trial 2 by clicks"
start "$LIKERT" "$STIMULI" W01
wait_file "$SNAP/W01/screen_instructions.png"
WID=$(window)
key space
wait_file "$SNAP/W01/trial_1_onset.png"
log "keys and a click at once after the onset, before min_view_ms (1200): locked, they answer nothing"
key 6 6
click_target 0 1
sleep 1.0
key 4 2 5 1 6 3
wait_file "$SNAP/W01/trial_1_answered.png"
key Return
wait_file "$SNAP/W01/trial_2_onset.png"
sleep 1.0
click_target 0 6; click_target 1 1; click_target 2 5; click_target 3 2; click_target 4 6; click_target 5 1
click_target 2 4   # change an answer within the trial (allowed; no going back to earlier trials)
wait_file "$SNAP/W01/trial_2_answered.png"
click_target -1 0  # Next
wait_file "$SNAP/W01/trial_3_onset.png"
key 3 3
log "SIGKILL in the middle of trial 3"
kill -9 "$APP_PID"; wait "$APP_PID" 2>/dev/null || true; APP_PID=""
rm -f "$SNAP"/W01/trial_3_* "$SNAP"/W01/screen_instructions.png
if "$CROWDLAB" -q study "$LIKERT" --participant W01 --stimuli "$STIMULI" --out "$OUT" --responses /dev/null \
    >/dev/null 2>&1; then echo "[drive] a used id was accepted without --resume" >&2; exit 1; fi

log "resume W01: trial 3 again, Esc then continue, trial 4"
start "$LIKERT" "$STIMULI" W01 --resume
wait_file "$SNAP/W01/screen_instructions.png"
WID=$(window)
key space
wait_file "$SNAP/W01/trial_3_onset.png"
key Escape
sleep 0.3
key n           # any key but Y continues
sleep 1.0
key 2 2 2 5 5 5
wait_file "$SNAP/W01/trial_3_answered.png"
log "Next, and a 3 typed 100 ms later, before trial 4's clip is on screen: it must not answer trial 4"
xdotool key --delay 100 Return 3
wait_file "$SNAP/W01/trial_4_onset.png"
sleep 1.0
key 1 6 1 6 1 6 Return
wait_file "$SNAP/W01/screen_finished.png"
key space
wait "$APP_PID"; APP_PID=""

log "2AFC session A01: play once, then y/n and 1..7"
start "$AFC" "$AFC_STIMULI" A01
wait_file "$SNAP/A01/trial_1_onset.png"
WID=$(window)
sleep 0.8        # the clip plays once; the questions open when it ends
key y 5
wait_file "$SNAP/A01/trial_1_answered.png"
key Return
wait_file "$SNAP/A01/screen_finished.png"
key space
wait "$APP_PID"; APP_PID=""
log "done"
