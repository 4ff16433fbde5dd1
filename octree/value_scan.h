#pragma once
// Internal: the scan behind SampleField's tie rule (sample_field.h): the value range, whether a
// sample or a face or cell saddle equals v, and the gap below v. Its results are minima, maxima
// and an "or", so scans of parts of the volume join into the scan of the whole in any order: at
// any thread count, and across the processes of a partitioned run that each read one slab of
// the file (surface/partitioned_file.h).
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace isodel::octree {

struct ValueScan {
    explicit ValueScan(double isovalue) : v(isovalue), round_off(1e-12 * std::max(1.0, std::abs(isovalue))) {}
    double v, round_off;
    double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
    bool tie = false;
    double gap = std::numeric_limits<double>::infinity();

    void consider(double f)
    {
        vmin = std::min(vmin, f);
        vmax = std::max(vmax, f);
        if (f == v) tie = true;
        else if (f < v) gap = std::min(gap, v - f);
    }
    /// A saddle's value is a quotient or a square root: a tie is within rounding of v.
    void critical(double f)
    {
        if (std::abs(f - v) <= round_off) tie = true;
        else if (f < v) gap = std::min(gap, v - f);
    }
    /// Minima, maxima and an "or": the same result in any order.
    void join(const ValueScan& o)
    {
        vmin = std::min(vmin, o.vmin);
        vmax = std::max(vmax, o.vmax);
        tie = tie || o.tie;
        gap = std::min(gap, o.gap);
    }
};

/// Every sample of the whole volume (no filter), for the scans below.
inline openvdb::CoordBBox every_sample()
{
    return openvdb::CoordBBox(openvdb::Coord(std::numeric_limits<int>::min()),
                              openvdb::Coord(std::numeric_limits<int>::max()));
}

/// Every stored value of the domain whose sample lies in \p owned: active voxels and tiles, and
/// inactive ones inside \p lattice (and in the ring around it when the ring reads the
/// background; values stored beyond the domain are no samples of F). Tiles are read
/// once, never expanded; inactive tiles of the background value are skipped, since the caller
/// counts the background itself whenever an inactive sample can read it. A tile that merely
/// meets the samples of \p owned (\p owned within the lattice, or within the lattice and its
/// ring when the ring reads the background) is counted: its value is a sample of F either way.
void scan_stored_values(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& lattice, bool ring_reads_background,
                        const openvdb::CoordBBox& owned, ValueScan& scan);

/// Critical values of the faces and cells (critical_values.h) whose lowest corner is an active
/// voxel in \p owned; the grid must hold the samples of those cells' upper corners too.
void scan_critical_values(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& lattice,
                          bool ring_reads_background, const openvdb::CoordBBox& owned, ValueScan& scan);

/// The active voxels in \p owned (active tiles counted voxel by voxel, never expanded), from the
/// value masks alone.
std::uint64_t active_voxels_in(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& owned);

/// The samples \p grid holds in memory: 512 per leaf whose values are loaded (OpenVDB's delayed
/// loading reads a .vdb leaf's values when they are first read).
std::uint64_t samples_in_memory(const openvdb::FloatGrid& grid);

} // namespace isodel::octree
