#include "support/adaptive_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace isodel::octree {
namespace {

// Unit cell next to the line {P + x e_a} in quadrant q (offsets -1/0 in the two other axes).
Coord quadrant_cell(const Coord& p, int axis, int q)
{
    Coord u = p;
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    u[b] += (q & 1) ? 0 : -1;
    u[c] += (q & 2) ? 0 : -1;
    return u;
}

// The leaf that reports the leaf edge starting at p along axis: the first quadrant leaf that
// has the edge's line on one of its 12 edges. (Not merely the first quadrant leaf: a fine leaf's
// edge inside a coarse neighbour's face lies on no edge of the coarse leaf, which would then
// own it and drop it.)
std::optional<CellId> edge_owner(const AdaptiveGrid::Reader& r, const Coord& p, int axis)
{
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    for (int q = 0; q < 4; ++q)
        if (auto l = r.leaf(quadrant_cell(p, axis, q))) {
            const int s = l->size();
            const bool on_b = p[b] == l->origin[b] || p[b] == l->origin[b] + s;
            const bool on_c = p[c] == l->origin[c] || p[c] == l->origin[c] + s;
            if (on_b && on_c) return l;
        }
    return std::nullopt;
}

std::vector<CellId> candidate_cells(const AdaptiveGrid& g)
{
    // Coarse leaves, level-0 leaves where samples vary, and level-0 leaves next to coarse ones
    // (their hanging corners vary even inside constant regions).
    std::vector<CellId> out;
    AdaptiveGrid::Reader r(g);
    for (const Coord& u : value_cells_sparse(g))
        if (r.leaf_level(u) == 0) out.push_back({u, 0});
    for (int l = 1; l <= g.max_level(); ++l)
        for (const CellId& c : g.leaves(l)) {
            out.push_back(c);
            for (const auto& n : neighbours(r, c))
                if (n.cell.level == 0) out.push_back(n.cell);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}
} // namespace

std::optional<CellId> leaf_containing(const AdaptiveGrid::Reader& r, const Vec3d& p)
{
    const CoordBBox cells = r.grid().unit_cells();
    Coord u(int(std::floor(p.x())), int(std::floor(p.y())), int(std::floor(p.z())));
    for (int a = 0; a < 3; ++a)
        if (u[a] == cells.max()[a] + 1 && p[a] == double(u[a])) u[a] -= 1;
    return r.leaf(u);
}

std::vector<LeafEdge> leaf_edges(const InterpolantReader& ir, const CellId& c)
{
    const AdaptiveGrid::Reader& r = ir.cells();
    const int s = c.size();
    std::vector<LeafEdge> out;
    for (int axis = 0; axis < 3; ++axis) {
        const int b = (axis + 1) % 3, cc = (axis + 2) % 3;
        for (int e = 0; e < 4; ++e) {
            Coord p = c.origin;
            p[b] += (e & 1) * s;
            p[cc] += ((e >> 1) & 1) * s;
            // Split points: the extents along the axis of the leaves in the 4 quadrants around
            // the edge line (their corners and T-junctions on it). F is linear along the whole
            // coarse edge, so extra splits never change a value or a crossing.
            std::vector<int> xs{0, s};
            if (s > 1)
                for (int q = 0; q < 4; ++q)
                    for (int x = 0; x < s;) {
                        Coord u = quadrant_cell(p, axis, q);
                        u[axis] += x;
                        const auto l = r.leaf(u);
                        if (!l) { ++x; continue; }
                        const int lo = l->origin[axis] - p[axis], hi = lo + l->size();
                        if (lo > 0) xs.push_back(lo);
                        if (hi < s) xs.push_back(hi);
                        x = hi;
                    }
            std::sort(xs.begin(), xs.end());
            xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
            double prev = 0;
            for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
                LeafEdge le;
                le.start = p;
                le.start[axis] += xs[i];
                le.axis = axis;
                le.length = xs[i + 1] - xs[i];
                le.v0 = i == 0 ? ir.node_value(le.start) : prev;
                le.v1 = prev = ir.node_value(le.end());
                out.push_back(le);
            }
        }
    }
    return out;
}

bool is_crossed(const InterpolantReader& r, const SampleField& f, const CellId& c)
{
    double v[8];
    r.corners(c, v);
    bool pos = false, neg = false;
    for (double x : v) (f.phi_of_value(x) > 0 ? pos : neg) = true;
    return pos && neg;
}

