#!/bin/bash
# Two builds of isodel, interleaved on the same volumes: `isodel mesh` at eps 0.5 voxel, uniform
# and `--adaptive --adaptive-field input`, 2 threads, medians over REPS runs of the mesh's own
# seconds (--stats: total minus read and write) and of its facet-loop scan. Prints a table.
#
#   tools/bench/ab_builds.sh BEFORE_BUILD_DIR AFTER_BUILD_DIR [DATA_DIR] [SPHERE_VDB] [REPS]
#
# A build dir holds bin/isodel and lib/ (copy one aside before rebuilding). SPHERE_VDB: the
# radius-60 level-set sphere of docs/benchmarks.md (optional; grid name "sphere").
set -eu
A=$1 B=$2 D=${3:-../shared/data} S=${4:-} REPS=${5:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
vols="$D/levelset/bunny.vdb:0:below: $D/analytic/torus.vdb:0:below: $D/analytic/tangle_cube.vdb:0:below: $D/ct/skull_2.9.vdb:2.9:above: $D/analytic/nested_spheres.vdb:0:below:"
[ -n "$S" ] && vols="$S:0:below:sphere $vols"
for rep in $(seq "$REPS"); do
    for v in $vols; do
        IFS=: read -r p iso inside g <<<"$v"
        n=$(basename "$p" .vdb)
        gopt=()
        [ -n "$g" ] && gopt=(--grid "$g")
        for mode in uniform input; do
            opt=()
            [ $mode = input ] && opt=(--adaptive --adaptive-field input)
            for ab in before after; do
                dir=$A
                [ $ab = after ] && dir=$B
                LD_LIBRARY_PATH=$dir/lib "$dir/bin/isodel" mesh "$p" -o "$out/m.ply" --iso "$iso" --inside "$inside" \
                    "${gopt[@]}" --eps-voxels 0.5 "${opt[@]}" --quiet --stats "$out/s.json"
                python3 -c "
import json; s = json.load(open('$out/s.json')); t = s['seconds']
print('$n', '$mode', '$ab', t['total'] - t.get('read', 0) - t.get('write', 0),
      s['refinement_seconds'].get('facet_loops', 0), s['counts']['vertices'])" >>"$out/runs.txt"
            done
        done
    done
done
python3 - "$out/runs.txt" <<'EOF'
import collections, statistics, sys
d, keys = collections.defaultdict(list), []
for line in open(sys.argv[1]):
    v, m, ab, t, f, n = line.split()
    d[(v, m, ab)].append((float(t), float(f), int(n)))
    if (v, m) not in keys:
        keys.append((v, m))
print("| volume, mode | before: s (facet loops s) | after: s (facet loops s) | after / before | vertices before → after |")
print("| --- | --- | --- | ---: | --- |")
for v, m in keys:
    b, a = d[(v, m, 'before')], d[(v, m, 'after')]
    bt, at = statistics.median(x[0] for x in b), statistics.median(x[0] for x in a)
    bf, af = statistics.median(x[1] for x in b), statistics.median(x[1] for x in a)
    print(f"| {v}, {m} | {bt:.2f} ({bf:.2f}) | {at:.2f} ({af:.2f}) | {at / bt:.2f} | {b[0][2]:,} → {a[0][2]:,} |")
EOF
