#!/usr/bin/env bash
# Replays every finding of a fuzz campaign and says where it happens: tools/triage_fuzz.sh BUILD_DIR
# The first stack frame outside the sanitizers and libFuzzer decides: a frame in libhdf5 (or another Debian
# library) is an upstream finding, a frame in centaur's sources is ours (fix it, then add the input to
# fuzz/regressions/<target>/).
set -uo pipefail
build=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
for f in "$build"/findings/*; do
  [ -f "$f" ] || continue
  name=$(basename "$f")
  target=$(echo "$name" | sed -E 's/-(crash|leak|timeout|oom|slow-unit)-.*//')
  out=$(LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp" ASAN_OPTIONS=fast_unwind_on_malloc=0 \
        timeout 120 "$build/fuzz/fuzz_$target" -timeout=30 "$f" 2>&1)
  rc=$?
  kind=$(echo "$out" | grep -o -m1 -E 'ERROR: [A-Za-z]+Sanitizer: [a-z-]+|ERROR: libFuzzer: [a-z-]+|FINDING: .*' )
  frame=$(echo "$out" | grep -E '^ +#[0-9]+ ' | grep -v -E 'sanitizer|interceptor|__asan|__ubsan|fuzzer::|libc\.so|malloc|calloc|realloc|operator new' | head -1)
  if [ $rc -eq 0 ] && [ "${name#*-leak-}" != "$name" ]; then where="upstream leak, suppressed by fuzz/lsan.supp"
  elif [ $rc -eq 0 ]; then where="no longer reproduces"
  elif echo "$frame" | grep -q '/src/\|/fuzz/'; then where="centaur: $(echo "$frame" | grep -o '/[^ ]*/\(src\|fuzz\)/[^ ]*' | sed 's|.*/\(src\|fuzz\)/|\1/|')"
  elif echo "$frame" | grep -q 'lib[a-z0-9_]*\.so'; then where="upstream: $(echo "$frame" | grep -o 'lib[a-z0-9_]*\.so[.0-9]*' | head -1) $(echo "$frame" | grep -o ' in [A-Za-z0-9_]*' | head -1)"
  else where="unknown: $frame"
  fi
  printf "%-60s %-45s %s\n" "$name" "${kind:-exit $rc}" "$where"
done
