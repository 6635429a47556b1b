#!/bin/sh
# Cost of progress output: compiles one scene with --progress none, bar (on a pseudo-terminal made by
# script(1)) and log, alternating, ROUNDS times, and prints CSV rows and each style's ratio of median wall
# time to none's. Usage: bench/progress-overhead.sh [SCENE.toml] [ROUNDS]   (default: quake-dm1, 3)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
walk=${WALK:-$here/build/tools/walk}
scene=${1:-$here/config/scenes/quake-dm1.toml}
rounds=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT INT TERM
echo "round,style,wall_s,user_s"
for r in $(seq "$rounds"); do
  for style in none bar log; do
    rm -f "$out/x.walk"  # a bundle left there would be reused, stage by stage
    cmd="$walk compile $scene -o $out/x.walk --progress $style"
    if [ "$style" = bar ]; then cmd="script -qfec '$cmd' /dev/null"; fi
    /usr/bin/time -f "%e %U" -o "$out/time" sh -c "$cmd" >"$out/$style.$r.txt" 2>&1
    read -r wall user <"$out/time"
    echo "$r,$style,$wall,$user" | tee -a "$out/rows"
  done
done
median() { grep ",$1," "$out/rows" | cut -d, -f3 | sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
none=$(median none)
for style in bar log; do
  echo "ratio $style/none (median wall): $(echo "$(median "$style") $none" | awk '{ printf "%.3f", $1 / $2 }')"
done
