#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang, ASan + UBSan) into build-fuzz/ and fuzzes each for SECONDS
# (default 60) from its seed corpus, copied to a scratch folder so that the repository's corpus does not grow.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: raw nrrd ... as in fuzz/fuzz_TARGET.cpp; default all)
# Prints executions per target; exits non-zero on any finding (crash, sanitizer report, leak, timeout, out of
# memory), whose inputs and log are kept in build-fuzz/findings/TARGET/.
set -euo pipefail
seconds=${1:-60}
shift || true
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang libclang-rt-14-dev  # libclang-rt-14-dev: libFuzzer and the sanitizer runtimes

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVR_FUZZ=ON \
  -DVR_SANITIZE=ON >/dev/null
if (($#)); then targets=("$@"); else targets=($(ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||')); fi
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]/#/fuzz_}"

# Memory caps: an "absurd size" input is a finding only if the code really allocates that much before checking.
# Leaks are checked per input; those inside VTK/OpenVDB/Mesa are suppressed (fuzz/lsan.supp).
fuzz() {
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 "$1" -timeout=20 -rss_limit_mb=2048 -malloc_limit_mb=2048 "${@:2}"
}

scratch=$(mktemp -d -p /dev/shm 2>/dev/null || mktemp -d)  # in memory where possible: one file per execution
trap 'rm -rf "$scratch"' EXIT
export VR_FUZZ_SCRATCH=$scratch/inputs  # the fuzzers' own folders, also of those that crashed
mkdir -p "$VR_FUZZ_SCRATCH"
findings=0
printf '%-18s %12s %8s  %s\n' target executions seconds findings
for t in "${targets[@]}"; do
  work=$scratch/$t
  mkdir -p "$work/corpus" "$work/artifacts"
  cp fuzz/corpus/"$t"/* "$work/corpus/"
  start=$(date +%s)
  # Fork mode keeps fuzzing past a finding (each is saved), so that one known bug does not end the run.
  fuzz build-fuzz/fuzz/fuzz_"$t" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$seconds" -max_len=65536 -artifact_prefix="$work/artifacts/" "$work/corpus" >"$work/log" 2>&1 || true
  # Fork mode may blame an input for what another did: a finding is an input that fails again on its own.
  found=0
  rm -rf build-fuzz/findings/"$t"
  for input in "$work"/artifacts/*; do
    [[ -f $input ]] || continue
    if ! fuzz build-fuzz/fuzz/fuzz_"$t" "$input" >"$input.log" 2>&1; then
      found=$((found + 1))
      mkdir -p build-fuzz/findings/"$t"
      cp "$input" "$input.log" build-fuzz/findings/"$t"/
    fi
  done
  findings=$((findings + found))
  executions=$(grep -o '^#[0-9]*:' "$work/log" | tail -1 | tr -d '#:')
  printf '%-18s %12s %8s  %s\n' "$t" "${executions:-?}" "$(($(date +%s) - start))" \
    "$( ((found)) && echo "$found: build-fuzz/findings/$t/" || echo 0)"
done
((findings == 0)) || { echo "$findings finding(s): see build-fuzz/findings/ (reproduce: build-fuzz/fuzz/fuzz_TARGET FILE)" >&2; exit 1; }
