#include "mesher/point_insertion.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace isodel::mesher {
namespace {

struct Key3 {
    long x, y, z;
    bool operator==(const Key3& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct Key3Hash {
    std::size_t operator()(const Key3& k) const
    {
        return std::size_t((k.x * 73856093) ^ (k.y * 19349663) ^ (k.z * 83492791));
    }
};

} // namespace

InsertionResult insert_candidates(Delaunay& dt, FacetCache& cache, std::vector<Candidate> candidates,
                                  std::uint32_t& next_id, double cell_size)
{
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.origin < b.origin; });
    std::unordered_map<Key3, std::vector<Point>, Key3Hash> accepted;
    auto key_of = [&](const Point& p) {
        return Key3{long(std::floor(p.x() / cell_size)), long(std::floor(p.y() / cell_size)),
                    long(std::floor(p.z() / cell_size))};
    };
    InsertionResult out;
    Cell_handle hint;
    for (const Candidate& c : candidates) {
        const double r = 0.5 * c.spacing;
        const Key3 k = key_of(c.p);
        const long reach = std::min<long>(2, long(std::ceil(r / cell_size)));
        bool close = false;
        for (long dx = -reach; dx <= reach && !close; ++dx)
            for (long dy = -reach; dy <= reach && !close; ++dy)
                for (long dz = -reach; dz <= reach && !close; ++dz) {
                    auto it = accepted.find({k.x + dx, k.y + dy, k.z + dz});
                    if (it == accepted.end()) continue;
                    for (const Point& q : it->second)
                        if (CGAL::squared_distance(q, c.p) < r * r) {
                            close = true;
                            break;
                        }
                }
        if (close) continue;
        const Vertex_handle v = cache.insert(dt, c.p, VertexInfo{next_id, c.kind}, hint);
        if (v == Vertex_handle()) continue; // already a vertex
        ++next_id;
        hint = v->cell();
        out.inserted.push_back(v);
        accepted[k].push_back(c.p);
    }
    return out;
}

} // namespace isodel::mesher
