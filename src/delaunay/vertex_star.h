#pragma once
// Internal: the cells around a vertex, gathered so that several threads may do it at once.
// CGAL's incident_cells marks the cells it visits inside the triangulation itself, so two
// threads gathering overlapping stars would race on those marks; this walk keeps its marks in
// a set of its own thread. The mesher's checks gather the stars of tens of thousands of vertices per
// round, and gathering them serially would leave the other threads idle for that part of it.
#include "delaunay/delaunay.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <vector>

namespace isodel::mesher {

namespace detail {

/// The set of cells gather_star has reached: open addressing on the cells' addresses, entries
/// stamped so that emptying it is one increment. One per thread, reused for every star.
class CellSet {
public:
    void clear()
    {
        size_ = 0;
        // Back to the first size after a hub: a few dozen cells spread over a large table
        // would miss the cache more often.
        if (slots_.size() != kFirstSize) {
            resize(kFirstSize);
            return;
        }
        if (++stamp_ == 0) { // wrapped: forget every old entry
            for (auto& s : slots_) s.stamp = 0;
            stamp_ = 1;
        }
    }
    /// Adds \p c; false if it was there.
    bool insert(const void* c)
    {
        if (2 * (size_ + 1) > slots_.size()) grow();
        return insert_new(c);
    }

private:
    struct Slot {
        const void* cell = nullptr;
        std::uint32_t stamp = 0;
    };
    bool insert_new(const void* c)
    {
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = (reinterpret_cast<std::uintptr_t>(c) * 0x9E3779B97F4A7C15ull) >> shift_;; i = (i + 1) & mask) {
            Slot& s = slots_[i];
            if (s.stamp != stamp_) {
                s = {c, stamp_};
                ++size_;
                return true;
            }
            if (s.cell == c) return false;
        }
    }
    void grow()
    {
        std::vector<Slot> old;
        old.swap(slots_);
        const std::uint32_t stamp = stamp_;
        resize(4 * old.size());
        size_ = 0;
        for (const Slot& s : old)
            if (s.stamp == stamp) insert_new(s.cell);
    }
    void resize(std::size_t n) // n a power of two; empties the set
    {
        slots_.assign(n, Slot());
        stamp_ = 1;
        shift_ = 64;
        for (std::size_t k = n; k > 1; k >>= 1) --shift_;
    }
    static constexpr std::size_t kFirstSize = 256;
    std::vector<Slot> slots_;
    std::uint32_t stamp_ = 0;
    std::size_t size_ = 0;
    int shift_ = 64;
};

} // namespace detail

/// The cells incident to \p v (infinite ones included) in \p out, in an order that depends only
/// on the triangulation's connectivity (a walk from v->cell()). Read-only: threads may gather
/// stars of one triangulation concurrently while nothing modifies it. Dimension 3 only.
inline void gather_star(Vertex_handle v, std::vector<Cell_handle>& out)
{
    // The cells reached, in a per-thread hash set: a star has a few dozen cells, up to
    // thousands at a hub, and a linear search of the list per neighbour would make the walk
    // quadratic in the star (tests/delaunay/test_vertex_star.cpp walks such hubs).
    static thread_local detail::CellSet reached;
    reached.clear();
    out.clear();
    out.push_back(v->cell());
    reached.insert(&*v->cell());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const Cell_handle c = out[i];
        const int iv = c->index(v);
        for (int j = 0; j < 4; ++j) {
            if (j == iv) continue;
            const Cell_handle n = c->neighbor(j); // shares the face opposite j, which contains v
            if (reached.insert(&*n)) out.push_back(n);
        }
    }
}

/// Calls f(i, cells) for every i in [begin, end), in parallel, with cells the star of
/// vertices[i] (gather_star); f may run concurrently for different i.
template <class F>
void for_each_star(const std::vector<Vertex_handle>& vertices, std::size_t begin, std::size_t end, F&& f)
{
    tbb::enumerable_thread_specific<std::vector<Cell_handle>> stars;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        auto& cells = stars.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            gather_star(vertices[i], cells);
            f(i, cells);
        }
    });
}

} // namespace isodel::mesher
