#include "verify/local_reference.h"

#include "geometry/closest_on_triangle.h"

#include <algorithm>
#include <cmath>

namespace isodel::verify {

CrossedCellSet::CrossedCellSet(const std::vector<Coord>& cells, const Coord& base) : base_(base)
{
    keys_.reserve(cells.size());
    for (const Coord& c : cells) keys_.insert(key(c));
}

bool CrossedCellSet::contains(const Coord& c) const
{
    if (c[0] < base_[0] || c[1] < base_[1] || c[2] < base_[2]) return false;
    return keys_.count(key(c)) != 0;
}

LocalReference::LocalReference(const TrilinearField& field, const CrossedCellSet& crossed, std::size_t cache_cells)
    : field_(field), crossed_(crossed), ev_(field), refiner_(kRefine, nullptr, crossed.base()), cache_cells_(cache_cells)
{
}

const LocalReference::CellTriangles& LocalReference::triangles(const Coord& c)
{
    CellTriangles* ct = &scratch_;
    if (cache_cells_ > 0) {
        const std::uint64_t key = crossed_.key(c);
        const auto it = cache_.find(key);
        if (it != cache_.end()) {
            ++hits_;
            return it->second;
        }
        if (cache_.size() >= cache_cells_) cache_.clear();
        ct = &cache_[key];
    }
    ct->tri.clear();
    ct->on_sigma.clear();
    refiner_.run(ev_.reader(), c, [&](const RefTriangle& t) {
        std::uint8_t on = 0;
        for (int v = 0; v < 3; ++v) {
            const unsigned dir = unsigned(t.key[v] & 7u);
            if (dir == 1 || dir == 2 || dir == 4) on |= std::uint8_t(1u << v);
        }
        ct->tri.push_back({field_.to_world(t.pos[0]), field_.to_world(t.pos[1]), field_.to_world(t.pos[2])});
        ct->on_sigma.push_back(on);
    });
    return *ct;
}

bool LocalReference::search(const Vec3d& p, double r, double& best)
{
    // Conservative index box of the world ball B(p, r): image of its world bounding box.
    Vec3d lo(1e300), hi(-1e300);
    for (int c = 0; c < 8; ++c) {
        const Vec3d w = p + Vec3d(c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r);
        const Vec3d x = field_.to_index(w);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], x[a]);
            hi[a] = std::max(hi[a], x[a]);
        }
    }
    Vec3d bestq;
    double bestd = 1e300;
    // The nearest vertex on Sigma bounds dist(p, Sigma) when the projection below does not
    // converge (e.g. where F is flat).
    double vertex_bound = 1e300;
    for (int k = int(std::floor(lo[2])); k <= int(std::floor(hi[2])); ++k)
        for (int j = int(std::floor(lo[1])); j <= int(std::floor(hi[1])); ++j)
            for (int i = int(std::floor(lo[0])); i <= int(std::floor(hi[0])); ++i) {
                const Coord c(i, j, k);
                if (!crossed_.contains(c)) continue;
                const CellTriangles& ct = triangles(c);
                for (std::size_t t = 0; t < ct.tri.size(); ++t) {
                    const auto& w = ct.tri[t];
                    const Vec3d q = geometry::closest_on_triangle(p, w[0], w[1], w[2]);
                    for (int v = 0; v < 3; ++v)
                        if (ct.on_sigma[t] >> v & 1u)
                            vertex_bound = std::min(vertex_bound, (w[std::size_t(v)] - p).length());
                    const double d = (q - p).length();
                    if (d < bestd) {
                        bestd = d;
                        bestq = q;
                    }
                }
            }
    if (bestd == 1e300) return false;
    Vec3d y;
    if (ev_.project(field_.to_index(bestq), y)) vertex_bound = std::min(vertex_bound, (field_.to_world(y) - p).length());
    best = std::min(best, vertex_bound);
    return true;
}

} // namespace isodel::verify
