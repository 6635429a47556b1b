#!/usr/bin/env bash
# Compares `walk` binaries on `walk bench rays`, the way docs/RAYCAST.md measures every change: the binaries
# run in turn, the order reversed each round (this machine's speed drifts by 10-15 % over minutes), and each
# binary's best rate per model and ray set is divided by Embree's best in that binary's own runs.
#
#   scripts/compare-ray-builds.sh "OLD_WALK NEW_WALK ..." [models] [sets] [rays] [rounds] [threads]
#
# Prints CSV: model, set, each binary's best Mrays/s, then each binary's ratio to Embree.
set -euo pipefail
binaries=$1
models=${2:-house,office,tower,e1m1,dm1}
sets=${3:-primary,radiosity,occlusion}
rays=${4:-200000}
rounds=${5:-4}
threads=${6:-1}
read -ra list <<<"$binaries"
for round in $(seq "$rounds"); do
  order=("${list[@]}")
  if ((round % 2 == 0)); then
    order=()
    for ((i = ${#list[@]} - 1; i >= 0; i--)); do order+=("${list[i]}"); done
  fi
  for bin in "${order[@]}"; do
    "$bin" bench rays --models "$models" --sets "$sets" --casters axial,embree --threads "$threads" \
      --rays "$rays" --repeat 2 2>/dev/null | tail -n +2 | awk -F, -v b="$bin" '{print b "," $1 "," $4 "," $7 "," $11}'
  done
done | python3 -c '
import collections, sys
bins = sys.argv[1].split()
best = collections.defaultdict(float)
for line in sys.stdin:
    b, model, caster, ray_set, rate = line.strip().split(",")
    best[(b, model, ray_set, caster)] = max(best[(b, model, ray_set, caster)], float(rate))
print("model,set," + ",".join(bins) + "," + ",".join("ratio " + b for b in bins))
for model, ray_set in sorted({(m, s) for _, m, s, _ in best}):
    rates = [best[(b, model, ray_set, "axial")] for b in bins]
    ratios = [r / best[(b, model, ray_set, "embree")] for r, b in zip(rates, bins)]
    print(f"{model},{ray_set}," + ",".join(f"{r:.2f}" for r in rates) + "," + ",".join(f"{q:.3f}" for q in ratios))
' "$binaries"
