#!/bin/bash
# The speed targets are stated on "protein volumes of ~128^3"; ../shared/data has none that size.
# This makes one (the blurred-atom density of PDB 1HPV at 0.45 A: 125 x 107 x 144, the same
# construction as the shared 1hpv_blobby_1A at 1 A) and runs compare_bench on it.
#
#   tools/bench/protein_128_bench.sh [compare_bench options...]
#   e.g. tools/bench/protein_128_bench.sh --eps-voxels 0.1 --reps 3 --methods i1,i2,ms,vdb,dt
#
# Needs (Debian): python3-numpy python3-mrcfile pymol-data (for /usr/share/pymol/data/tut/1hpv.pdb),
# and a build (build/bin/isodel, build/bin/compare_bench).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
dir=${ISODEL_BENCH_DIR:-/tmp/isodel_protein_128}
pdb=/usr/share/pymol/data/tut/1hpv.pdb
[ -f "$pdb" ] || { echo "protein_128_bench.sh: $pdb missing (apt-get install pymol-data)" >&2; exit 2; }
mkdir -p "$dir/protein"
if [ ! -f "$dir/protein/1hpv_blurred_0.45A.vdb" ]; then
  /usr/bin/python3 "$here/tools/data/blurred_atoms_mrc.py" "$pdb" 0.45 "$dir/1hpv_blurred_0.45A.mrc"
  "$here/build/bin/isodel" convert "$dir/1hpv_blurred_0.45A.mrc" -o "$dir/protein/1hpv_blurred_0.45A.vdb"
fi
cat > "$dir/manifest.json" <<'J'
[{"file": "protein/1hpv_blurred_0.45A.vdb", "format": "vdb", "grid_name": "density", "dims": [125, 107, 144],
  "isovalue": 1.0, "inside": "above", "category": "protein", "kind": "protein"}]
J
exec "$here/build/bin/compare_bench" --data "$dir" --all "$@"
