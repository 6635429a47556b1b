#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into OUT and runs each for SECONDS on a copy of the
# committed seed corpus, with a fixed seed and run count: CI explores the same inputs (or, on a slower machine
# stopped by the time limit, a prefix of them) as the run that was checked before submitting.
# A hang is an input running past 60 s: ctest runs tests in parallel, and under ASan on a loaded machine an
# input with deep INSERT nesting was seen at 11 s (0.17 s in a release build), so 10 s would be a false alarm.
# Exit 0: no crash, no hang (-timeout), no rejection without file and line; 77: no
# clang with libFuzzer here (the caller skips). Usage: run_fuzzers.sh SOURCE_DIR OUT [SECONDS]
set -euo pipefail
src=$(cd "$1" && pwd)  # absolute: the fuzzers run from $out
out=$2
seconds=${3:-30}
cxx=${WALK_FUZZ_CXX:-clang++}
command -v "$cxx" >/dev/null 2>&1 || { echo "run_fuzzers: $cxx not found"; exit 77; }
mkdir -p "$out"
echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' > "$out/probe.cpp"
if ! "$cxx" -fsanitize=fuzzer "$out/probe.cpp" -o "$out/probe" 2>/dev/null; then
  echo "run_fuzzers: $cxx cannot link libFuzzer (install libclang-rt-14-dev)"
  exit 77
fi
# The targets and their sources are fuzz/CMakeLists.txt's: a clang build of this project with only the fuzzers
# built (shared sources compiled once, in parallel, rebuilt when a source or header changes).
cmake -S "$src" -B "$out/build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Fuzz -DCMAKE_CXX_FLAGS_FUZZ="-O1 -g" \
  -DWALK_BUILD_FUZZERS=ON -DWALK_BUILD_TESTS=OFF -DWALK_HARDENING=OFF > "$out/configure.log" 2>&1 ||
  { echo "run_fuzzers: configuring the fuzz build failed:"; tail -30 "$out/configure.log"; exit 1; }
echo "run_fuzzers: building the fuzzers"
ninja -C "$out/build" fuzzers
status=0
for kind in dxf map bundle csv_trace hid_report modbus_registers scene_toml kiosk_toml obj; do
  corpus="$out/corpus-$kind"
  mkdir -p "$corpus" "$out/artifacts-$kind"
  cp -n "$src"/fuzz/corpus/$kind/* "$corpus"/ 2>/dev/null || true
  echo "run_fuzzers: ${kind}_fuzzer for ${seconds} s"
  if ! (cd "$out" && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$src/fuzz/lsan.supp" UBSAN_OPTIONS=print_stacktrace=1 \
        "$out/build/fuzz/${kind}_fuzzer" -seed=1 -runs=$((seconds * 5000)) -max_total_time="$seconds" -timeout=60 -report_slow_units=60 -rss_limit_mb=2048 -max_len=65536 \
        $([ -f "$src/fuzz/$kind.dict" ] && echo "-dict=$src/fuzz/$kind.dict") -artifact_prefix="$out/artifacts-$kind/" -print_final_stats=1 "$corpus" > "$out/${kind}_fuzzer.log" 2>&1); then
    echo "run_fuzzers: ${kind}_fuzzer FAILED; the last lines of $out/${kind}_fuzzer.log:"
    tail -40 "$out/${kind}_fuzzer.log"
    # The failing input itself, so that a failure seen only in CI's log can be replayed anywhere:
    # base64 -d > input && build/fuzz/${kind}_fuzzer input
    for artifact in "$out"/artifacts-$kind/*; do
      [ -f "$artifact" ] || continue
      echo "run_fuzzers: input $(basename "$artifact") ($(stat -c %s "$artifact") bytes), base64:"
      head -c 8192 "$artifact" | base64 -w 0
      echo
    done
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$out/${kind}_fuzzer.log" | tail -2
  fi
done
exit $status
