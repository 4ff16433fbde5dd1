#include "delaunay/point_insertion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace isodel::mesher {
namespace {

struct Key3 {
    long x, y, z;
    bool operator==(const Key3& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// The points accepted so far in a batch, by hash cell: an open-addressing table (linear
/// probing, power-of-two size) from a cell to its first point, a cell's points chained through
/// `next_`. Each candidate looks up to 125 cells, nearly all empty; std::unordered_map would
/// pay a chain of cache misses for each of those misses, on the serial path of every round.
class AcceptedPoints {
public:
    AcceptedPoints() : slots_(1024) {}

    void add(const Key3& k, const Point& p)
    {
        if (2 * (used_ + 1) > slots_.size()) grow();
        Slot& s = slots_[find(k)];
        if (s.head < 0) {
            s.key = k;
            ++used_;
        }
        points_.push_back(p);
        next_.push_back(s.head);
        s.head = std::int32_t(points_.size() - 1);
    }

    /// Whether some point of cell \p k satisfies \p pred.
    template <class Pred>
    bool any_in(const Key3& k, Pred&& pred) const
    {
        for (std::int32_t i = slots_[find(k)].head; i >= 0; i = next_[std::size_t(i)])
            if (pred(points_[std::size_t(i)])) return true;
        return false;
    }

private:
    struct Slot {
        Key3 key{0, 0, 0};
        std::int32_t head = -1; ///< first point; -1: empty slot
    };

    /// The slot holding \p k, or the empty slot where it would go.
    std::size_t find(const Key3& k) const
    {
        std::uint64_t h = std::uint64_t(k.x) * 0x9E3779B97F4A7C15ull;
        h = (h ^ std::uint64_t(k.y)) * 0xC2B2AE3D27D4EB4Full;
        h = (h ^ std::uint64_t(k.z)) * 0x165667B19E3779F9ull;
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = std::size_t(h ^ (h >> 31)) & mask;; i = (i + 1) & mask)
            if (slots_[i].head < 0 || slots_[i].key == k) return i;
    }

    void grow()
    {
        std::vector<Slot> old(slots_.size() * 2);
        old.swap(slots_);
        for (const Slot& s : old)
            if (s.head >= 0) slots_[find(s.key)] = s;
    }

    std::vector<Slot> slots_;
    std::vector<Point> points_;
    std::vector<std::int32_t> next_;
    std::size_t used_ = 0;
};

} // namespace

InsertionResult insert_candidates(Delaunay& dt, FacetCache& cache, std::vector<Candidate> candidates,
                                  std::uint32_t& next_id, double cell_size)
{
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.origin < b.origin; });
    AcceptedPoints accepted;
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
                for (long dz = -reach; dz <= reach && !close; ++dz)
                    close = accepted.any_in({k.x + dx, k.y + dy, k.z + dz},
                                            [&](const Point& q) { return CGAL::squared_distance(q, c.p) < r * r; });
        if (close) continue;
        // The walk to p starts at the vertex that asked for it, near p, when it names one.
        const Cell_handle near = c.near != Candidate::kNoVertex ? cache.cell_near(dt, c.near) : Cell_handle();
        const Vertex_handle v = cache.insert(dt, c.p, VertexInfo{next_id, c.kind}, near != Cell_handle() ? near : hint);
        if (v == Vertex_handle()) continue; // already a vertex
        ++next_id;
        hint = v->cell();
        out.inserted.push_back(v);
        accepted.add(k, c.p);
    }
    return out;
}

} // namespace isodel::mesher
