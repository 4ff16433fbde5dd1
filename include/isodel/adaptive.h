#pragma once
/// \file adaptive.h
/// Adaptive (octree) volumes: decimation, resampling, files (paper Property IV, Section 4.2).
///
/// An adaptive volume keeps its samples in one FloatGrid at the finest resolution and its cell
/// structure as one MaskGrid per level l >= 1 (voxel o >> l on = leaf cell of size 2^l at o);
/// level 0 is implied. Adjacent leaves (sharing a face, edge or vertex) differ by at most k
/// levels. F is the trilinear interpolant per leaf with hanging-node values constrained to the
/// coarse neighbour's interpolant, so it is continuous.
#include <isodel/interrupt.h>

#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace isodel {

struct AdaptiveVolume {
    openvdb::FloatGrid::Ptr samples;             ///< finest-resolution samples (leaf corners)
    std::vector<openvdb::MaskGrid::Ptr> levels;  ///< levels[l], l >= 1; levels[0] is null
    openvdb::CoordBBox domain;                   ///< samples read through the grid (closed box)
    int k = 1;                                   ///< level-difference bound
    double tolerance = 0;                        ///< decimation tolerance T (value units)
    std::string source;                          ///< where the samples came from
};

struct DecimateOptions {
    int k = 1;                 ///< max level difference of touching leaves, >= 1
    double tolerance = 0;      ///< T: every replaced fine sample is reproduced within T
    std::optional<double> iso; ///< keep cells within band voxels of {F = iso} fine
    double band = 1.0;         ///< in voxels (Chebyshev distance from crossed cells)
    openvdb::GridBase::ConstPtr importance; ///< keep cells fine where this grid is active
    int max_level = 8;         ///< coarsest level considered
    std::string source;        ///< recorded in the metadata
};

struct DecimateResult {
    AdaptiveVolume volume;
    std::uint64_t cells_before = 0, cells_after = 0;
    std::size_t memory_before = 0, memory_after = 0; ///< samples + masks, bytes (memUsage)
    std::vector<std::uint64_t> histogram;            ///< leaves per level
    double max_error = 0;      ///< max |F_adaptive - f| over all fine samples, measured
    int max_level_difference = 0;
    std::size_t balance_splits = 0, repair_splits = 0;
    double seconds = 0;
};

/// Coarsens \p grid bottom-up (see octree/decimate.h). \throw InvalidInput bad options.
DecimateResult decimate(const openvdb::FloatGrid& grid, const DecimateOptions& options,
                        Interrupter* interrupter = nullptr);

/// The adaptive interpolant sampled at every finest sample (exact for trilinear: a trilinear
/// function restricted to a sub-cell is the trilinear function of its corner values).
openvdb::FloatGrid::Ptr resample(const AdaptiveVolume& volume, Interrupter* interrupter = nullptr);

/// The one-level adaptive volume of a uniform grid (shares \p grid, no masks).
AdaptiveVolume uniform_adaptive(openvdb::FloatGrid::Ptr grid, int k = 1);

/// Writes the sample grid, one MaskGrid per level and metadata (isodel_adaptive, k, levels,
/// source, tolerance, domain) to a .vdb file (atomic). \throw IoError
void save_adaptive(const std::string& path, const AdaptiveVolume& volume);
/// \throw IoError unreadable; InvalidInput not an isodel adaptive file
AdaptiveVolume load_adaptive(const std::string& path);

/// The grid of a .vdb file that DecimateOptions::importance takes: the one OpenVDB lists first
/// (by name). The file is checked before OpenVDB reads it, as every isodel reader does.
/// \throw IoError unreadable; InvalidInput corrupt, no grid, or a grid type isodel does not read
openvdb::GridBase::Ptr read_importance_grid(const std::string& path);

/// What `isodel info` prints for an adaptive file; nullopt when \p path is not one (or
/// unreadable). Reads metadata and masks only, not the samples.
struct AdaptiveInfo {
    int k = 1;
    int levels = 1;            ///< number of levels including 0
    double tolerance = 0;
    std::string source;
    std::string sample_grid;   ///< name of the sample grid
    openvdb::CoordBBox domain;
    std::vector<std::uint64_t> histogram; ///< leaves per level (level 0 derived)
    std::uint64_t cells = 0;
};
std::optional<AdaptiveInfo> adaptive_info(const std::string& path);

} // namespace isodel
