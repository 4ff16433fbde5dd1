#include "closed_ball/voxel_bound.h"

#include "seeding/adaptive_points.h"
#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"

#include <cmath>
#include <vector>

namespace isodel::mesher {

namespace {

/// The box of the Voronoi vertices of \p incident (v's star), false if one is infinite.
bool star_box(const Delaunay& dt, Vertex_handle v, const std::vector<Cell_handle>& incident,
              const octree::SampleField& field, openvdb::CoordBBox& cells)
{
    openvdb::Vec3d lo(INFINITY), hi(-INFINITY);
    auto add = [&](const Point& p) {
        const auto q = field.world_to_index({p.x(), p.y(), p.z()});
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], q[a]);
            hi[a] = std::max(hi[a], q[a]);
        }
    };
    add(v->point());
    for (const Cell_handle& c : incident) {
        if (dt.is_infinite(c)) return false;
        add(robust_circumcenter(c));
    }
    // Tolerance for Voronoi vertices computed in floating point on a cell face.
    constexpr double tol = 1e-7;
    constexpr double cap = 1e6; // a runaway Voronoi vertex must not overflow int
    openvdb::Coord a, b;
    for (int k = 0; k < 3; ++k) {
        a[k] = int(std::clamp(std::floor(lo[k] + tol), -cap, cap));
        b[k] = int(std::clamp(std::floor(hi[k] - tol), -cap, cap));
        if (b[k] < a[k]) b[k] = a[k];
    }
    cells = openvdb::CoordBBox(a, b);
    return true;
}

int count_in_box(const openvdb::CoordBBox& box, const octree::AdaptiveGrid::Reader* adaptive)
{
    if (adaptive) return leaves_in_box(*adaptive, box);
    const double count = double(box.dim().x()) * box.dim().y() * box.dim().z();
    return count > 1e6 ? 1000000 : int(count);
}

} // namespace

bool voronoi_cell_box(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                      openvdb::CoordBBox& cells)
{
    std::vector<Cell_handle> incident;
    dt.incident_cells(v, std::back_inserter(incident));
    return star_box(dt, v, incident, field, cells);
}

int voronoi_cell_count(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                       const octree::AdaptiveGrid::Reader* adaptive)
{
    openvdb::CoordBBox box;
    if (!voronoi_cell_box(dt, v, field, box)) return -1;
    return count_in_box(box, adaptive);
}

std::vector<int> voronoi_cell_counts(const Delaunay& dt, const std::vector<Vertex_handle>& vertices,
                                     const octree::SampleField& field, const octree::AdaptiveGrid::Reader* adaptive)
{
    // Called for every E/N point after the first Delaunay and for each round's new points
    // (Theorem 2's bound), so the boxes are measured in parallel.
    std::vector<int> out(vertices.size());
    if (dt.dimension() < 3) { // gather_star walks 3-cells
        for (std::size_t i = 0; i < vertices.size(); ++i) out[i] = voronoi_cell_count(dt, vertices[i], field, adaptive);
        return out;
    }
    std::vector<openvdb::CoordBBox> boxes(vertices.size());
    std::vector<char> bounded(vertices.size(), 0);
    for_each_star(vertices, 0, vertices.size(), [&](std::size_t i, const std::vector<Cell_handle>& cells) {
        bounded[i] = star_box(dt, vertices[i], cells, field, boxes[i]);
    });
    for (std::size_t i = 0; i < vertices.size(); ++i) out[i] = bounded[i] ? count_in_box(boxes[i], adaptive) : -1;
    return out;
}

} // namespace isodel::mesher
