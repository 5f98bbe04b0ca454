#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang, ASan + UBSan) into build-fuzz/ and fuzzes each for SECONDS
# (default 60) from its seed corpus, copied to a scratch folder so that the repository's corpus does not grow.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: raw nrrd ... as in fuzz/fuzz_TARGET.cpp; default all)
# Prints executions per target; exits non-zero on any finding (crash, sanitizer report, leak, timeout, out of
# memory), whose input is kept in build-fuzz/findings/TARGET/.
set -euo pipefail
seconds=${1:-60}
shift || true
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang libclang-rt-14-dev  # libclang-rt-14-dev: libFuzzer and the sanitizer runtimes

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVR_FUZZ=ON \
  -DVR_SANITIZE=ON >/dev/null
if (($#)); then targets=("$@"); else targets=($(ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||')); fi
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]/#/fuzz_}"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
findings=0
printf '%-18s %12s %8s  %s\n' target executions seconds result
for t in "${targets[@]}"; do
  work=$scratch/$t
  mkdir -p "$work/corpus" "$work/artifacts"
  cp fuzz/corpus/"$t"/* "$work/corpus/"
  start=$(date +%s)
  # Memory caps: an "absurd size" input is a finding only if the code really allocates that much before checking.
  # Leaks are checked per input (libFuzzer with LeakSanitizer); VTK/OpenVDB frames are suppressed (fuzz/lsan.supp).
  if ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp \
     UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
     build-fuzz/fuzz/fuzz_"$t" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$work/corpus" >"$work/log" 2>&1; then
    result=ok
  else
    result="FINDING (log: build-fuzz/findings/$t/log)"
    findings=$((findings + 1))
  fi
  if [[ $result != ok ]] || compgen -G "$work/artifacts/*" >/dev/null; then
    mkdir -p build-fuzz/findings/"$t"
    cp "$work/log" "$work"/artifacts/* build-fuzz/findings/"$t"/ 2>/dev/null || true
  fi
  executions=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo '?')
  printf '%-18s %12s %8s  %s\n' "$t" "$executions" "$(($(date +%s) - start))" "$result"
done
((findings == 0)) || { echo "$findings target(s) found something: see build-fuzz/findings/" >&2; exit 1; }
