#include "seeding/initial_points.h"

#include "geometry/point_lattice.h"
#include "seeding/adaptive_points.h"
#include "seeding/snap_edge_points.h"
#include "seeding/thin_tubes.h"
#include "seeding/tunnel_shoulders.h"
#include "octree/balance.h"
#include "octree/edge_crossings.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <functional>

namespace isodel::mesher {
namespace {

Point to_point(const openvdb::Vec3d& p) { return {p[0], p[1], p[2]}; }

/// A grid-edge crossing in mesh index space, on the point lattice (geometry/point_lattice.h):
/// lower + its offset along the edge, the face slabs' preimage of t (FaceSlabs::from_sample),
/// rounded to the lattice and kept inside the edge's core, so that the point lies where the
/// crossing does wherever the edge is.
openvdb::Vec3d edge_point_on_lattice(const octree::EdgePoint& e, const octree::FaceSlabs& slabs)
{
    const double step = 1.0 / kLatticePerVoxel;
    const double lo = std::max(step, std::ceil(slabs.h * kLatticePerVoxel) * step);
    const double u = slabs.h == 0 ? e.t : slabs.h + e.t * (1 - 2 * slabs.h);
    openvdb::Vec3d m = e.lower.asVec3d();
    m[e.axis] += std::clamp(on_lattice(u, step), lo, 1.0 - lo);
    return m;
}

} // namespace

InitialPoints initial_points(const octree::SampleField& field, const octree::AdaptiveGrid* adaptive,
                             const octree::AdaptiveGrid::Reader* leaves, bool use_snap, double snap_radius,
                             const std::vector<SeedPoint>& seeds, MeshStats& st, Interrupter* interrupter,
                             const openvdb::CoordBBox* cells_within)
{
    InitialPoints out;
    const octree::FaceSlabs& slabs = field.face_slabs();
    InterruptScope scope(interrupter, "points");
    // Progress in leaves: the work before Del(E u G) follows the active leaves, not the box.
    octree::EdgeCrossings e = octree::edge_crossings(
        field, [&](std::size_t done, std::size_t total) { scope.check(done, total, "leaves"); });
    if (cells_within) {
        const openvdb::CoordBBox& box = *cells_within;
        e.points.erase(std::remove_if(e.points.begin(), e.points.end(),
                                      [&](const octree::EdgePoint& p) {
                                          return !box.isInside(p.lower) || !box.isInside(p.lower.offsetBy(p.axis == 0, p.axis == 1, p.axis == 2));
                                      }),
                       e.points.end());
        e.crossed_cells.erase(std::remove_if(e.crossed_cells.begin(), e.crossed_cells.end(),
                                             [&](const openvdb::Coord& c) { return !box.isInside(c) || !box.isInside(c.offsetBy(1)); }),
                              e.crossed_cells.end());
    }
    if (adaptive) {
        // E on leaf edges only; G from the leaves (adaptive_points.h).
        e.points.erase(std::remove_if(e.points.begin(), e.points.end(),
                                      [&](const octree::EdgePoint& p) { return !on_leaf_edge(*leaves, p.lower, p.axis); }),
                       e.points.end());
        const auto uniform = octree::protective_layer(field, {}); // radius and bounds only
        out.layer.radius = uniform.radius;
        out.layer.bound_e = std::max(uniform.bound_e, octree::voronoi_bound_e(adaptive->k()));
        out.layer.bound_n = std::max(uniform.bound_n, octree::voronoi_bound_n(adaptive->k()));
        out.layer.points = adaptive_protective_layer(*adaptive, e.crossed_cells, out.layer.radius);
    } else {
        out.layer = octree::protective_layer(field, e.crossed_cells);
    }
    out.crossed_cells = std::move(e.crossed_cells);
    st.e_points = e.points.size();
    st.g_points = out.layer.points.size();
    st.bound_e = out.layer.bound_e;
    st.bound_n = out.layer.bound_n;
    // Section 5 (--snap): E points gathered around a sample give way to the sample.
    SnapResult snap;
    if (use_snap) {
        // On an adaptive grid only G points may take the place of E points.
        std::vector<openvdb::Coord> g_sorted;
        std::function<bool(const openvdb::Coord&)> in_g;
        if (adaptive) {
            g_sorted = out.layer.points;
            std::sort(g_sorted.begin(), g_sorted.end());
            in_g = [&](const openvdb::Coord& g) { return std::binary_search(g_sorted.begin(), g_sorted.end(), g); };
        }
        snap = snap_edge_points(e.points, field, snap_radius, in_g);
    }
    // G, then E, each at its index: a point's id is its slot, so the parallel fill writes the
    // same points in the same order at any thread count. Snapped E points leave no slot.
    const std::size_t n_g = out.layer.points.size(), n_e = e.points.size();
    std::vector<std::uint32_t> e_slot; // with --snap only: slots of the E points kept
    std::size_t n_e_kept = n_e;
    if (use_snap) {
        e_slot.resize(n_e);
        n_e_kept = 0;
        for (std::size_t i = 0; i < n_e; ++i) {
            e_slot[i] = std::uint32_t(n_e_kept);
            if (!snap.snapped[i]) ++n_e_kept;
        }
        st.snapped += n_e - n_e_kept;
    }
    out.points.resize(n_g + n_e_kept);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_g, 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const openvdb::Coord& g = out.layer.points[i];
            out.points[i] = {to_point(field.index_to_world(g.asVec3d())),
                             {std::uint32_t(i), snap.is_snapped_grid_point(g) ? PointKind::Snapped : PointKind::Grid}};
        }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n_e, 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (use_snap && snap.snapped[i]) continue;
            const std::size_t slot = n_g + (use_snap ? e_slot[i] : i);
            out.points[slot] = {to_point(field.index_to_world(edge_point_on_lattice(e.points[i], slabs))),
                                {std::uint32_t(slot), PointKind::Edge}};
        }
    });
    std::uint32_t id = std::uint32_t(n_g + n_e_kept);
    auto tubes = thin_tube_points(field, out.crossed_cells);
    const auto necks = tunnel_shoulder_points(field, out.crossed_cells);
    tubes.insert(tubes.end(), necks.begin(), necks.end());
    st.n_topology += tubes.size();
    const double step = lattice_step(field.min_voxel_edge());
    for (const auto& p : tubes)
        out.points.push_back({on_lattice(to_point(field.index_to_world(slabs.from_sample(p))), step), {id++, PointKind::Topology}});
    for (const SeedPoint& s : seeds) {
        ++(s.kind == PointKind::Geometry ? st.n_geometry : st.n_topology);
        out.points.push_back({Point(s.p[0], s.p[1], s.p[2]), {id++, s.kind}});
    }
    out.g_mask = GridPointMask(std::move(out.layer.mask), out.layer.points);
    return out;
}

} // namespace isodel::mesher
