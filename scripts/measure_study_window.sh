#!/usr/bin/env bash
# Measures the native study window's inter-trial gaps and dropped frames on real stimuli (issue 29,
# docs/study.md "Playback timing, measured"): runs `crowdlab study` full screen on a private Xvfb and
# answers like a hurried participant (Y, 5, Enter every 0.3 s: the window drops every key until the
# answers open, so each trial ends right after its minimum viewing time), then prints the per-trial
# inter_trial_ms and frames_dropped (median, p95, max), and the process's peak memory.
#
# usage: [NICE=-10] scripts/measure_study_window.sh CROWDLAB SPEC STIMULI OUT [WIDTHxHEIGHT] [PARTICIPANT]
#   NICE: the window's scheduling priority (a negative value needs root; it stands for a study machine
#   that runs nothing else while other users' jobs keep the CPUs busy).
#   SPEC: a 2AFC or Likert spec (2AFC: the yes/no question answers Y, the rating 5; Likert: 5 5 5 ...);
#   STIMULI: a folder with manifest.csv; OUT: a fresh response folder.
set -euo pipefail
CROWDLAB=$1 SPEC=$2 STIMULI=$3 OUT=$4 SIZE=${5:-1920x1080} PARTICIPANT=${6:-M01}
source "$(dirname "$0")/../tests/study/xvfb_session.sh"
start_xvfb "$SIZE"
/usr/bin/time -v -o "$OUT.time" nice -n "${NICE:-0}" "$CROWDLAB" -q study "$SPEC" --participant "$PARTICIPANT" --stimuli "$STIMULI" \
  --out "$OUT" >"$OUT.log" 2>&1 &
APP_PID=$!
sleep 2
while kill -0 "$APP_PID" 2>/dev/null; do
  xdotool key --delay 40 y 5 5 5 5 5 5 Return 2>/dev/null || true
  sleep 0.3
done
wait "$APP_PID" || true
APP_PID=""
python3 - "$OUT/$PARTICIPANT.csv" "$OUT.time" <<'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
trials = {}
for r in rows:
    trials.setdefault(r["trial"], r)
gaps = sorted(float(r["inter_trial_ms"]) for r in trials.values())
drops = sorted(int(r["frames_dropped"]) for r in trials.values())
shown = sorted(int(r["frames_shown"]) for r in trials.values())
def p95(v):  # nearest rank
    return v[max(0, -(-95 * len(v) // 100) - 1)]
print(f"trials {len(trials)}")
print(f"inter_trial_ms  median {statistics.median(gaps):.1f}  p95 {p95(gaps):.1f}  max {gaps[-1]:.1f}")
print(f"frames_dropped  median {statistics.median(drops)}  p95 {p95(drops)}  max {drops[-1]}  (frames shown median {statistics.median(shown)})")
for line in open(sys.argv[2]):
    if "Maximum resident" in line:
        print("peak RSS MB", int(line.split(":")[1]) // 1024)
PY
