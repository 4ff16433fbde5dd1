#!/usr/bin/python3
"""Reads a volume WITHOUT isodel and prints {dims, voxel_size, value_range, ...} as JSON, so the
tests can cross-check `isodel info`: python3-mrcfile for .mrc/.map, vdb_print (libopenvdb-tools)
for .vdb, and a direct numpy parse of the INRIMAGE header for .inr/.inr.gz.
Exit 3 (and a JSON "error") when the independent tool is not installed."""
import gzip
import json
import re
import subprocess
import sys


def read_mrc(path):
    import mrcfile
    import numpy as np
    with mrcfile.open(path, permissive=True) as m:
        h = m.header
        n = [int(h.nx), int(h.ny), int(h.nz)]
        order = [int(h.mapc), int(h.mapr), int(h.maps)]
        dims = [0, 0, 0]
        for f in range(3):
            dims[order[f] - 1] = n[f]
        vs = m.voxel_size
        data = np.asarray(m.data, dtype=np.float64)
        return {"tool": "mrcfile", "dims": dims, "voxel_size": [float(vs.x), float(vs.y), float(vs.z)],
                "value_range": [float(data.min()), float(data.max())]}


def read_vdb(path):
    out = subprocess.run(["vdb_print", "-l", path], capture_output=True, text=True, check=True).stdout
    dims = [int(x) for x in re.search(r"Dimensions of active voxels:\s+(\d+) x (\d+) x (\d+)", out).groups()]
    active = int(re.search(r"Number of active voxels:\s+([\d,]+)", out).group(1).replace(",", ""))
    vmin = float(re.search(r"Min value:\s+(\S+)", out).group(1))
    vmax = float(re.search(r"Max value:\s+(\S+)", out).group(1))
    bg = float(re.search(r"Background value:\s+(\S+)", out).group(1))
    uniform = re.search(r"voxel size:\s+(\S+)", out)
    if uniform:
        vox = [float(uniform.group(1))] * 3
    else:  # anisotropic: "voxel dimensions: [a, b, c]"
        vox = [float(x) for x in re.search(r"voxel dimensions:\s+\[([^\]]*)\]", out).group(1).split(",")]
    return {"tool": "vdb_print", "dims": dims, "active_voxels": active, "active_range": [vmin, vmax],
            "background": bg, "voxel_size_printed": vox}


def read_inr(path):
    import numpy as np
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        raw = f.read()
    end = raw.index(b"##}")
    hlen = ((end + 4 + 255) // 256) * 256
    kv = dict(line.split("=", 1) for line in raw[:end].decode("ascii").splitlines() if "=" in line)
    dims = [int(kv["XDIM"]), int(kv["YDIM"]), int(kv["ZDIM"])]
    bits = int(kv["PIXSIZE"].split()[0])
    kind = {"float": "f", "unsigned fixed": "u", "signed fixed": "i"}[kv["TYPE"]]
    order = ">" if kv.get("CPU", "decm") in ("sun", "sgi") else "<"
    dtype = np.dtype(order + kind + str(bits // 8))
    n = dims[0] * dims[1] * dims[2]
    data = np.frombuffer(raw[hlen:hlen + n * dtype.itemsize], dtype=dtype).astype(np.float64)
    if data.size != n:
        raise ValueError("truncated")
    return {"tool": "numpy", "dims": dims,
            "voxel_size": [float(kv.get("VX", 1)), float(kv.get("VY", 1)), float(kv.get("VZ", 1))],
            "value_range": [float(data.min()), float(data.max())]}


def main():
    path = sys.argv[1]
    try:
        if path.endswith(".vdb"):
            result = read_vdb(path)
        elif path.endswith((".mrc", ".map", ".ccp4")):
            result = read_mrc(path)
        else:
            result = read_inr(path)
    except (ImportError, FileNotFoundError) as e:
        print(json.dumps({"error": "independent reader unavailable: %s" % e}))
        return 3
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
