// OpenVDB files: any float or double scalar grid (double converted to float). Half-float storage
// is decoded by OpenVDB itself. The grid's class picks the default inside side.
#include "dense_volume.h"
#include "readers.h"

#include "octree/stored_tiles.h"
#include "octree/vdb_file_layout.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace isodel::io {
namespace {

bool is_scalar(const openvdb::GridBase& g)
{
    return g.isType<openvdb::FloatGrid>() || g.isType<openvdb::DoubleGrid>();
}

std::string grid_list(const openvdb::GridPtrVec& grids)
{
    if (grids.empty()) return "the file has no grids";
    std::string s = "grids in the file: ";
    for (std::size_t n = 0; n < grids.size(); ++n) {
        if (n) s += ", ";
        s += "'" + grids[n]->getName() + "' [" + grids[n]->valueType() + "]";
    }
    return s;
}

openvdb::FloatGrid::Ptr to_float_grid(const openvdb::GridBase::Ptr& base)
{
    if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) return f;
    auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(base);
    // Tree's converting copy constructor keeps topology and tiles and casts every value.
    auto tree = std::make_shared<openvdb::FloatTree>(d->tree());
    auto f = openvdb::FloatGrid::create(tree);
    f->insertMeta(*d);
    f->setTransform(d->transform().copy());
    f->setName(d->getName());
    f->setGridClass(d->getGridClass());
    return f;
}

/// ReadOptions::regions on a delay-loaded grid: the lattice from the topology, the value range
/// (finish_volume's) over the tiles and the leaves that meet a region, which are all that is
/// loaded; their values are checked to be finite.
void finish_partial_vdb(Volume& vol, const std::vector<openvdb::CoordBBox>& regions)
{
    check_transform_and_background(vol);
    const auto& tree = vol.grid->tree();
    if (tree.activeVoxelCount() == 0) invalid(vol.path, "empty grid '" + vol.grid->getName() + "' (no active voxels)");
    vol.partial = true;
    vol.lattice = vol.grid->evalActiveVoxelBoundingBox();
    const bool incomplete = tree.activeVoxelCount() < vol.lattice.volume();
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    const auto consider = [&](float v, const openvdb::Coord& at) {
        if (!std::isfinite(v))
            invalid(vol.path, std::string(std::isnan(v) ? "NaN" : "Inf") + " value at index (i,j,k) = (" +
                                  std::to_string(at.x()) + ", " + std::to_string(at.y()) + ", " + std::to_string(at.z()) +
                                  "); non-finite samples are not accepted");
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    };
    // Active tiles lie in the lattice, and inactive ones are samples only there.
    octree::for_each_stored_tile(tree, vol.lattice, [&](const openvdb::CoordBBox& b, float v, bool active) {
        if (active || (incomplete && vol.lattice.hasOverlap(b))) consider(v, b.min());
    });
    if (incomplete) consider(tree.background(), vol.lattice.min());
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        const openvdb::CoordBBox nb = leaf->getNodeBoundingBox();
        if (std::none_of(regions.begin(), regions.end(), [&](const openvdb::CoordBBox& r) { return r.hasOverlap(nb); }))
            continue;
        vol.samples_read += openvdb::FloatTree::LeafNodeType::SIZE;
        for (auto v = leaf->cbeginValueAll(); v; ++v)
            if (v.isValueOn() || (incomplete && vol.lattice.isInside(v.getCoord()))) consider(*v, v.getCoord());
    }
    vol.value_min = lo, vol.value_max = hi; // min > max: nothing read
}

} // namespace

Volume read_vdb(const std::string& path, const ReadOptions& opt)
{
    file_size_or_throw(path);
    openvdb::initialize(); // idempotent; library users may not have called it
    // Before OpenVDB reads anything: it allocates whatever sizes the file states.
    octree::check_vdb_file_layout(path);
    // An isodel adaptive file (octree/, `isodel decimate`): F is the adaptive interpolant, which
    // the finest-grid resampling reproduces exactly (trilinear on every sub-cell), so every
    // command meshes and verifies the decimated F (Property IV) through the one uniform path.
    if (const auto info = adaptive_info(path); info && (opt.grid_name.empty() || opt.grid_name == info->sample_grid)) {
        const AdaptiveVolume av = load_adaptive(path);
        Volume vol;
        vol.path = path;
        vol.format = "vdb";
        vol.grid = resample(av);
        vol.grid->setTransform(av.samples->transform().copy());
        vol.grid->setGridClass(av.samples->getGridClass());
        vol.grid->setName(av.samples->getName());
        vol.adaptive_levels = info->levels;
        vol.adaptive_k = info->k;
        vol.default_inside = default_inside(*vol.grid);
        finish_volume(vol);
        return vol;
    }
    openvdb::io::File file(path);
    try {
        // ReadOptions::regions: OpenVDB's delayed loading maps the file and loads a leaf's values
        // when they are first read, so only the leaves the caller reads are loaded. No private
        // copy of the file is made (the caller reads it within one run).
        file.setCopyMaxBytes(0);
        file.open(/*delayLoad=*/opt.regions.has_value());
    } catch (const std::exception& e) { // OpenVDB's exceptions, or std::bad_alloc for a corrupt size
        invalid(path, std::string("not a readable OpenVDB file (wrong magic number or corrupt header): ") + e.what());
    }
    openvdb::GridPtrVec metas;
    openvdb::GridBase::Ptr base;
    try {
        metas = *file.readAllGridMetadata();
        std::string name = opt.grid_name;
        if (!name.empty()) {
            bool found = false;
            for (const auto& g : metas) {
                if (g->getName() != name) continue;
                found = true;
                if (!is_scalar(*g))
                    invalid(path, "grid '" + name + "' is not a scalar grid (value type " + g->valueType() +
                                      "); isodel reads float or double scalar grids");
            }
            if (!found) invalid(path, "no grid named '" + name + "' (" + grid_list(metas) + ")");
        } else {
            // The first scalar grid that File::readGrid(name) returns: the first of its name
            // (OpenVDB lists grids by name, those of one name in file order).
            bool chosen = false;
            for (std::size_t i = 0; i < metas.size() && !chosen; ++i) {
                const bool first_of_name = i == 0 || metas[i]->getName() != metas[i - 1]->getName();
                if (first_of_name && is_scalar(*metas[i])) {
                    name = metas[i]->getName();
                    chosen = true;
                }
            }
            if (!chosen && !std::any_of(metas.begin(), metas.end(), [](auto& g) { return is_scalar(*g); }))
                invalid(path, "no float or double scalar grid (" + grid_list(metas) + ")");
            if (!chosen)
                invalid(path, "every float or double grid has the name of a grid of another type before it, "
                              "which OpenVDB would read in its place (" + grid_list(metas) + ")");
        }
        // readGrid(name) returns the first grid of that name, which is the one chosen above.
        base = file.readGrid(name);
        file.close();
    } catch (const isodel::Error&) {
        throw;
    } catch (const std::exception& e) {
        io_failure(path, std::string("cannot read grid data (truncated or corrupt file?): ") + e.what());
    }
    Volume vol;
    vol.path = path;
    vol.format = "vdb";
    // A double grid is converted, which reads every value: it is read whole.
    const bool in_part = opt.regions && base->isType<openvdb::FloatGrid>();
    vol.grid = to_float_grid(base);
    vol.default_inside = default_inside(*vol.grid);
    if (in_part) finish_partial_vdb(vol, *opt.regions);
    else finish_volume(vol);
    return vol;
}

} // namespace isodel::io
