#include "volume/crowding_grid_points.h"

#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"
#include "octree/cell_function.h"
#include "octree/cell_interpolant.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace isodel::mesher {

bool voronoi_cell_misses_sigma(const Delaunay& dt, Vertex_handle g, const std::vector<Cell_handle>& cells,
                               const octree::SampleField::Reader& reader, int max_cells)
{
    const auto& field = reader.field();
    openvdb::Vec3d lo(INFINITY), hi(-INFINITY);
    for (const Cell_handle& c : cells) {
        if (dt.is_infinite(c)) return false; // on the hull: unbounded cell
        const Point w = robust_circumcenter(c);
        const openvdb::Vec3d q = field.world_to_index({w.x(), w.y(), w.z()});
        lo = openvdb::math::minComponent(lo, q);
        hi = openvdb::math::maxComponent(hi, q);
    }
    // Rounding of the circumcentres: grow the box by a hair (a larger box only makes the
    // certificate harder to pass).
    const double pad = 1e-9 * (1.0 + std::max(lo.length(), hi.length()));
    lo -= openvdb::Vec3d(pad);
    hi += openvdb::Vec3d(pad);
    const openvdb::Coord c0(int(std::floor(lo[0])), int(std::floor(lo[1])), int(std::floor(lo[2])));
    const openvdb::Coord c1(int(std::floor(hi[0])), int(std::floor(hi[1])), int(std::floor(hi[2])));
    if (std::int64_t(c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) * (c1[2] - c0[2] + 1) > max_cells) return false;
    const openvdb::Vec3d gi = field.world_to_index({g->point().x(), g->point().y(), g->point().z()});
    const openvdb::Coord gcell(int(std::floor(gi[0])), int(std::floor(gi[1])), int(std::floor(gi[2])));
    const bool inside = octree::cell_function(reader, gcell)(gi[0] - gcell[0], gi[1] - gcell[1], gi[2] - gcell[2]) >= 0;
    for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x) {
                const octree::CellFunction cf = octree::cell_function(reader, openvdb::Coord(x, y, z));
                const openvdb::Vec3d base(x, y, z);
                // The box's part inside this cell, in local coordinates; F' is multilinear on
                // each of the cell's slab/core boxes, so their corners bound it.
                const openvdb::Vec3d a = openvdb::math::maxComponent(lo - base, openvdb::Vec3d(0.0));
                const openvdb::Vec3d b = openvdb::math::minComponent(hi - base, openvdb::Vec3d(1.0));
                bool same = true;
                octree::for_each_piece(cf.slabs(), a, b, [&](int ix, int iy, int iz, const openvdb::Vec3d& pa, const openvdb::Vec3d& pb) {
                    if (!same) return;
                    const octree::Trilinear f = cf.piece(ix, iy, iz);
                    for (int n = 0; n < 8 && same; ++n) {
                        const double phi = f(n & 1 ? pb[0] : pa[0], n & 2 ? pb[1] : pa[1], n & 4 ? pb[2] : pa[2]);
                        same = (phi >= 0) == inside;
                    }
                });
                if (!same) return false;
            }
    return true;
}

std::vector<Vertex_handle> crowding_grid_points(const Delaunay& dt, const octree::SampleField& field, double reach)
{
    // Grid vertices with a surface neighbour within reach, found from the surface vertices'
    // stars in parallel (CGAL's finite_edges walk is serial and visits every edge of the
    // triangulation, nearly all far from M), then in id order.
    std::vector<Vertex_handle> surface;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        if (v->info().on_surface()) surface.push_back(v);
    std::vector<std::vector<Vertex_handle>> near_of(surface.size());
    const double r2 = reach * reach;
    for_each_star(surface, 0, surface.size(), [&](std::size_t i, const std::vector<Cell_handle>& cells) {
        for (const Cell_handle& c : cells)
            for (int j = 0; j < 4; ++j) {
                const Vertex_handle a = c->vertex(j);
                if (!dt.is_infinite(a) && a->info().kind == PointKind::Grid &&
                    CGAL::squared_distance(a->point(), surface[i]->point()) < r2)
                    near_of[i].push_back(a);
            }
    });
    std::vector<Vertex_handle> near;
    for (const auto& list : near_of) near.insert(near.end(), list.begin(), list.end());
    std::sort(near.begin(), near.end(), [](Vertex_handle x, Vertex_handle y) { return x->info().id < y->info().id; });
    near.erase(std::unique(near.begin(), near.end()), near.end());

    // Certified on the unchanged triangulation (each certificate reads g's star), in parallel.
    std::vector<char> ok(near.size(), 0);
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    for_each_star(near, 0, near.size(), [&](std::size_t i, const std::vector<Cell_handle>& cells) {
        ok[i] = voronoi_cell_misses_sigma(dt, near[i], cells, readers.local());
    });
    std::vector<Vertex_handle> out;
    for (std::size_t i = 0; i < near.size(); ++i)
        if (ok[i]) out.push_back(near[i]);
    return out;
}

} // namespace isodel::mesher
