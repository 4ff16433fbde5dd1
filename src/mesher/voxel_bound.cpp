#include "mesher/voxel_bound.h"

#include "mesher/circumcenter.h"

#include <cmath>
#include <vector>

namespace isodel::mesher {

int voronoi_cell_count(const Delaunay& dt, Vertex_handle v, const octree::SampleField& field)
{
    std::vector<Cell_handle> cells;
    dt.incident_cells(v, std::back_inserter(cells));
    openvdb::Vec3d lo(INFINITY), hi(-INFINITY);
    auto add = [&](const Point& p) {
        const auto q = field.world_to_index({p.x(), p.y(), p.z()});
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], q[a]);
            hi[a] = std::max(hi[a], q[a]);
        }
    };
    add(v->point());
    for (const Cell_handle& c : cells) {
        if (dt.is_infinite(c)) return -1;
        add(robust_circumcenter(c));
    }
    // Tolerance for Voronoi vertices computed in floating point on a cell face.
    constexpr double tol = 1e-7;
    double count = 1;
    for (int a = 0; a < 3; ++a) count *= std::floor(hi[a] - tol) - std::floor(lo[a] + tol) + 1;
    return count > 1e6 ? 1000000 : int(count);
}

} // namespace isodel::mesher
