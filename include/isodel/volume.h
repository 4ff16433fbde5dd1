#pragma once
/// \file volume.h
/// Reading sampled scalar volumes into an openvdb::FloatGrid.
///
/// Conventions (the same everywhere in isodel): sample (i,j,k) sits at OpenVDB index (i,j,k);
/// the grid's transform maps index to world (voxel size, origin, and for crystallographic maps
/// a sheared affine map). Dense formats (MRC/CCP4, INR, raw) produce grids whose every sample
/// is an active voxel, so the active bounding box is the file's lattice.
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace isodel {

/// Which side of the isovalue is the solid.
enum class Inside { Above, Below };

/// "above" or "below".
inline const char* to_string(Inside inside) { return inside == Inside::Above ? "above" : "below"; }

/// The inside side when the caller does not say: Below for level sets (OpenVDB's convention,
/// negative inside), Above for everything else (densities, fog volumes, maps).
inline Inside default_inside(const openvdb::FloatGrid& grid)
{
    return grid.getGridClass() == openvdb::GRID_LEVEL_SET ? Inside::Below : Inside::Above;
}

/// Layout of a headerless raw volume (x fastest, then y, then z; little-endian).
struct RawLayout {
    std::array<int, 3> dims{0, 0, 0};
    std::string type = "float32"; ///< float32 | uint8 | uint16 | int16
    double spacing = 1.0;         ///< voxel size in world units, > 0
};

struct ReadOptions {
    /// `.vdb`: name of the grid to read; empty = the first float/double scalar grid.
    std::string grid_name;
    /// Required for raw volumes (files that are not .vdb/.mrc/.map/.ccp4/.inr/.inr.gz).
    std::optional<RawLayout> raw;
    /// Refuse headers announcing more samples than this, before allocating anything.
    std::uint64_t max_voxels = std::uint64_t(1) << 31;
    /// When set, only the samples in these index boxes (clipped to the file's lattice) are read:
    /// MRC/CCP4 and raw volumes by offset (Volume::grid then holds those samples alone), float
    /// .vdb grids by OpenVDB's delayed loading (the grid's topology is read, and a leaf's values
    /// when they are first read: those of the leaves meeting the boxes, and any leaf the caller
    /// reads later). Volume::lattice is still the whole file's, and the value range is over the
    /// samples read (for a .vdb also its tiles; value_min > value_max when nothing was read, as for an
    /// empty list: the header alone).
    /// Other formats (.inr, double grids) are read whole (Volume::partial stays false). What a
    /// process of a partitioned run reads (mesh_isosurface_file in mesh.h).
    std::optional<std::vector<openvdb::CoordBBox>> regions;
};

/// A volume as read from a file.
struct Volume {
    openvdb::FloatGrid::Ptr grid; ///< samples and index->world transform; never null
    std::string path;             ///< the file it came from
    std::string format;           ///< "vdb", "mrc", "inr", "raw"
    Inside default_inside = Inside::Above; ///< level set grid class -> Below; everything else Above
    openvdb::CoordBBox lattice;   ///< index box of the sample lattice
    float value_min = 0, value_max = 0;    ///< over the lattice's samples
    /// > 0 for an isodel adaptive file (`isodel decimate`): its number of levels; `grid` then holds
    /// the adaptive interpolant resampled exactly on the finest grid (include/isodel/adaptive.h).
    int adaptive_levels = 0;
    int adaptive_k = 0;
    /// ReadOptions::regions was honoured: the grid holds (or loads) only the samples of those boxes.
    bool partial = false;
    /// Samples read from the file: the active voxels of a whole read, a region read's samples,
    /// for a .vdb the voxels of the leaves loaded.
    std::uint64_t samples_read = 0;
};

/// Reads \p path by extension (.vdb, .mrc/.map/.ccp4, .inr/.inr.gz, else raw with \p opt.raw).
/// \throw IoError the file cannot be opened or is truncated
/// \throw InvalidInput unknown extension, wrong magic, bad header, non-finite samples, ...
/// Every message starts with the path.
Volume read_volume(const std::string& path, const ReadOptions& opt = {});

/// Refuses an isovalue outside [vol.value_min, vol.value_max] (or non-finite):
/// \throw InvalidInput "<path>: isovalue V is outside the value range [min, max] of the samples".
void check_isovalue(const Volume& vol, double isovalue);

/// Writes \p grid (and optional extra grids) to a .vdb file atomically (temporary name + rename).
void write_vdb(const std::string& path, const openvdb::GridPtrVec& grids);

} // namespace isodel
