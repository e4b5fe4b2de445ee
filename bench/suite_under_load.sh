#!/usr/bin/env bash
# The README's test command while two busy loops hold both cores, three times
# in a row: pass/fail and wall time of each run (figures for docs/performance.md).
#
#   bash bench/suite_under_load.sh [RUNS] [BUSY]
#
# RUNS (3) runs; BUSY (2) busy-loop processes. Run it from the repository, with
# the test extras installed (the README's second command). The busy loops end
# with the script, whatever happens.
set -uo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
busy=${2:-2}
command=$(sed -n '/^```sh$/,/^```$/p' README.md | grep 'pytest' | sed 's/.*&& //')
[ -n "$command" ] || { echo "no test command found in README.md" >&2; exit 2; }
loops=()
stop_loops() { [ ${#loops[@]} -gt 0 ] && kill "${loops[@]}" 2>/dev/null; wait 2>/dev/null; }
trap stop_loops EXIT INT TERM
for _ in $(seq "$busy"); do
    sh -c 'while :; do :; done' &
    loops+=($!)
done
echo "== $busy busy loops (pids ${loops[*]}) on $(nproc) cores; test command: $command"
failed=0
for run in $(seq "$runs"); do
    log=$(mktemp -t dhsim-suite-XXXXXX.log)
    start=$SECONDS
    bash -c "$command" >"$log" 2>&1
    code=$?
    seconds=$((SECONDS - start))
    summary=$(grep -E '(passed|failed|error)' "$log" | tail -1)
    verdict=$([ "$code" -eq 0 ] && echo green || echo RED)
    printf 'run %d: %s, exit %d, %d s: %s (log %s)\n' "$run" "$verdict" "$code" "$seconds" "$summary" "$log"
    [ "$code" -eq 0 ] || failed=$((failed + 1))
done
echo "== $((runs - failed)) of $runs runs green under load"
[ "$failed" -eq 0 ]
