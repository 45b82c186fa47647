#!/usr/bin/env bash
# Times a cold build as a new user meets it (issue 31): clones the repository into a temporary folder and
# runs the README's two commands there, `make demo` then `make test`, without ccache and with the
# package step (apt, npm) run first and timed on its own. Prints, per phase, the wall time and the CPU
# seconds of the compiler processes (user + sys, measured per compile by /usr/bin/time, so far less
# sensitive to other load than wall time), then the 15 slowest translation units from .ninja_log (wall
# seconds, as ninja saw them) and by compile CPU.
#
# Usage: scripts/measure-cold-build.sh [--repo PATH_OR_URL] [--rev REV] [--jobs N] [--keep]
#                                      [--target TARGET]
#   --repo    what to clone (default: the checkout this script is in; uncommitted changes are not seen)
#   --rev     commit to check out after cloning (default: the clone's HEAD)
#   --target  cheap mode: configure and build only TARGET (e.g. crowdlab_core); no packages, no demo,
#             no tests. For trying the script out; the numbers are not the issue's.
#   --keep    leave the temporary folder (default: removed)
# Needs /usr/bin/time (Debian package `time`). Report the machine and its load with the numbers: the
# script prints both.
set -euo pipefail

repo="$(cd "$(dirname "$0")/.." && pwd)"
rev="" jobs="$(nproc)" keep=0 target=""
while (($#)); do
  case "$1" in
    --repo) repo="$2"; shift 2 ;;
    --rev) rev="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --target) target="$2"; shift 2 ;;
    --keep) keep=1; shift ;;
    *) echo "measure-cold-build: unknown argument '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done
[[ -x /usr/bin/time ]] || { echo "measure-cold-build: needs /usr/bin/time (apt install time)" >&2; exit 2; }

tmp="$(mktemp -d /tmp/crowdlab-cold.XXXXXX)"
((keep)) || trap 'rm -rf "$tmp"' EXIT
src="$tmp/crowdlab"
cpu_log="$tmp/compile-cpu.log"

# Every compile runs through this launcher: it records user, sys and wall seconds and the object.
# CMake takes the launcher from the environment on the first configure, which also keeps ccache out.
launcher="$tmp/time-compile"
cat >"$launcher" <<EOF
#!/bin/sh
out=unknown; prev=""
for a in "\$@"; do [ "\$prev" = "-o" ] && out="\$a"; prev="\$a"; done
exec /usr/bin/time -a -o "$cpu_log" -f "%U %S %e \$out" "\$@"
EOF
chmod +x "$launcher"
export CMAKE_CXX_COMPILER_LAUNCHER="$launcher" CMAKE_C_COMPILER_LAUNCHER="$launcher" CCACHE_DISABLE=1

now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.0f", b - a }'; }
cpu_total() { [[ -f $cpu_log ]] && awk '{ s += $1 + $2 } END { printf "%.0f", s }' "$cpu_log" || echo 0; }
declare -a rows=()
phase() {  # phase NAME COMMAND...: runs the command in the clone, records wall and compile CPU
  local name="$1"; shift
  local cpu0 t0 t1 rc=0
  cpu0="$(cpu_total)"; t0="$(now)"
  (cd "$src" && "$@") >"$tmp/$name.log" 2>&1 || rc=$?
  t1="$(now)"
  rows+=("| $name | $(secs "$t0" "$t1") | $(( $(cpu_total) - cpu0 )) | $rc |")
  if ((rc)); then echo "measure-cold-build: '$name' failed (exit $rc); log: $tmp/$name.log" >&2; keep=1; trap - EXIT; fi
  return 0
}

echo "machine: $(nproc) cores, $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo), $(uname -sr)"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
git clone --quiet --no-local "$repo" "$src"
[[ -z $rev ]] || git -C "$src" checkout --quiet "$rev"
echo "commit: $(git -C "$src" log -1 --format='%h %s' | cut -c1-100)"

if [[ -n $target ]]; then
  phase "configure" cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
  phase "build $target" cmake --build build -j "$jobs" --target "$target"
else
  # `make X -o D` treats the package target D as up to date: the packages are timed apart, first.
  phase "packages (apt, npm)" make test-deps
  phase "make demo" make demo JOBS="$jobs" -o deps
  phase "make test" make test JOBS="$jobs" -o test-deps
fi

echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| phase | wall (s) | compile CPU (s) | exit |"
echo "|---|---|---|---|"
printf '%s\n' "${rows[@]}"
echo
echo "Top 15 translation units by wall time (.ninja_log, seconds):"
# sed -n 1,15p reads to the end where head would exit early: under pipefail a SIGPIPE to sort (exit 141) once ended
# this script before its last table (session 22).
awk -F'\t' 'NR > 1 && $4 ~ /\.o$/ { printf "%8.1f  %s\n", ($2 - $1) / 1000, $4 }' "$src/build/.ninja_log" |
  sort -rn | sed -n '1,15p'
echo
echo "Top 15 translation units by compile CPU (user + sys, seconds):"
awk '{ printf "%8.1f  %s\n", $1 + $2, $4 }' "$cpu_log" | sort -rn | sed -n '1,15p'
echo
echo "compile CPU total: $(cpu_total) s over $(wc -l <"$cpu_log") compiles"
((keep)) && echo "kept: $tmp"
exit 0
