# Sourced by the study-window tests (drive_window_session.sh, fullscreen_window.sh): a private X server.
# start_xvfb WIDTHxHEIGHT [DISPLAY_NUMBER] starts Xvfb on a free display number that Xvfb picks itself
# (-displayfd; other users of the machine may run their own Xvfb) unless one is given, exports DISPLAY
# once the server answers, and sets an EXIT trap that kills APP_PID (the caller's window, when set) and
# the server. Returns 1, with Xvfb's log on stderr, when the server did not start after 4 tries.
APP_PID=""
xvfb_cleanup() {
  [[ -n "$APP_PID" ]] && kill "$APP_PID" 2>/dev/null || true
  kill "$XVFB_PID" 2>/dev/null || true
  rm -f "$XLOG" "$DFILE"
}
# Two servers started at the same moment with -displayfd can both try the same display number, and the
# loser exits with "Server is already active for display N" instead of trying the next number (seen
# when ctest runs two window tests at once), so a server that did not start is retried a few times
# after a short random pause.
start_xvfb() {
  local attempt
  for attempt in 1 2 3 4; do
    start_xvfb_once "$@" && return 0
    [[ $attempt -lt 4 ]] || break
    kill "$XVFB_PID" 2>/dev/null || true
    wait "$XVFB_PID" 2>/dev/null || true
    rm -f "$XLOG" "$DFILE"
    sleep "0.$((RANDOM % 9 + 1))"
  done
  echo "Xvfb did not start:" >&2
  cat "$XLOG" >&2
  return 1
}
start_xvfb_once() {
  local size=$1 dnum=${2:-}
  XLOG=$(mktemp) DFILE=$(mktemp)
  if [[ -n "$dnum" ]]; then
    Xvfb ":$dnum" -screen 0 "${size}x24" -nolisten tcp >"$XLOG" 2>&1 &
  else
    Xvfb -displayfd 3 -screen 0 "${size}x24" -nolisten tcp 3>"$DFILE" >"$XLOG" 2>&1 &
  fi
  XVFB_PID=$!
  trap xvfb_cleanup EXIT
  for _ in $(seq 300); do
    [[ -n "$dnum" || -s "$DFILE" ]] && break
    kill -0 "$XVFB_PID" 2>/dev/null || return 1  # exited: no display will come
    sleep 0.1
  done
  [[ -n "$dnum" ]] || dnum=$(head -1 "$DFILE" | tr -d '[:space:]')
  [[ -n "$dnum" ]] || return 1
  export DISPLAY=:$dnum
  for _ in $(seq 300); do
    xdotool getdisplaygeometry >/dev/null 2>&1 && return 0
    kill -0 "$XVFB_PID" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
