#!/usr/bin/env bash
# Runs a libFuzzer target (tests/fuzz/meson.build):
#   run.sh replay EXE DIR...                  every file under the DIRs, once each
#   run.sh fuzz EXE SECONDS WORKDIR DIR...    fuzzing for SECONDS from the DIRs' files; new
#                                             inputs and crash artifacts go to WORKDIR
# libFuzzer's exit code is passed on: non-zero on a crash, sanitizer report, leak or timeout.
set -uo pipefail
mode=$1 exe=$2
shift 2
# -timeout: an input that takes longer is a finding (an endless loop, a quadratic blow-up).
# -rss_limit_mb: so is one that needs more memory.
common=(-timeout=20 -rss_limit_mb=2048)
case "$mode" in
replay)
  files=()
  for d in "$@"; do
    while IFS= read -r -d '' f; do files+=("$f"); done < <(find "$d" -type f -print0 | sort -z)
  done
  if [ ${#files[@]} -eq 0 ]; then
    echo "run.sh: no corpus files under $*" >&2
    exit 1
  fi
  echo "replaying ${#files[@]} inputs" >&2
  exec "$exe" "${common[@]}" "${files[@]}"
  ;;
fuzz)
  seconds=$1 work=$2
  shift 2
  mkdir -p "$work/new" "$work/artifacts"
  # Seeds from the tree are read, never written: new inputs go to $work/new (listed first).
  # -close_fd_mask=2: the targets' own messages (every refused input explains itself on
  # stderr) are dropped; libFuzzer keeps its own output and the sanitizers' reports.
  exec "$exe" "${common[@]}" -max_total_time="$seconds" -print_final_stats=1 -close_fd_mask=2 \
    -artifact_prefix="$work/artifacts/" "$work/new" "$@"
  ;;
*)
  echo "usage: run.sh replay EXE DIR... | run.sh fuzz EXE SECONDS WORKDIR DIR..." >&2
  exit 2
  ;;
esac