std::vector<AdaptiveEdgeCrossing> adaptive_edge_crossings(const AdaptiveGrid& g, const SampleField& f)
{
    const auto cells = candidate_cells(g);
    std::vector<std::vector<AdaptiveEdgeCrossing>> per(cells.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& rg) {
                          InterpolantReader ir(g);
                          for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                              if (!is_crossed(ir, f, cells[i])) continue;
                              for (const LeafEdge& e : leaf_edges(ir, cells[i])) {
                                  const double p0 = f.phi_of_value(e.v0), p1 = f.phi_of_value(e.v1);
                                  if ((p0 > 0) == (p1 > 0)) continue;
                                  if (edge_owner(ir.cells(), e.start, e.axis) != cells[i]) continue;
                                  AdaptiveEdgeCrossing x{e, p0 / (p0 - p1), Vec3d()};
                                  x.point = Vec3d(e.start.x(), e.start.y(), e.start.z());
                                  x.point[e.axis] += x.t * e.length;
                                  per[i].push_back(x);
                              }
                          }
                      });
    std::vector<AdaptiveEdgeCrossing> out;
    for (auto& v : per) out.insert(out.end(), v.begin(), v.end());
    // The outside ring (sample_field.h): beyond the domain phi = outside_phi, so an inside node on
    // the domain boundary gives a crossing on its unit edge leading out (as edge_crossings.h).
    {
        InterpolantReader ir(g);
        const CoordBBox& d = g.domain();
        const double s = f.inside() == Inside::Above ? 1.0 : -1.0;
        const double v_out = f.effective_isovalue() + f.outside_phi() / s;
        for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
                CoordBBox face = d;
                face.min()[a] = face.max()[a] = side ? d.max()[a] : d.min()[a];
                for (auto it = face.begin(); it; ++it) {
                    const double v = ir.node_value(*it);
                    if (!(f.phi_of_value(v) > 0)) continue;
                    AdaptiveEdgeCrossing x;
                    x.edge.axis = a;
                    x.edge.length = 1;
                    x.edge.start = *it;
                    if (!side) x.edge.start[a] -= 1;
                    x.edge.v0 = side ? v : v_out;
                    x.edge.v1 = side ? v_out : v;
                    const double p0 = f.phi_of_value(x.edge.v0), p1 = f.phi_of_value(x.edge.v1);
                    x.t = p0 / (p0 - p1);
                    x.point = Vec3d(x.edge.start.x(), x.edge.start.y(), x.edge.start.z());
                    x.point[a] += x.t;
                    out.push_back(x);
                }
            }
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
        return a.edge.start != b.edge.start ? a.edge.start < b.edge.start : a.edge.axis < b.edge.axis;
    });
    return out;
}

std::vector<Coord> adaptive_protective_layer(const AdaptiveGrid& g, const SampleField& f)
{
    const auto cells = candidate_cells(g);
    std::vector<std::vector<Coord>> per(cells.size());
    auto add_corners = [](const CellId& c, std::vector<Coord>& v) {
        for (int m = 0; m < 8; ++m)
            v.push_back(c.origin.offsetBy((m & 1) * c.size(), ((m >> 1) & 1) * c.size(),
                                          ((m >> 2) & 1) * c.size()));
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& rg) {
                          InterpolantReader ir(g);
                          for (std::size_t i = rg.begin(); i < rg.end(); ++i) {
                              if (!is_crossed(ir, f, cells[i])) continue;
                              add_corners(cells[i], per[i]);
                              for (const auto& n : neighbours(ir.cells(), cells[i]))
                                  add_corners(n.cell, per[i]);
                          }
                      });
    std::vector<Coord> out;
    for (auto& v : per) out.insert(out.end(), v.begin(), v.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<SegmentPiece> walk_segment(const AdaptiveGrid::Reader& r, const Vec3d& a, const Vec3d& b)
{
    std::vector<SegmentPiece> out;
    const CoordBBox& dom = r.grid().domain();
    const Vec3d d = b - a;
    // Clip t in [0,1] to the node box of the domain (slab method).
    double t0 = 0, t1 = 1;
    for (int ax = 0; ax < 3; ++ax) {
        const double lo = dom.min()[ax], hi = dom.max()[ax];
        if (d[ax] == 0) {
            if (a[ax] < lo || a[ax] > hi) return out;
            continue;
        }
        double ta = (lo - a[ax]) / d[ax], tb = (hi - a[ax]) / d[ax];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 > t1) return out;
    const CoordBBox cells = r.grid().unit_cells();
    // The unit cell the segment enters at t: on a cell plane, the side it moves to.
    auto cell_at = [&](double t, const int* forced, const int* fval) {
        const Vec3d p = a + d * t;
        Coord u;
        for (int ax = 0; ax < 3; ++ax) {
            if (forced && forced[ax]) { u[ax] = fval[ax]; continue; }
            const double fl = std::floor(p[ax]);
            u[ax] = int(fl);
            if (d[ax] < 0 && p[ax] == fl) u[ax] -= 1;
            u[ax] = std::clamp(u[ax], cells.min()[ax], cells.max()[ax]);
        }
        return u;
    };
    double t = t0;
    Coord u = cell_at(t, nullptr, nullptr);
    for (std::size_t guard = 0; guard < (std::size_t(1) << 26); ++guard) {
        const auto leaf = r.leaf(u);
        if (!leaf) break;
        double te = std::numeric_limits<double>::infinity();
        double tax[3];
        for (int ax = 0; ax < 3; ++ax) {
            tax[ax] = std::numeric_limits<double>::infinity();
            if (d[ax] == 0) continue;
            const double plane = leaf->origin[ax] + (d[ax] > 0 ? leaf->size() : 0);
            tax[ax] = (plane - a[ax]) / d[ax];
            te = std::min(te, tax[ax]);
        }
        te = std::clamp(te, t, t1);
        out.push_back({*leaf, t, te});
        if (te >= t1) break;
        int forced[3] = {0, 0, 0}, fval[3];
        for (int ax = 0; ax < 3; ++ax)
            if (tax[ax] <= te) {
                forced[ax] = 1;
                fval[ax] = d[ax] > 0 ? leaf->origin[ax] + leaf->size() : leaf->origin[ax] - 1;
            }
        u = cell_at(te, forced, fval);
        if (!cells.isInside(u)) break;
        t = te;
    }
    return out;
}

Cubic restrict_to_segment(const InterpolantReader& r, const CellId& c, const Vec3d& a, const Vec3d& b)
{
    double v[8];
    r.corners(c, v);
    return r.local().along_segment(v, local_coords(c, a), local_coords(c, b));
}

} // namespace isodel::octree
