#include "mesher/voxel_bound.h"

#include "mesher/adaptive_points.h"
#include "mesher/circumcenter.h"

#include <cmath>
#include <vector>

namespace isodel::mesher {

bool voronoi_cell_box(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                      openvdb::CoordBBox& cells)
{
    std::vector<Cell_handle> incident;
    dt.incident_cells(v, std::back_inserter(incident));
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

int voronoi_cell_count(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field,
                       const octree::AdaptiveGrid::Reader* adaptive)
{
    openvdb::CoordBBox box;
    if (!voronoi_cell_box(dt, v, field, box)) return -1;
    if (adaptive) return leaves_in_box(*adaptive, box);
    const double count = double(box.dim().x()) * box.dim().y() * box.dim().z();
    return count > 1e6 ? 1000000 : int(count);
}

} // namespace isodel::mesher
