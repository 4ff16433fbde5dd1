#include "octree/adaptive_queries.h"

#include <algorithm>

namespace isodel::octree {

namespace {

Contact contact_of(const CoordBBox& a, const CoordBBox& b)
{
    int dim = 0;
    for (int ax = 0; ax < 3; ++ax)
        if (std::min(a.max()[ax], b.max()[ax]) > std::max(a.min()[ax], b.min()[ax])) ++dim;
    return Contact(dim);
}

void collect(const AdaptiveGrid::Reader& r, const CellId& c, const CellId& b, std::vector<CellId>& out)
{
    const CoordBBox cells = r.grid().unit_cells();
    for (int ax = 0; ax < 3; ++ax)
        if (b.origin[ax] + b.size() - 1 < cells.min()[ax] || b.origin[ax] > cells.max()[ax]) return;
    const int q = r.leaf_level(b.origin);
    if (q >= b.level) {
        out.push_back({align_down(b.origin, q), q});
        return;
    }
    if (b.level == 0) return;
    const int h = b.size() / 2;
    for (int m = 0; m < 8; ++m) {
        const CellId ch{b.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h),
                        b.level - 1};
        if (boxes_touch(ch.nodes(), c.nodes())) collect(r, c, ch, out);
    }
}

} // namespace

std::vector<Neighbour> neighbours(const AdaptiveGrid::Reader& r, const CellId& c, int kinds)
{
    std::vector<CellId> found;
    const int s = c.size();
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (dx || dy || dz)
                    collect(r, c, {c.origin.offsetBy(dx * s, dy * s, dz * s), c.level}, found);
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    std::vector<Neighbour> out;
    for (const CellId& n : found) {
        const Contact k = contact_of(c.nodes(), n.nodes());
        if (kinds & (1 << int(k))) out.push_back({n, k});
    }
    return out;
}

} // namespace isodel::octree
