#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang, ASan + UBSan) and fuzzes each for SECONDS from its seed corpus,
# copied to a scratch folder so that the repository's corpus does not grow.
# Usage: scripts/fuzz.sh [--ci] [--jobs N] [SECONDS] [TARGET...]   (targets: raw nrrd ... as in fuzz/fuzz_TARGET.cpp;
#   default all)
#   --ci      CI's bounded run: 45 s per target unless SECONDS is given, --jobs $(nproc), and every finding's
#             report printed in full (CI keeps no files). Seed inputs that fail fail the run; findings of the
#             exploration are reported and fail it only with VR_FUZZ_STRICT=1 (below).
#   --jobs N  targets fuzzed side by side, each on one core (default 1: a fair share of a shared machine).
# The build folder is $VR_FUZZ_BUILD (default build-fuzz/). Prints per target the executions, the coverage the seeds
# reached and what fuzzing added to it (cov: code edges, ft: features) and the corpus growth; exits non-zero on any
# finding (crash, sanitizer report, leak, timeout, out of memory), whose inputs and logs are kept in
# BUILD/findings/TARGET/. A fixed finding's input goes to fuzz/regressions/ (tests/load_fuzz_regressions_test.cpp).
# Why CI does not fail on what exploration finds: its inputs depend on chance (the targets' coverage is not
# reproducible, as VTK and TBB run threads), so a bug found in one CI run would block changes unrelated to it, while
# the next run may miss it. Everything found stays fatal where it is reproducible: the seeds here, the regression
# inputs in the suite (scripts/sanitize.sh runs it under ASan + UBSan).
set -euo pipefail
ci=0
parallel=1
seconds=
while (($#)); do
  case $1 in
    --ci) ci=1; parallel=$(nproc); shift ;;
    --jobs) parallel=$2; shift 2 ;;
    *) break ;;
  esac
done
if [[ ${1:-} =~ ^[0-9]+$ ]]; then seconds=$1; shift; fi
seconds=${seconds:-$( ((ci)) && echo 45 || echo 60)}
cd "$(dirname "$0")/.."
build=${VR_FUZZ_BUILD:-build-fuzz}
bash scripts/install-deps.sh clang libclang-rt-14-dev  # libclang-rt-14-dev: libFuzzer and the sanitizer runtimes

start=$(date +%s)
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVR_FUZZ=ON \
  -DVR_SANITIZE=ON >/dev/null
if (($#)); then
  targets=("$@")
else
  targets=($(ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||'))
fi
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
echo "fuzz.sh: build $(($(date +%s) - start)) s; fuzzing ${#targets[@]} targets for $seconds s each, $parallel at once"

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

# "EDGES FEATURES" that TARGET's inputs in FOLDER reach; fails, its log in LOG, when one of the inputs fails.
coverage() {
  fuzz "$build"/fuzz/fuzz_"$1" -runs=0 -artifact_prefix="$scratch/" "$2" >"$3" 2>&1 || return 1
  grep -o 'INITED cov: [0-9]* ft: [0-9]*' "$3" | awk '{print $3, $5}'
}

# Fuzzes one target and writes its line of the table to $scratch/TARGET.row.
fuzz_target() {
  local t=$1 work=$scratch/$1 found=0 began
  mkdir -p "$work/corpus" "$work/artifacts"
  cp fuzz/corpus/"$t"/* "$work/corpus/"
  local seeds=$(ls "$work/corpus" | wc -l)
  began=$(date +%s)
  # Fork mode keeps fuzzing past a finding (each is saved), so that one known bug does not end the run; new inputs
  # go to the (scratch) corpus.
  fuzz "$build"/fuzz/fuzz_"$t" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$seconds" -max_len=65536 -artifact_prefix="$work/artifacts/" "$work/corpus" \
    >"$work/log" 2>&1 || true
  # Fork mode may blame an input for what another did: a finding is an input that fails again on its own.
  rm -rf "$build"/findings/"$t"
  for input in "$work"/artifacts/*; do
    [[ -f $input ]] || continue
    if ! fuzz "$build"/fuzz/fuzz_"$t" "$input" >"$input.log" 2>&1; then
      found=$((found + 1))
      mkdir -p "$build"/findings/"$t"
      cp "$input" "$input.log" "$build"/findings/"$t"/
    fi
  done
  # Fork mode's progress lines ("#EXECUTIONS: cov: ...") count coverage their own way: both corpora are measured
  # alike, by running them once (-runs=0).
  local executions=$(grep -oE '^#[0-9]+: cov:' "$work/log" | tail -1 | tr -dc '0-9')
  local before after
  if before=$(coverage "$t" fuzz/corpus/"$t" "$work/seeds.log"); then before=($before); else
    before=()
    mkdir -p "$build"/findings/"$t"
    cp "$work/seeds.log" "$build"/findings/"$t"/seeds.log
    echo 1 >"$scratch/$t.seeds_failed"
  fi
  after=($(coverage "$t" "$work/corpus" "$work/corpus.log"))
  local cov="${before[0]:-?}+$((${after[0]:-0} - ${before[0]:-0}))"
  local ft="${before[1]:-?}+$((${after[1]:-0} - ${before[1]:-0}))"
  printf '%-18s %12s %8s %12s %12s %6s -> %-6s %s\n' "$t" "${executions:-?}" "$(($(date +%s) - began))" "$cov" "$ft" \
    "$seeds" "$(ls "$work/corpus" | wc -l)" "$( ((found)) && echo "$found: $build/findings/$t/" || echo 0)" \
    >"$scratch/$t.row"
  echo "$found" >"$scratch/$t.found"
}

for t in "${targets[@]}"; do
  fuzz_target "$t" &
  while (($(jobs -rp | wc -l) >= parallel)); do wait -n || true; done
done
wait

printf '%-18s %12s %8s %12s %12s %16s  %s\n' target executions seconds cov+new ft+new corpus findings
findings=0 seeds_failed=0
for t in "${targets[@]}"; do
  cat "$scratch/$t.row"
  findings=$((findings + $(cat "$scratch/$t.found")))
  [[ -f $scratch/$t.seeds_failed ]] && seeds_failed=$((seeds_failed + 1)) && echo "fuzz.sh: $t: a seed input fails"
done
((findings + seeds_failed)) || exit 0
if ((ci)); then  # the reports themselves, as CI keeps no files
  for log in "$build"/findings/*/*.log; do
    echo "=== $log"
    grep -v '^INFO:\|^Running\|^Executed' "$log" | tail -60
  done
fi
echo "$findings finding(s): see $build/findings/ (reproduce: $build/fuzz/fuzz_TARGET FILE)" >&2
if ((ci && !seeds_failed)) && [[ ${VR_FUZZ_STRICT:-0} != 1 ]]; then
  echo "fuzz.sh: the findings above came from exploration: reported, not failing CI (see the top of this script);" \
    "fix each and keep its input in fuzz/regressions/" >&2
  exit 0
fi
exit 1
