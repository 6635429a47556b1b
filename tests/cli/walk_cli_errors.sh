#!/usr/bin/env bash
# The `walk` command line on bad input: non-zero exit, a message naming the file (and line or key), and no
# bundle left behind. Usage: walk_cli_errors.sh WALK_BINARY SOURCE_DIR
set -uo pipefail
walk=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passed=0

# expect_failure NAME OUTPUT_BUNDLE PATTERN... : runs the rest after `--` and checks exit code and message.
check() {
  local name=$1 bundle=$2
  shift 2
  local patterns=()
  while [ "$1" != "--" ]; do patterns+=("$1"); shift; done
  shift
  local out
  out=$("$@" 2>&1)
  local rc=$?
  local ok=1
  [ $rc -ne 0 ] || { echo "FAIL $name: exit code 0"; ok=0; }
  for p in "${patterns[@]}"; do
    grep -qF -- "$p" <<<"$out" || { echo "FAIL $name: message lacks '$p': $out"; ok=0; }
  done
  if [ -n "$bundle" ] && ls "$bundle"* >/dev/null 2>&1; then echo "FAIL $name: left $(ls "$bundle"*)"; ok=0; fi
  if [ $ok -eq 1 ]; then passed=$((passed + 1)); echo "ok   $name"; else failures=$((failures + 1)); fi
}

scene() {  # scene NAME MODEL_PATH [UNITS]
  printf '[model]\nfile = "%s"\nunits = "%s"\n[luminaires.per_group]\n' "$2" "${3:-m}" >"$tmp/$1.toml"
  echo "$tmp/$1.toml"
}

check "missing scene file" "$tmp/a.walk" "no_such.toml" -- "$walk" compile "$tmp/no_such.toml" -o "$tmp/a.walk"
check "missing model file" "$tmp/b.walk" "nowhere.dxf" -- "$walk" compile "$(scene b "$tmp/nowhere.dxf")" -o "$tmp/b.walk"
check "unknown unit" "$tmp/c.walk" "c.toml:3" "model.units" "parsec" -- \
  "$walk" compile "$(scene c "$src/../shared/data/eplus-house-doors/house.dxf" parsec)" -o "$tmp/c.walk"

head -c 30000 "$src/../shared/data/eplus-house-doors/house.dxf" >"$tmp/truncated.dxf"
check "truncated DXF" "$tmp/d.walk" "truncated.dxf:" -- "$walk" compile "$(scene d "$tmp/truncated.dxf")" -o "$tmp/d.walk"

awk 'face == 1 && done == 0 && prev == " 20" { $0 = " twelve"; done = 1 } /^3DFACE$/ { face = 1 } { prev = $0; print }' \
  "$src/../shared/data/eplus-house-doors/house.dxf" >"$tmp/garbled.dxf"
line=$(grep -n '^ twelve$' "$tmp/garbled.dxf" | cut -d: -f1)
check "non-numeric coordinate" "$tmp/e.walk" "garbled.dxf:$line" -- "$walk" compile "$(scene e "$tmp/garbled.dxf")" -o "$tmp/e.walk"

printf '  0\nSECTION\n  2\nENTITIES\n  0\nENDSEC\n  0\nEOF\n' >"$tmp/empty.dxf"
check "empty model" "$tmp/f.walk" "empty.dxf" -- "$walk" compile "$(scene f "$tmp/empty.dxf")" -o "$tmp/f.walk"

# A good bundle, then one byte flipped in its middle.
if "$walk" compile "$src/config/scenes/house.toml" -o "$tmp/good.walk" >/dev/null 2>&1 && "$walk" inspect "$tmp/good.walk" >/dev/null; then
  passed=$((passed + 1)); echo "ok   good bundle compiles and inspects"
else
  failures=$((failures + 1)); echo "FAIL good bundle"
fi
# `walk probe` on the good bundle: a reading in lux per circuit and mixed; a wrong dimmer count names the
# circuits.
probe_out=$("$walk" probe "$tmp/good.walk" --at 0,0,0.8 --rays 256 2>&1)
if grep -q "^mix: [0-9.]* lx" <<<"$probe_out" && [ "$(grep -c " 1.00 " <<<"$probe_out")" -eq 16 ]; then
  passed=$((passed + 1)); echo "ok   probe reads lux per circuit"
else
  failures=$((failures + 1)); echo "FAIL probe: $probe_out"
fi
check "probe: dimmer count" "" "--dimmers gives 2 levels" "16 circuits" -- \
  "$walk" probe "$tmp/good.walk" --at 0,0,0.8 --dimmers 1,0.5
check "probe: zero normal" "" "--normal must be a finite, non-zero direction" -- \
  "$walk" probe "$tmp/good.walk" --at 0,0,0.8 --normal 0,0,0
size=$(stat -c %s "$tmp/good.walk")
printf '\x5a' | dd of="$tmp/good.walk" bs=1 seek=$((size / 2)) conv=notrunc status=none
check "flipped byte" "" "good.walk" "corrupt bundle" -- "$walk" inspect "$tmp/good.walk"

# `walk gen building` on bad options: a clear error naming the option, and no scene folder written.
data="$src/../shared/data"
check "gen: unknown plan" "$tmp/g1" "--plan" "castle" "known: apartment" -- \
  "$walk" gen building -o "$tmp/g1" --plan castle --data "$data"
check "gen: zero storeys" "$tmp/g2" "--storeys" "at least 1" -- "$walk" gen building -o "$tmp/g2" --storeys 0 --data "$data"
check "gen: density that cannot fit" "$tmp/g3" "--furnish" "objects per square metre" -- \
  "$walk" gen building -o "$tmp/g3" --furnish 8 --data "$data"
check "gen: unknown preset" "$tmp/g4" "--size" "XL" -- "$walk" gen building -o "$tmp/g4" --size XL --data "$data"
check "gen: missing data" "$tmp/g5" "floorplan.dxf" "--data" -- "$walk" gen building -o "$tmp/g5" --data "$tmp/nowhere"

echo "$passed passed, $failures failed"
[ $failures -eq 0 ]
