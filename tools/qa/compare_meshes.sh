#!/bin/bash
# compare_meshes.sh OLD_ISODEL|OLD_DIR NEW_ISODEL [OUT_DIR] [EPS_VOXELS]
# Meshes every .vdb volume of ../shared/data/manifest.json (entries without expect_error) with
# two isodel executables at eps (default 0.5 voxel, 2 threads), and the tetrahedra of three
# volumes (1hpv_molmap inside, torus both, eight outside at 1 thread), then compares the files
# byte for byte: the check that a change not meant to change meshes did not. Exit 1 on any
# difference or failure. OLD may be a directory of meshes an earlier run wrote (OUT_DIR/new of
# the base commit), so the base need not be rebuilt.
set -u
OLD=$1; NEW=$2; OUT=${3:-/tmp/isodel-compare}; EPS=${4:-0.5}
DATA=$(cd "$(dirname "$0")/../../../shared/data" && pwd) || { echo "../shared/data not found"; exit 2; }
mesh_all() { # BIN DIR
  mkdir -p "$2"
  python3 - "$DATA" <<'PY' | while read -r f iso inside grid; do
import json, sys
for e in json.load(open(sys.argv[1] + "/manifest.json")):
    if e.get("format") == "vdb" and not e.get("expect_error"):
        print(e["file"], e["isovalue"], e.get("inside") or "above", e.get("grid_name") or "-")
PY
    name=$(echo "$f" | tr '/' '_'); g=(); [ "$grid" != "-" ] && g=(--grid "$grid")
    timeout 600 "$1" mesh "$DATA/$f" -o "$2/${name%.vdb}.ply" --iso "$iso" --inside "$inside" --eps-voxels "$EPS" \
      --threads 2 "${g[@]}" --quiet || echo "FAILED $f"
  done
  "$1" mesh "$DATA/protein/1hpv_molmap_6A_2A.vdb" -o "$2/molmap.ply" --tets "$2/molmap.mesh" --iso 4.75 \
    --inside above --eps-voxels "$EPS" --threads 2 --quiet || echo "FAILED molmap tets"
  "$1" mesh "$DATA/analytic/torus.vdb" -o "$2/torus.ply" --tets "$2/torus.vtu" --region both --iso 0 \
    --inside below --eps-voxels "$EPS" --threads 2 --quiet || echo "FAILED torus tets"
  "$1" mesh "$DATA/levelset/eight.vdb" -o "$2/eight.ply" --tets "$2/eight.msh" --region outside --iso 0 \
    --inside below --eps-voxels "$EPS" --threads 1 --quiet || echo "FAILED eight tets"
}
rm -rf "$OUT"
if [ -d "$OLD" ]; then OLD_DIR=$OLD; else OLD_DIR=$OUT/old; mesh_all "$OLD" "$OLD_DIR"; fi
mesh_all "$NEW" "$OUT/new"
same=0; diff=0
for f in "$OLD_DIR"/*; do
  if cmp -s "$f" "$OUT/new/$(basename "$f")"; then same=$((same + 1)); else diff=$((diff + 1)); echo "DIFFERS $(basename "$f")"; fi
done
echo "$same files identical, $diff differ"
[ "$diff" -eq 0 ]
