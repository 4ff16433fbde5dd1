#!/usr/bin/python3
"""Writes two_blobs.mrc, the bundled sample volume for the README demo and the tests:
32^3 float32 samples of a sum of two Gaussian densities (voxel size 0.5, origin (-8,-8,-8)),
as MRC2014 mode 2, little-endian. Mesh it at isovalue 0.5 with inside = above: two closed
surfaces of genus 0, far from the box faces (boundary samples are < 1e-3).
Regenerate with: python3 tools/data/make_sample.py (needs only numpy)."""
import os
import struct

import numpy as np

N = 32
VOXEL = 0.5
ORIGIN = -8.0


def density():
    idx = np.arange(N, dtype=np.float64) * VOXEL + ORIGIN
    z, y, x = np.meshgrid(idx, idx, idx, indexing="ij")  # array order (z, y, x): x fastest on disk
    blob1 = np.exp(-((x + 2.5) ** 2 + y ** 2 + z ** 2) / (2 * 1.6 ** 2))
    blob2 = 0.9 * np.exp(-((x - 3.0) ** 2 + (y - 0.5) ** 2 + (z + 0.5) ** 2) / (2 * 1.3 ** 2))
    return (blob1 + blob2).astype("<f4")


def header(data):
    h = bytearray(1024)
    struct.pack_into("<3i", h, 0, N, N, N)          # NC NR NS
    struct.pack_into("<i", h, 12, 2)                # MODE float32
    struct.pack_into("<3i", h, 16, 0, 0, 0)         # NCSTART NRSTART NSSTART
    struct.pack_into("<3i", h, 28, N, N, N)         # MX MY MZ
    struct.pack_into("<3f", h, 40, N * VOXEL, N * VOXEL, N * VOXEL)  # cell lengths
    struct.pack_into("<3f", h, 52, 90.0, 90.0, 90.0)                 # cell angles
    struct.pack_into("<3i", h, 64, 1, 2, 3)         # MAPC MAPR MAPS
    struct.pack_into("<3f", h, 76, float(data.min()), float(data.max()), float(data.mean()))
    struct.pack_into("<i", h, 108, 20140)           # NVERSION
    struct.pack_into("<3f", h, 196, ORIGIN, ORIGIN, ORIGIN)
    h[208:212] = b"MAP "
    h[212:216] = b"\x44\x44\x00\x00"                # little-endian machine stamp
    struct.pack_into("<f", h, 216, float(data.std()))
    struct.pack_into("<i", h, 220, 1)
    label = b"isodel sample: two Gaussian blobs, iso 0.5"
    h[224:224 + len(label)] = label
    return bytes(h)


def main():
    data = density()
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "two_blobs.mrc")
    with open(out, "wb") as f:
        f.write(header(data))
        f.write(data.tobytes())
    print("wrote %s (%d bytes), value range [%g, %g]" % (out, 1024 + data.nbytes, data.min(), data.max()))


if __name__ == "__main__":
    main()
