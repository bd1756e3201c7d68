#!/usr/bin/env bash
# Run each fuzz target for a while: tools/run_fuzz.sh BUILD_DIR SECONDS TARGET...
# The committed seeds (fuzz/corpus/<target>) are read; new inputs go to BUILD_DIR/corpus/<target> (merge them into
# fuzz/corpus with `fuzz_<target> -merge=1 fuzz/corpus/<target> BUILD_DIR/corpus/<target>` when worth keeping);
# findings (crash-*, leak-*, timeout-*, oom-*) go to BUILD_DIR/findings/. Prints one line per target and appends
# it to BUILD_DIR/fuzz-runs.tsv (date, target, seconds, executions, coverage, features, findings), whose totals
# docs/reliability.md reports.
#
# The HDF5 targets run in libFuzzer's fork mode and go on after a finding: raw file images reach bugs of libhdf5
# itself (docs/reliability.md, "Upstream findings"), which must not end the campaign; every finding is kept and
# triaged by its stack (tools/triage_fuzz.sh).
set -uo pipefail
build=$1; seconds=$2; shift 2
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$build/findings" "$build/logs"
status=0
printf "%-16s %8s %12s %8s %8s %s\n" target seconds executions cov ft findings
for t in "$@"; do
  exe="$build/fuzz/fuzz_$t"
  [ -x "$exe" ] || { echo "missing $exe (build it: make fuzz)"; exit 2; }
  mkdir -p "$build/corpus/$t"
  log="$build/logs/$t.log"
  before=$(ls "$build/findings" | grep -c "^$t-" || true)
  mode=()
  case $t in primitive|arm_trajectory|sim_log) mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1) ;; esac
  # Each input must finish in 10 s and stay under 3 GiB; inputs up to 256 KiB (the HDF5 seeds are 14-135 KiB).
  # Leaks inside libhdf5 on corrupt files are upstream: suppressed (fuzz/lsan.supp); ours are not.
  # ASan tuned for throughput (1.3-1.4x more executions of the YAML loaders here): a 4 MB quarantine still catches a
  # use after a recent free; short allocation stacks and no fill of new blocks. Replay a finding with the defaults.
  LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:print_suppressions=0" \
    ASAN_OPTIONS="malloc_context_size=2:quarantine_size_mb=4:max_malloc_fill_size=0" \
    "$exe" "${mode[@]}" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 -rss_limit_mb=3072 \
    -max_len=262144 -artifact_prefix="$build/findings/$t-" "$build/corpus/$t" "$root/fuzz/corpus/$t" >"$log" 2>&1
  rc=$?
  # Executions: the final stats (plain mode) or the last status line "#N: ..." (fork mode).
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tr -d '#' | sort -n | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  after=$(ls "$build/findings" | grep -c "^$t-" || true)
  found=$((after - before))
  printf "%-16s %8s %12s %8s %8s %s\n" "$t" "$seconds" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$found"
  printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n" "$(date -u +%FT%TZ)" "$t" "$seconds" "${execs:-0}" "${cov:-0}" "${ft:-0}" \
    "$found" >>"$build/fuzz-runs.tsv"
  if [ $rc -ne 0 ] || [ $found -ne 0 ]; then status=1; echo "  finding: see $log and $build/findings/"; fi
done
exit $status
