#include "octree/adaptive_vdb_format.h"
#include "octree/vdb_file_layout.h"

#include <isodel/errors.h>

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace isodel::octree {

namespace {
openvdb::Vec3i to_vec(const Coord& c) { return openvdb::Vec3i(c.x(), c.y(), c.z()); }
Coord to_coord(const openvdb::Vec3i& v) { return Coord(v.x(), v.y(), v.z()); }

template <typename T, typename MetaT>
T meta_or(const openvdb::MetaMap& m, const char* key, T dflt)
{
    const auto p = m.getMetadata<MetaT>(key);
    return p ? T(p->value()) : dflt;
}

std::string level_name(int l) { return "level_" + std::to_string(l); }

// Finds the sample grid of an adaptive file among grids (with or without trees).
openvdb::GridBase::Ptr find_samples(const openvdb::GridPtrVec& grids)
{
    for (const auto& g : grids)
        if (g && is_adaptive_sample_grid(*g)) return g;
    return nullptr;
}
} // namespace

bool is_adaptive_sample_grid(const openvdb::GridBase& g)
{
    return g.getMetadata<openvdb::Int32Metadata>("isodel_adaptive") != nullptr;
}

AdaptiveGrid to_adaptive_grid(const AdaptiveVolume& v)
{
    if (!v.samples) throw InvalidInput("adaptive volume without samples");
    if (v.domain.empty()) return AdaptiveGrid(v.samples, v.k);
    std::vector<openvdb::MaskGrid::Ptr> masks = v.levels;
    return AdaptiveGrid(v.samples, v.domain, masks, v.k);
}

} // namespace isodel::octree

namespace isodel {

using namespace isodel::octree;

AdaptiveVolume uniform_adaptive(openvdb::FloatGrid::Ptr grid, int k)
{
    AdaptiveVolume v;
    const AdaptiveGrid g(grid, k); // derives the domain; no masks
    v.samples = std::move(grid);
    v.levels.resize(1);
    v.domain = g.domain();
    v.k = k;
    return v;
}

void save_adaptive(const std::string& path, const AdaptiveVolume& v)
{
    if (!v.samples) throw InvalidInput(path + ": adaptive volume without samples");
    // Shallow copy: shares the tree, so the caller's grid metadata is untouched.
    auto s = openvdb::gridPtrCast<openvdb::FloatGrid>(v.samples->copyGrid());
    s->setSaveFloatAsHalf(false); // save -> load must be exact
    if (s->getName().empty()) s->setName("samples");
    const AdaptiveGrid g = to_adaptive_grid(v);
    s->insertMeta("isodel_adaptive", openvdb::Int32Metadata(kAdaptiveFormatVersion));
    s->insertMeta("isodel_k", openvdb::Int32Metadata(v.k));
    s->insertMeta("isodel_levels", openvdb::Int32Metadata(g.max_level() + 1));
    s->insertMeta("isodel_tolerance", openvdb::DoubleMetadata(v.tolerance));
    s->insertMeta("isodel_source", openvdb::StringMetadata(v.source));
    s->insertMeta("isodel_domain_min", openvdb::Vec3IMetadata(to_vec(g.domain().min())));
    s->insertMeta("isodel_domain_max", openvdb::Vec3IMetadata(to_vec(g.domain().max())));
    openvdb::GridPtrVec grids{s};
    for (int l = 1; l <= g.max_level(); ++l) {
        openvdb::MaskGrid::Ptr m = g.masks()[l] ? openvdb::gridPtrCast<openvdb::MaskGrid>(g.masks()[l]->copyGrid())
                                                : openvdb::MaskGrid::create(false);
        if (!g.masks()[l]) {
            auto xf = s->transform().copy();
            xf->preScale(double(1 << l));
            m->setTransform(xf);
        }
        m->setName(level_name(l));
        m->insertMeta("isodel_level", openvdb::Int32Metadata(l));
        grids.push_back(m);
    }
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    try {
        openvdb::io::File f(tmp);
        f.write(grids);
        f.close();
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw IoError(path + ": cannot write: " + e.what());
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw IoError(path + ": cannot rename the temporary file into place");
    }
}

AdaptiveVolume load_adaptive(const std::string& path)
{
    check_vdb_file_layout(path); // before OpenVDB allocates what the file states
    openvdb::GridBase::Ptr base;
    std::vector<openvdb::GridBase::Ptr> level_grids; // level l at l - 1; null when absent
    try {
        openvdb::io::File f(path);
        f.open(/*delayLoad=*/false); // delayed loading would read leaf data apart from the check
        const auto metas = f.readAllGridMetadata();
        const auto sample_meta = find_samples(*metas);
        if (!sample_meta) throw InvalidInput(path + ": not an isodel adaptive file (no isodel_adaptive metadata)");
        // Only the sample grid and the level masks are read, each of a type the check walked.
        // File::readGrid(name) reads the first grid of that name.
        const auto read_checked = [&](const std::string& name) -> openvdb::GridBase::Ptr {
            for (const auto& m : *metas)
                if (m->getName() == name) {
                    if (!vdb_grid_type_checked(m->type()))
                        throw InvalidInput(path + ": grid " + name + " has type " + m->type() +
                                           ", which an isodel adaptive file does not hold");
                    return f.readGrid(name);
                }
            return nullptr;
        };
        base = read_checked(sample_meta->getName());
        const int levels = meta_or<int, openvdb::Int32Metadata>(*sample_meta, "isodel_levels", 1);
        for (int l = 1; l < std::min(levels, AdaptiveGrid::kMaxLevel + 1); ++l)
            level_grids.push_back(read_checked(level_name(l)));
        f.close();
    } catch (const isodel::Error&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(path + ": cannot read: " + e.what());
    }
    auto s = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!s || !is_adaptive_sample_grid(*s)) throw InvalidInput(path + ": adaptive sample grid is not a float grid");
    if (s->tree().activeVoxelCount() == 0)
        throw InvalidInput(path + ": adaptive sample grid '" + s->getName() + "' is empty (no active voxels)");
    AdaptiveVolume v;
    v.samples = s;
    v.k = meta_or<int, openvdb::Int32Metadata>(*s, "isodel_k", 1);
    // Touching leaves differ by at most k levels; a bound below 1 describes no octree (the
    // balance and the 3k+1 trap bound need k >= 1).
    if (v.k < 1)
        throw InvalidInput(path + ": isodel_k (the level difference of touching leaves) is " + std::to_string(v.k) +
                           ", must be at least 1");
    v.tolerance = meta_or<double, openvdb::DoubleMetadata>(*s, "isodel_tolerance", 0.0);
    v.source = meta_or<std::string, openvdb::StringMetadata>(*s, "isodel_source", std::string());
    const int levels = meta_or<int, openvdb::Int32Metadata>(*s, "isodel_levels", 1);
    const auto dmin = s->getMetadata<openvdb::Vec3IMetadata>("isodel_domain_min");
    const auto dmax = s->getMetadata<openvdb::Vec3IMetadata>("isodel_domain_max");
    if (!dmin || !dmax || levels < 1 || levels > AdaptiveGrid::kMaxLevel + 1)
        throw InvalidInput(path + ": inconsistent isodel adaptive metadata");
    v.domain = CoordBBox(to_coord(dmin->value()), to_coord(dmax->value()));
    v.levels.assign(levels, nullptr);
    for (int l = 1; l < levels; ++l) {
        const auto g = std::size_t(l - 1) < level_grids.size() ? level_grids[l - 1] : nullptr;
        if (!g) throw InvalidInput(path + ": missing grid " + level_name(l));
        v.levels[l] = openvdb::gridPtrCast<openvdb::MaskGrid>(g);
        if (!v.levels[l]) throw InvalidInput(path + ": grid " + level_name(l) + " is not a mask grid");
    }
    return v;
}

