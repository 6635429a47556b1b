#!/usr/bin/env bash
# Sanitizer runs over the test suites, each in its own build folder beside the main one.
#   scripts/sanitize.sh quick BUILD  ASan+UBSan over the common, model and devices suites, TSan over the
#                                    devices suite (reader threads, Modbus poller and simulator, fault
#                                    tracker): CTest `sanitizers` runs this in CI.
#   scripts/sanitize.sh full BUILD   ASan+UBSan over every suite (GL included); tens of minutes on 2 cores.
# TSan stays on code without TBB: oneTBB from Debian is not instrumented, so TSan reports its own
# synchronisation as races (the compiler's parallel loops are checked by ASan and by their tests instead).
# Findings abort the test binary (-fno-sanitize-recover), so the run fails naming the report.
set -euo pipefail
mode=${1:?usage: sanitize.sh quick|full BUILD_DIR}
build=${2:?usage: sanitize.sh quick|full BUILD_DIR}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1

configure() {  # folder sanitizers [extra cmake args]
  local dir=$1 sanitizers=$2
  shift 2
  cmake -S "$source_dir" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWALK_SANITIZE="$sanitizers" \
    -DWALK_HARDENING=OFF -DWALK_DEBUG_INFO=lines "$@" >/dev/null  # reports need file:line only
}

case $mode in
  quick)
    configure "$build/sanitize-asan" address,undefined
    ninja -C "$build/sanitize-asan" -j"$jobs" walk_common_tests walk_model_tests walk_devices_tests
    for suite in common model devices; do
      echo "== ASan+UBSan: walk_${suite}_tests"
      "$build/sanitize-asan/tests/walk_${suite}_tests" --gtest_brief=1
    done
    configure "$build/sanitize-tsan" thread
    ninja -C "$build/sanitize-tsan" -j"$jobs" walk_devices_tests
    echo "== TSan: walk_devices_tests"
    "$build/sanitize-tsan/tests/walk_devices_tests" --gtest_brief=1
    ;;
  full)
    configure "$build/sanitize-full" address,undefined
    ninja -C "$build/sanitize-full" -j"$jobs"
    # The soak test is the one long test: under ASan its day takes far longer, so it runs two hours here.
    WALK_SOAK_HOURS=2 ctest --test-dir "$build/sanitize-full" -j"$jobs" --output-on-failure -E '^package_deb$'
    ;;
  *)
    echo "sanitize.sh: unknown mode '$mode' (quick or full)" >&2
    exit 2
    ;;
esac
echo "sanitize.sh $mode: no findings"
