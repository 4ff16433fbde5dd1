#include "seeding/thin_tubes.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace isodel::mesher {

std::vector<openvdb::Vec3d> thin_tube_points(const octree::SampleField& field,
                                             const std::vector<openvdb::Coord>& crossed_cells)
{
    using openvdb::Coord;
    using openvdb::Vec3d;
    std::vector<std::vector<Vec3d>> found(crossed_cells.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, crossed_cells.size(), 64), [&](const auto& r) {
        auto& reader = readers.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const Coord c = crossed_cells[i];
            for (int a = 0; a < 3; ++a) {
                Coord ea(0, 0, 0);
                ea[a] = 1;
                const double p1 = reader.phi(c), p2 = reader.phi(c + ea);
                if ((p1 >= 0) != (p2 >= 0)) continue;
                const double pm = 0.5 * (p1 + p2);
                Vec3d mid = c.asVec3d();
                mid[a] += 0.5;
                std::vector<Vec3d> pts;
                for (int b = 0; b < 3 && pts.size() < 4; ++b) {
                    if (b == a) continue;
                    for (int s = -1; s <= 1; s += 2) {
                        Coord eb(0, 0, 0);
                        eb[b] = s;
                        const double q = 0.5 * (reader.phi(c + eb) + reader.phi(c + ea + eb));
                        if ((q >= 0) == (pm >= 0)) break;
                        const double t = pm / (pm - q); // F is linear on this line
                        if (!(t <= 0.5)) break;
                        Vec3d x = mid;
                        x[b] += s * t;
                        pts.push_back(x);
                    }
                }
                if (pts.size() == 4) found[i].insert(found[i].end(), pts.begin(), pts.end());
            }
        }
    });
    std::vector<Vec3d> out;
    for (auto& v : found) out.insert(out.end(), v.begin(), v.end());
    return out;
}

} // namespace isodel::mesher
