#!/usr/bin/python3
"""Decimation then meshing on the leaves (paper Property IV), against meshing the same F densely.

For each (volume, iso, inside, tolerance, k): `isodel decimate`, `isodel mesh` of the adaptive
file (E on leaf edges, G from leaves, G' = leaf corners), `isodel resample` + `isodel mesh` of the
dense resampling (the same F on the unit lattice), and `isodel verify` of the adaptive mesh against
the adaptive interpolant. Prints one table; ratios are adaptive / dense from the same run.

  tools/bench/adaptive_bench.py [--bin build/bin] [--data ../shared/data] [--eps-voxels 0.5] [--filter bunny]
"""
import argparse, json, os, subprocess, sys, tempfile, time

CASES = [  # file, iso, inside, decimation tolerance (value units), k
    ("ct/skull_2.9.vdb", 2.9, "above", 0.27, 1),
    ("ct/skull_2.9.vdb", 2.9, "above", 0.27, 2),
    ("protein/1hpv_molmap_6A_2A.vdb", 4.75, "above", 0.5, 1),
    ("protein/1hpv_molmap_6A_2A.vdb", 4.75, "above", 0.5, 2),
    ("levelset/bunny.vdb", 0.0, "below", 0.002, 2),  # ~1/4 voxel; the narrow band is +-3 voxels
    ("@torus", 0.0, "below", 0.005, 2),  # tests/data/torus.vdb
]


def run(cmd):
    t = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p, time.monotonic() - t


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.normpath(os.path.join(here, "..", ".."))
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(root, "build", "bin"))
    ap.add_argument("--data", default=os.path.join(root, "..", "shared", "data"))
    ap.add_argument("--eps-voxels", default="0.5")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--filter", default="", help="only volumes whose name contains this")
    a = ap.parse_args()
    isodel = os.path.join(a.bin, "isodel")
    tmp = tempfile.mkdtemp(prefix="adaptive_bench_")
    print("| volume | k | tol | leaves / unit cells | E adaptive / dense | G | vertices | tets (both) | mesh s | max cells E (bound) | verify |")
    print("| --- | ---: | ---: | --- | --- | --- | --- | --- | --- | --- | --- |")
    for f, iso, inside, tol, k in CASES:
        if a.filter not in f:
            continue
        src = os.path.join(root, "tests", "data", "torus.vdb") if f == "@torus" else os.path.join(a.data, f)
        if not os.path.exists(src):
            print(f"| {f} | {k} | {tol} | missing: {src} | | | | | | | |")
            continue
        ad, de = os.path.join(tmp, "a.vdb"), os.path.join(tmp, "d.vdb")
        p, _ = run([isodel, "decimate", src, "-o", ad, "--k", str(k), "--tolerance", str(tol)])
        if p.returncode:
            print(f"| {f} | {k} | {tol} | decimate failed: {p.stderr.strip()} | | | | | | | |")
            continue
        cells = next((l.split(":", 1)[1].split("(")[0].strip() for l in p.stdout.splitlines() if l.startswith("cells:")), "?")
        run([isodel, "resample", ad, "-o", de])
        stats = {}
        for tag, vol in (("a", ad), ("d", de)):
            js = os.path.join(tmp, tag + ".json")
            p, secs = run([isodel, "mesh", vol, "--iso", str(iso), "--inside", inside, "--eps-voxels", a.eps_voxels,
                           "--threads", a.threads, "-o", os.path.join(tmp, tag + ".ply"), "--tets",
                           os.path.join(tmp, tag + ".mesh"), "--region", "both", "--quiet", "--stats", js])
            if p.returncode:
                stats[tag] = None
                print(f"mesh {tag} failed: {p.stderr.strip()}", file=sys.stderr)
                continue
            stats[tag] = json.load(open(js))
            stats[tag]["_s"] = secs
        sa, sd = stats.get("a"), stats.get("d")
        if not sa or not sd:
            print(f"| {f} | {k} | {tol} | {cells} | mesh failed | | | | | | |")
            continue
        p, _ = run([isodel, "verify", ad, "--iso", str(iso), "--inside", inside, "--eps-voxels", a.eps_voxels,
                    "--mesh", os.path.join(tmp, "a.ply"), "--tets", os.path.join(tmp, "a.mesh")])
        verdict = "VERIFIED" if p.returncode == 0 else "FAILED"
        ca, cd = sa["counts"], sd["counts"]
        ta = sa["tets"]["tets_inside"] + sa["tets"]["tets_outside"]
        td = sd["tets"]["tets_inside"] + sd["tets"]["tets_outside"]
        r = lambda x, y: f"{x} / {y} ({x / y:.2f})"
        vb = sa["voxel_bound"]
        print(f"| {f.lstrip('@')} | {k} | {tol} | {cells} | {r(ca['E'], cd['E'])} | {r(ca['G'], cd['G'])} | "
              f"{r(ca['vertices'], cd['vertices'])} | {r(ta, td)} | {sa['_s']:.1f} / {sd['_s']:.1f} | "
              f"{vb['max_cells_E']} ({vb['bound_E']}); N {vb['max_cells_N']} ({vb['bound_N']}) | {verdict} |")
        sys.stdout.flush()
    subprocess.run(["rm", "-rf", tmp])


if __name__ == "__main__":
    main()
