#include "seeding/snap_edge_points.h"

#include <algorithm>
#include <tuple>

namespace isodel::mesher {
namespace {

bool coord_less(const openvdb::Coord& a, const openvdb::Coord& b)
{
    return std::make_tuple(a[0], a[1], a[2]) < std::make_tuple(b[0], b[1], b[2]);
}

} // namespace

bool SnapResult::is_snapped_grid_point(const openvdb::Coord& g) const
{
    return std::binary_search(grid_points.begin(), grid_points.end(), g, coord_less);
}

SnapResult snap_edge_points(const std::vector<octree::EdgePoint>& points, const octree::SampleField& field,
                            double radius, const std::function<bool(const openvdb::Coord&)>& allowed)
{
    SnapResult out;
    out.snapped.assign(points.size(), 0);
    // (grid point, E point) pairs within the radius, grouped by grid point.
    std::vector<std::pair<openvdb::Coord, std::size_t>> near;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto& e = points[i];
        openvdb::Coord upper = e.lower;
        upper[e.axis] += 1;
        const openvdb::Vec3d w = field.index_to_world(e.index_pos);
        const double d0 = (field.index_to_world(e.lower.asVec3d()) - w).length();
        const double d1 = (field.index_to_world(upper.asVec3d()) - w).length();
        const openvdb::Coord g = d0 <= d1 ? e.lower : upper;
        if (std::min(d0, d1) < radius && (!allowed || allowed(g))) near.push_back({g, i});
    }
    std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) {
        return coord_less(a.first, b.first) || (a.first == b.first && a.second < b.second);
    });
    // Crossings per grid point on its (up to 6) incident edges.
    std::vector<std::pair<openvdb::Coord, int>> incident;
    incident.reserve(2 * points.size());
    for (const auto& e : points) {
        openvdb::Coord upper = e.lower;
        upper[e.axis] += 1;
        incident.push_back({e.lower, 1});
        incident.push_back({upper, 1});
    }
    std::sort(incident.begin(), incident.end(), [](const auto& a, const auto& b) { return coord_less(a.first, b.first); });
    auto crossed_edges = [&](const openvdb::Coord& g) {
        const auto lo = std::lower_bound(incident.begin(), incident.end(), g,
                                         [](const auto& a, const openvdb::Coord& c) { return coord_less(a.first, c); });
        std::size_t n = 0;
        for (auto it = lo; it != incident.end() && it->first == g; ++it) ++n;
        return n;
    };
    for (std::size_t s = 0; s < near.size();) {
        std::size_t t = s;
        while (t < near.size() && near[t].first == near[s].first) ++t;
        // The paper's e0, e1, e2 around one sample - unless all six edges of the sample are
        // crossed: then Sigma may enclose it, and a component inside the Voronoi cell of a
        // surface vertex is invisible to every closed-ball test, and M would lose it. With an
        // uncrossed edge, no component fits in Vor(g): one small enough would enclose g, one
        // that does not encloses another sample, itself a vertex.
        // And the paper's configuration exactly: three E points, one per axis, so Sigma cuts off
        // one octant's corner at g. Two on one axis (both sides of g) mean two sheets or one
        // folded around g; snapping those merges sheets that the closed-ball tests may then
        // fail to separate, and M loses or gains a component or handle.
        bool one_per_axis = (t - s == 3);
        int axes = 0;
        for (std::size_t k = s; k < t && one_per_axis; ++k) {
            const int bit = 1 << points[near[k].second].axis;
            one_per_axis = !(axes & bit);
            axes |= bit;
        }
        if (one_per_axis && crossed_edges(near[s].first) < 6) {
            out.grid_points.push_back(near[s].first);
            for (std::size_t k = s; k < t; ++k) out.snapped[near[k].second] = 1;
        }
        s = t;
    }
    return out; // grid_points are sorted: the groups came in Coord order
}

} // namespace isodel::mesher
