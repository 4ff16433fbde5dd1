#include "octree/edge_crossings.h"

namespace isodel::octree {

EdgeCrossings edge_crossings(const SampleField& field)
{
    EdgeCrossings out;
    out.crossed_cells = openvdb::MaskGrid::create();
    auto cells = out.crossed_cells->getAccessor();
    const SampleField::Reader reader(field);
    // Every edge with an endpoint in the domain; edges wholly outside it are never crossed.
    CoordBBox box = field.domain();
    box.expand(1);
    for (int z = box.min().z(); z < box.max().z(); ++z)
        for (int y = box.min().y(); y < box.max().y(); ++y)
            for (int x = box.min().x(); x < box.max().x(); ++x) {
                const Coord s(x, y, z);
                const double p0 = reader.phi(s);
                for (int axis = 0; axis < 3; ++axis) {
                    Coord s1 = s;
                    s1[axis] += 1;
                    const double p1 = reader.phi(s1);
                    if ((p0 > 0) == (p1 > 0)) continue;
                    const double t = p0 / (p0 - p1);
                    Vec3d pos(x, y, z);
                    pos[axis] += t;
                    out.points.push_back({pos, s, axis});
                    // The four cells around this edge.
                    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
                    for (int i = 0; i < 2; ++i)
                        for (int j = 0; j < 2; ++j) {
                            Coord cell = s;
                            cell[b] -= i;
                            cell[c] -= j;
                            cells.setValueOn(cell);
                        }
                }
            }
    return out;
}

} // namespace isodel::octree
