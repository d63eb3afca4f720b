#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# in build-fuzz/ and runs each for SECONDS (default 30) from its seed corpus fuzz/corpus/<target>/.
# A crash, a sanitizer report or an input slower than 10 s fails the run; libFuzzer writes the
# input to build-fuzz/findings/. New inputs go to build-fuzz/corpus/<target>/, not the repository.
# With GRIP_FUZZ_RUNS=N (CI's short run) each target starts from seed 1 and the committed corpus
# alone (new inputs go to a folder emptied first) and runs at most N inputs (0: the seed corpus
# alone) within SECONDS.
# Usage: [GRIP_FUZZ_RUNS=N] scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
source "$root/scripts/instrumented-tree.sh"
seconds="${1:-30}"
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(fuzz_scene fuzz_job fuzz_candidates fuzz_mesh fuzz_tet_mesh fuzz_gripper_description fuzz_dataset
                                        fuzz_dataset_values)
"$root/scripts/install-deps.sh"
configure_instrumented_tree OFF
cmake --build "$build" --parallel "$(nproc)" --target "${targets[@]}"

# Leaks are findings too, except inside the system libraries listed in lsan.supp (HDF5 leaks
# a few bytes when it fails to open a damaged file). An allocation over 512 MB fails, as on a
# small machine: HDF5 then reports an error (it would otherwise allocate whatever size a damaged
# file claims), and grip code that lets std::bad_alloc out is a finding.
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1:max_allocation_size_mb=512"
export LSAN_OPTIONS="suppressions=$root/scripts/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/scripts/sanitize/ubsan.supp"
mkdir -p "$build/findings" "$build/tmp"
export TMPDIR="$build/tmp"  # where the targets write each input as a file
failed=()
runs=()
corpus="$build/corpus"
if [[ -n "${GRIP_FUZZ_RUNS:-}" ]]; then
  runs=(-seed=1 -runs="$GRIP_FUZZ_RUNS")
  corpus="$build/corpus-short"
  rm -rf "$corpus"
fi
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target"
  echo "fuzz: $target for $seconds s ${runs[*]}" >&2
  if ! "$build/fuzz/$target" -max_total_time="$seconds" "${runs[@]}" -timeout=10 \
       -rss_limit_mb=4096 -artifact_prefix="$build/findings/$target-" -print_final_stats=1 \
       "$corpus/$target" "$root/fuzz/corpus/$target" 2>"$build/$target.log"; then
    failed+=("$target")
    tail -n 40 "$build/$target.log" >&2
  fi
  grep -aE "^stat::number_of_executed_units|^#[0-9]+ +DONE" "$build/$target.log" >&2 || true
done
rm -rf "$build/tmp"
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "fuzz: findings in ${failed[*]} (inputs in $build/findings/)" >&2
  exit 1
fi
echo "fuzz: no findings" >&2
