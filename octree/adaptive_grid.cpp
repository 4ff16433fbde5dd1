#include "octree/adaptive_grid.h"

#include <isodel/errors.h>

#include <algorithm>

namespace isodel::octree {

namespace {
CoordBBox sample_domain(const openvdb::FloatGrid& g)
{
    // The same rule as SampleField (sample_field.h): active bbox grown by one voxel.
    CoordBBox b = g.evalActiveVoxelBoundingBox();
    if (b.empty()) throw InvalidInput("grid '" + g.getName() + "' is empty (no active voxels)");
    b.expand(1);
    return b;
}
} // namespace

AdaptiveGrid::AdaptiveGrid(openvdb::FloatGrid::ConstPtr samples, int k)
    : samples_(std::move(samples)), k_(k)
{
    if (!samples_) throw InvalidInput("null sample grid");
    domain_ = sample_domain(*samples_);
    masks_.resize(1); // level 0 only, derived
}

AdaptiveGrid::AdaptiveGrid(openvdb::FloatGrid::ConstPtr samples, const CoordBBox& domain,
                           std::vector<openvdb::MaskGrid::Ptr> masks, int k)
    : samples_(std::move(samples)), domain_(domain), masks_(std::move(masks)), k_(k)
{
    if (!samples_) throw InvalidInput("null sample grid");
    if (masks_.empty()) masks_.resize(1);
    masks_[0].reset();
    if (int(masks_.size()) - 1 > kMaxLevel) throw InvalidInput("adaptive grid: too many levels");
}

bool AdaptiveGrid::inside(const CellId& c) const
{
    const CoordBBox n = c.nodes();
    return domain_.isInside(n.min()) && domain_.isInside(n.max());
}

openvdb::MaskGrid::ConstPtr AdaptiveGrid::mask(int level) const
{
    if (level <= 0 || level > max_level()) return nullptr;
    return masks_[level];
}

void AdaptiveGrid::set_leaf(const CellId& c, bool on)
{
    if (c.level <= 0) return; // level 0 is derived
    if (c.level > kMaxLevel) throw InvalidInput("adaptive grid: level above maximum");
    if (c.level > max_level()) masks_.resize(c.level + 1);
    auto& m = masks_[c.level];
    if (!m) {
        if (!on) return;
        m = openvdb::MaskGrid::create(false);
        auto xf = samples_->transform().copy();
        xf->preScale(double(1 << c.level)); // mask voxel o>>l sits at sample index o
        m->setTransform(xf);
        m->setName("level_" + std::to_string(c.level));
    }
    const Coord q(shift_down(c.origin.x(), c.level), shift_down(c.origin.y(), c.level),
                  shift_down(c.origin.z(), c.level));
    if (on) m->tree().setValueOn(q);
    else m->tree().setValueOff(q);
}

void AdaptiveGrid::split(const CellId& c)
{
    if (c.level <= 0) return;
    set_leaf(c, false);
    const int h = c.size() / 2;
    for (int n = 0; n < 8; ++n)
        set_leaf({c.origin.offsetBy((n & 1) * h, ((n >> 1) & 1) * h, ((n >> 2) & 1) * h), c.level - 1},
                 true);
}

void AdaptiveGrid::merge(const CellId& parent)
{
    const int h = parent.size() / 2;
    for (int n = 0; n < 8; ++n)
        set_leaf({parent.origin.offsetBy((n & 1) * h, ((n >> 1) & 1) * h, ((n >> 2) & 1) * h),
                  parent.level - 1},
                 false);
    set_leaf(parent, true);
}

void AdaptiveGrid::trim_levels()
{
    while (max_level() > 0 && (!masks_.back() || masks_.back()->activeVoxelCount() == 0))
        masks_.pop_back();
    for (auto& m : masks_)
        if (m) m->pruneGrid();
}

std::vector<CellId> AdaptiveGrid::leaves(int level) const
{
    std::vector<CellId> out;
    auto m = mask(level);
    if (!m) return out;
    out.reserve(m->activeVoxelCount());
    for (auto it = m->cbeginValueOn(); it; ++it) {
        // Masks hold voxels only (set one at a time; pruneGrid does not make active tiles of a
        // MaskGrid unless a whole node is on, which we expand here).
        CoordBBox b;
        it.getBoundingBox(b);
        for (auto c = b.begin(); c; ++c)
            out.push_back({Coord((*c).x() * (1 << level), (*c).y() * (1 << level), (*c).z() * (1 << level)), level});
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::uint64_t> AdaptiveGrid::level_histogram() const
{
    std::vector<std::uint64_t> h(masks_.size(), 0);
    const CoordBBox cells = unit_cells();
    std::uint64_t covered = 0;
    for (int l = 1; l <= max_level(); ++l) {
        if (masks_[l]) h[l] = masks_[l]->activeVoxelCount();
        covered += h[l] << (3 * l);
    }
    h[0] = cells.empty() ? 0 : cells.volume() - covered;
    return h;
}

std::uint64_t AdaptiveGrid::cell_count() const
{
    std::uint64_t n = 0;
    for (auto v : level_histogram()) n += v;
    return n;
}

std::size_t AdaptiveGrid::memory_bytes() const
{
    std::size_t n = samples_->memUsage();
    for (const auto& m : masks_)
        if (m) n += m->memUsage();
    return n;
}

AdaptiveGrid::Reader::Reader(const AdaptiveGrid& g) : g_(&g), acc_(g.samples_->getConstAccessor())
{
    for (int l = 1; l <= g.max_level(); ++l) {
        if (!g.masks_[l]) {
            // An absent level still needs a slot; use an empty static mask.
            static const openvdb::MaskGrid::Ptr empty = openvdb::MaskGrid::create(false);
            masks_.emplace_back(empty->getConstAccessor());
        } else {
            masks_.emplace_back(g.masks_[l]->getConstAccessor());
        }
    }
}

int AdaptiveGrid::Reader::leaf_level(const Coord& u) const
{
    const CoordBBox& d = g_->domain_;
    if (u.x() < d.min().x() || u.y() < d.min().y() || u.z() < d.min().z() || u.x() >= d.max().x() ||
        u.y() >= d.max().y() || u.z() >= d.max().z())
        return -1;
    for (int l = int(masks_.size()); l >= 1; --l) {
        const Coord q(shift_down(u.x(), l), shift_down(u.y(), l), shift_down(u.z(), l));
        if (masks_[l - 1].isValueOn(q)) return l;
    }
    return 0;
}

std::optional<CellId> AdaptiveGrid::Reader::leaf(const Coord& u) const
{
    const int l = leaf_level(u);
    if (l < 0) return std::nullopt;
    return CellId{align_down(u, l), l};
}

bool AdaptiveGrid::Reader::is_leaf(const CellId& c) const
{
    if (!g_->inside(c)) return false;
    if (c.level == 0) return leaf_level(c.origin) == 0;
    if (c.level > int(masks_.size())) return false;
    const Coord q(shift_down(c.origin.x(), c.level), shift_down(c.origin.y(), c.level),
                  shift_down(c.origin.z(), c.level));
    return masks_[c.level - 1].isValueOn(q);
}

std::vector<Coord> value_cells_sparse(const AdaptiveGrid& g)
{
    // A unit cell with origin c has corners c..c+1, so it touches node box B iff c lies in B
    // grown by one voxel towards -x,-y,-z.
    const CoordBBox cells = g.unit_cells();
    std::vector<Coord> out;
    for (auto leaf = g.samples().tree().cbeginLeaf(); leaf; ++leaf) {
        CoordBBox b = leaf->getNodeBoundingBox();
        b.min().offset(-1);
        b.intersect(cells);
        for (auto it = b.begin(); it; ++it) out.push_back(*it);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace isodel::octree
