#include "seeding/adaptive_points.h"

#include "octree/edge_crossings.h"

#include "octree/adaptive_queries.h"

#include <algorithm>

namespace isodel::mesher {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using octree::CellId;

bool on_boundary(int x, int lo, int size) { return x == lo || x == lo + size; }

void add_corners(const CellId& c, openvdb::MaskGrid::Accessor& acc)
{
    const int s = c.size();
    for (int m = 0; m < 8; ++m) acc.setValueOn(c.origin.offsetBy((m & 1) * s, ((m >> 1) & 1) * s, ((m >> 2) & 1) * s));
}

/// The leaf holding unit cell \p u, or the unit cell itself beyond the domain.
CellId leaf_or_unit(const octree::AdaptiveGrid::Reader& r, const Coord& u)
{
    const auto l = r.leaf(u);
    return l ? *l : CellId{u, 0};
}

} // namespace

bool on_leaf_edge(const octree::AdaptiveGrid::Reader& r, const Coord& lower, int axis)
{
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    // The four unit cells around the edge's line; the edge is a leaf edge iff it lies on two
    // boundary planes of one of their leaves.
    for (const Coord& u : octree::cells_around_edge(lower, axis)) {
        const CellId l = leaf_or_unit(r, u);
        if (on_boundary(lower[b], l.origin[b], l.size()) && on_boundary(lower[c], l.origin[c], l.size())) return true;
    }
    return false;
}

std::vector<Coord> adaptive_protective_layer(const octree::AdaptiveGrid& g, const std::vector<Coord>& crossed,
                                             const std::array<int, 3>& radius)
{
    const octree::AdaptiveGrid::Reader r(g);
    const CoordBBox& dom = g.domain();
    openvdb::MaskGrid mask;
    auto acc = mask.getAccessor();
    std::vector<CellId> ring;
    for (const Coord& u : crossed) {
        if (const auto l = r.leaf(u)) ring.push_back(*l);
        // Beyond the domain (and for leaves on its boundary) the lattice is the unit lattice.
        const CoordBBox block(u.offsetBy(-radius[0], -radius[1], -radius[2]),
                              u.offsetBy(1 + radius[0], 1 + radius[1], 1 + radius[2]));
        if (dom.isInside(block)) continue;
        for (auto n = block.begin(); n; ++n)
            if (!dom.isInside(*n)) acc.setValueOn(*n);
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    std::vector<CellId> all = ring;
    const int rings = std::max({radius[0], radius[1], radius[2]});
    for (int i = 0; i < rings; ++i) {
        std::vector<CellId> next;
        for (const CellId& c : ring)
            for (const auto& n : octree::neighbours(r, c)) next.push_back(n.cell);
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::vector<CellId> fresh;
        std::set_difference(next.begin(), next.end(), all.begin(), all.end(), std::back_inserter(fresh));
        std::vector<CellId> merged;
        std::merge(all.begin(), all.end(), fresh.begin(), fresh.end(), std::back_inserter(merged));
        all.swap(merged);
        ring.swap(fresh);
    }
    for (const CellId& c : all) add_corners(c, acc);
    std::vector<Coord> out;
    out.reserve(mask.activeVoxelCount());
    for (auto it = mask.cbeginValueOn(); it; ++it) out.push_back(it.getCoord());
    return out;
}

namespace {

void count_leaves(const octree::AdaptiveGrid::Reader& r, const CellId& c, const CoordBBox& box, int& n)
{
    if (c.level == 0 || r.is_leaf(c)) {
        ++n;
        return;
    }
    const int h = c.size() / 2;
    for (int m = 0; m < 8; ++m) {
        const CellId child{c.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h), c.level - 1};
        const CoordBBox span(child.origin, child.origin.offsetBy(h - 1)); // its unit cells
        if (span.hasOverlap(box)) count_leaves(r, child, box, n);
    }
}

} // namespace

int leaves_in_box(const octree::AdaptiveGrid::Reader& r, const CoordBBox& cells)
{
    CoordBBox inside = cells;
    inside.intersect(r.grid().unit_cells());
    const double outside = double(cells.volume()) - (inside.empty() ? 0.0 : double(inside.volume()));
    if (outside > 1e6) return 1000000;
    int n = int(outside);
    if (inside.empty()) return n;
    // Top-down from the coarsest level: a unit cell reached at level 0 has no leaf above it.
    const int top = r.grid().max_level();
    const Coord lo(octree::align_down(inside.min(), top)), hi(octree::align_down(inside.max(), top));
    const int s = 1 << top;
    for (int z = lo.z(); z <= hi.z(); z += s)
        for (int y = lo.y(); y <= hi.y(); y += s)
            for (int x = lo.x(); x <= hi.x(); x += s) {
                count_leaves(r, CellId{Coord(x, y, z), top}, inside, n);
                if (n > 1000000) return 1000000;
            }
    return n;
}

bool is_leaf_node(const octree::AdaptiveGrid::Reader& r, const Coord& n)
{
    for (int m = 0; m < 8; ++m) {
        const CellId l = leaf_or_unit(r, n.offsetBy(-(m & 1), -((m >> 1) & 1), -((m >> 2) & 1)));
        bool corner = true;
        for (int a = 0; a < 3; ++a) corner = corner && on_boundary(n[a], l.origin[a], l.size());
        if (corner) return true;
    }
    return false;
}


} // namespace isodel::mesher
