#!/bin/sh
# Time and peak memory of each refusal of hostile input (issue 28): every case is one compile (or a walkd
# check) of a small room made bad in one way, run under /usr/bin/time. Prints CSV: case, exit status,
# wall seconds, peak resident MiB, whether a bundle was written, and the first error or warning line.
# Usage: bench/refusals.sh   (WALK=path/to/walk to use another build)
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
walk=${WALK:-$here/build/tools/walk}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT INT TERM

room() {  # $1: extra OBJ lines, $2: extra [model] TOML, $3: [lighting] and later tables
  printf 'newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n' > "$dir/room.mtl"
  printf 'mtllib room.mtl\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nv 0 0 3\nv 4 0 3\nv 4 4 3\nv 0 4 3\n' > "$dir/room.obj"
  printf 'v 1.5 1.5 2.95\nv 1.5 2.5 2.95\nv 2.5 2.5 2.95\nv 2.5 1.5 2.95\n' >> "$dir/room.obj"
  printf 'usemtl wall\nf 1 2 3 4\nf 1 4 8 5\nf 2 6 7 3\nf 1 5 6 2\nf 4 3 7 8\nf 5 8 7 6\nusemtl lamp\nf 9 10 11 12\n' >> "$dir/room.obj"
  printf '%b' "$1" >> "$dir/room.obj"
  printf '[model]\nfile = "room.obj"\nunits = "m"\nup = "z"\n%b[lighting]\ngrid = 0.5\nrays_per_watt = 100\n%b' \
    "$2" "$3" > "$dir/scene.toml"
}

# A DXF whose nested INSERT arrays expand to 100^4 = 1e8 faces (the limit is 2e7).
bomb() {
  {
    printf '0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nB0\n10\n0\n20\n0\n30\n0\n'
    printf '0\n3DFACE\n8\nwalls\n10\n0\n20\n0\n30\n0\n11\n1\n21\n0\n31\n0\n12\n1\n22\n1\n32\n0\n13\n0\n23\n1\n33\n0\n'
    printf '0\nENDBLK\n'
    for i in 1 2 3 4; do
      printf '0\nBLOCK\n2\nB%d\n10\n0\n20\n0\n30\n0\n0\nINSERT\n2\nB%d\n8\nwalls\n10\n0\n20\n0\n30\n0\n' "$i" $((i - 1))
      printf '70\n10\n71\n10\n44\n2\n45\n2\n0\nENDBLK\n'
    done
    printf '0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nB4\n8\nwalls\n10\n0\n20\n0\n30\n0\n0\nENDSEC\n0\nEOF\n'
  } > "$dir/bomb.dxf"
  printf '[model]\nfile = "bomb.dxf"\nunits = "m"\n[lighting]\ngrid = 0.5\n' > "$dir/scene.toml"
}

run() {  # $1: case name; the rest: the command
  name=$1
  shift
  rm -f "$dir/out.walk"
  /usr/bin/time -f '%e %M' -o "$dir/time" "$@" > "$dir/log" 2>&1
  status=$?
  read -r wall kib <<EOT
$(tail -n 1 "$dir/time")
EOT
  line=$(grep -m1 -E 'error:|\[warning\]' "$dir/log" | sed 's/^\[[^]]*\] //; s/"/'"'"'/g' | cut -c1-200)
  written=no
  [ -f "$dir/out.walk" ] && written=yes
  printf '%s,%s,%s,%.1f,%s,"%s"\n' "$name" "$status" "$wall" "$(awk "BEGIN { print $kib / 1024 }")" "$written" "$line"
}
compile() { run "$1" "$walk" --progress none compile "$dir/scene.toml" -o "$dir/out.walk" -f; }

echo "case,exit,wall_s,peak_mib,bundle_written,message"
room '' '' ''; compile baseline_room
room '' '' '' && sed -i 's/rays_per_watt = 100/rays_per_watt = 1e9/' "$dir/scene.toml"; compile rays_per_watt_1e9
room '' '' '' && sed -i 's/grid = 0.5/grid = 0.02/; s/units = "m"/scale = 1000.0/' "$dir/scene.toml"
compile patches_over_memory  # the room drawn in km: 4 km walls on a 2 cm grid
room '' '' '[visibility]\nmethod = "sampled"\nsample_points = 1000000\nrays_per_point = 100000\n'
compile sampled_pvs_rays
room 'usemtl wall\nv 1e20 0 0\nf 1 2 13\n' '' ''; compile coordinate_1e20
room 'usemtl wall\nv 1e308 0 0\nf 1 2 13\n' '' ''; compile coordinate_1e308
room 'usemtl wall\nv nan 0 0\nf 1 2 13\n' '' ''; compile coordinate_nan
room 'usemtl wall\nv 1000000 0 0\nv 1000001 0 0\nv 1000001 1 0\nf 13 14 15\n' '' ''; compile stray_face_1000km
bomb; compile nested_insert_bomb
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n' > "$dir/room.obj"
printf '[model]\nfile = "room.obj"\nunits = "m"\n' > "$dir/scene.toml"; compile nothing_to_draw
room '' '' '' && sed -i 's/mtllib room.mtl/mtllib absent.mtl/' "$dir/room.obj" && rm "$dir/room.mtl"
compile missing_mtl
room '' '' '' && rm "$dir/room.obj" && mkdir "$dir/room.obj"; compile model_is_a_folder
rmdir "$dir/room.obj"
