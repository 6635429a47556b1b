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
flags=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -I"$src"
       -isystem /usr/include/polyclipping)
common=("$src"/model/error.cpp "$src"/model/model.cpp)
dxf=("$src"/compiler/import/dxf_{tokenizer,document,geometry,reader}.cpp)
map=("$src"/compiler/import/{map_parser,map_reader,brush_geometry,brush_csg}.cpp)
build() {  # name sources...: rebuilt only when a source is newer than the binary
  local name=$1
  shift
  local stale=0
  for f in "$@" "$src"/fuzz/*.hpp "$src"/compiler/import/*.hpp "$src"/model/*.hpp "$src"/devices/*/*.hpp "$src"/compiler/scene/*.hpp "$src"/compiler/photometry/*.hpp "$src"/firmware-host/*.hpp; do
    [ -f "$f" ] && [ "$f" -nt "$out/$name" ] && stale=1
  done
  [ -x "$out/$name" ] && [ $stale = 0 ] && return 0
  echo "run_fuzzers: building $name"
  "$cxx" "${flags[@]}" "$@" -o "$out/$name"
}
build dxf_fuzzer "$src"/fuzz/dxf_fuzzer.cpp "${dxf[@]}" "${common[@]}"
build map_fuzzer "$src"/fuzz/map_fuzzer.cpp "${map[@]}" "${common[@]}"
build bundle_fuzzer "$src"/fuzz/bundle_fuzzer.cpp "$src"/model/bundle.cpp "${common[@]}" -lz
build csv_trace_fuzzer "$src"/fuzz/csv_trace_fuzzer.cpp "$src"/devices/mock/csv_trace.cpp "${common[@]}"
build hid_report_fuzzer "$src"/fuzz/hid_report_fuzzer.cpp "$src"/devices/hid/report_layout.cpp -lfmt
# -DNDEBUG as the shipped (RelWithDebInfo) build: toml++'s internal debug asserts fire on inputs its parser
# then rejects with a located error (a key starting with '='), which is what `walk` does and reports.
# -fno-sanitize=unreachable: toml++ 3.3's whitespace test reaches TOML_UNREACHABLE for code points in
# U+00A1..U+0499, U+2C3E..U+3037 and U+FB26..U+FEFE, a defect in the system header that we cannot mend and
# that the shipped build survives (SceneConfigTest.NonAsciiNamesAndCommentsLoadAsWritten); everything else
# stays checked.
photometry=("$src"/compiler/photometry/{photometry_file,ies_reader,eulumdat_reader,symmetry,colour_temperature}.cpp
            "$src"/model/intensity_distribution.cpp "$src"/common/hash.cpp)
build scene_toml_fuzzer -DNDEBUG -fno-sanitize=unreachable "$src"/fuzz/scene_toml_fuzzer.cpp "$src"/compiler/scene/{scene_config,units}.cpp "$src"/model/toml_table.cpp \
  "$src"/compiler/partition/visibility_config.cpp "${photometry[@]}" \
  "${common[@]}" -ltomlplusplus -lspdlog -lfmt -lxxhash
# OBJ through the mesh reader: assimp (Debian's, uninstrumented) parses; our conversion of its scene is checked.
build obj_fuzzer "$src"/fuzz/obj_fuzzer.cpp "$src"/compiler/import/{mesh_reader,texture_image,uv_fit}.cpp \
  "$src"/compiler/cleanup/stray_geometry.cpp "$src"/model/srgb.cpp "${common[@]}" -lassimp -lpng -ljpeg -lspdlog -lfmt
build modbus_registers_fuzzer "$src"/fuzz/modbus_registers_fuzzer.cpp "$src"/devices/modbus/register_levels.cpp -lfmt
# The kiosk config goes through toml++ too: the same two flags, for the same reasons.
build kiosk_toml_fuzzer -DNDEBUG -fno-sanitize=unreachable "$src"/fuzz/kiosk_toml_fuzzer.cpp \
  "$src"/firmware-host/{kiosk_config,device_config}.cpp "$src"/devices/hid/report_layout.cpp "$src"/devices/devices.cpp \
  "$src"/model/{error,toml_table}.cpp -ltomlplusplus -lfmt
status=0
for kind in dxf map bundle csv_trace hid_report modbus_registers scene_toml kiosk_toml obj; do
  corpus="$out/corpus-$kind"
  mkdir -p "$corpus" "$out/artifacts-$kind"
  cp -n "$src"/fuzz/corpus/$kind/* "$corpus"/ 2>/dev/null || true
  echo "run_fuzzers: ${kind}_fuzzer for ${seconds} s"
  if ! (cd "$out" && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$src/fuzz/lsan.supp" UBSAN_OPTIONS=print_stacktrace=1 \
        ./${kind}_fuzzer -seed=1 -runs=$((seconds * 5000)) -max_total_time="$seconds" -timeout=60 -report_slow_units=60 -rss_limit_mb=2048 -max_len=65536 \
        $([ -f "$src/fuzz/$kind.dict" ] && echo "-dict=$src/fuzz/$kind.dict") -artifact_prefix="$out/artifacts-$kind/" -print_final_stats=1 "$corpus" > "$out/${kind}_fuzzer.log" 2>&1); then
    echo "run_fuzzers: ${kind}_fuzzer FAILED; the last lines of $out/${kind}_fuzzer.log:"
    tail -40 "$out/${kind}_fuzzer.log"
    # The failing input itself, so that a failure seen only in CI's log can be replayed anywhere:
    # base64 -d > input && ./${kind}_fuzzer input
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