openvdb::GridBase::Ptr read_importance_grid(const std::string& path)
{
    check_vdb_file_layout(path); // before OpenVDB allocates what the file states
    try {
        openvdb::io::File f(path);
        f.open(/*delayLoad=*/false);
        const auto metas = f.readAllGridMetadata();
        if (metas->empty()) throw InvalidInput(path + ": no grids");
        // The grid OpenVDB lists first (it lists grids by name); File::readGrid(name) reads
        // the first grid of that name.
        const auto& first = metas->front();
        if (!vdb_grid_type_checked(first->type()))
            throw InvalidInput(path + ": importance grid '" + first->getName() + "' has type " + first->type() +
                               " (isodel reads mask, bool, float, double and int32 grids)");
        auto g = f.readGrid(first->getName());
        f.close();
        return g;
    } catch (const isodel::Error&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(path + ": cannot read: " + e.what());
    }
}

std::optional<AdaptiveInfo> adaptive_info(const std::string& path)
{
    try {
        check_vdb_file_layout(path); // before OpenVDB allocates what the file states
        openvdb::io::File f(path);
        f.open(/*delayLoad=*/false);
        const auto metas = f.readAllGridMetadata();
        auto base = find_samples(*metas);
        if (!base) return std::nullopt;
        AdaptiveInfo info;
        info.sample_grid = base->getName();
        info.k = meta_or<int, openvdb::Int32Metadata>(*base, "isodel_k", 1);
        info.levels = meta_or<int, openvdb::Int32Metadata>(*base, "isodel_levels", 1);
        info.tolerance = meta_or<double, openvdb::DoubleMetadata>(*base, "isodel_tolerance", 0.0);
        info.source = meta_or<std::string, openvdb::StringMetadata>(*base, "isodel_source", std::string());
        const auto dmin = base->getMetadata<openvdb::Vec3IMetadata>("isodel_domain_min");
        const auto dmax = base->getMetadata<openvdb::Vec3IMetadata>("isodel_domain_max");
        if (!dmin || !dmax) return std::nullopt;
        info.domain = CoordBBox(to_coord(dmin->value()), to_coord(dmax->value()));
        info.histogram.assign(std::max(1, info.levels), 0);
        std::uint64_t covered = 0;
        for (int l = 1; l < info.levels; ++l) {
            if (!f.hasGrid(level_name(l))) return std::nullopt;
            const auto level_meta = f.readGridMetadata(level_name(l));
            if (!level_meta || !vdb_grid_type_checked(level_meta->type())) return std::nullopt;
            info.histogram[l] = f.readGrid(level_name(l))->activeVoxelCount();
            covered += info.histogram[l] << (3 * l);
        }
        const CoordBBox cells(info.domain.min(), info.domain.max().offsetBy(-1));
        info.histogram[0] = cells.volume() - covered;
        for (auto n : info.histogram) info.cells += n;
        f.close();
        return info;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

} // namespace isodel
