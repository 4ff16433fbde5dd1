#include "octree/far_field.h"

#include <isodel/errors.h>

#include <algorithm>

namespace isodel::octree {
namespace {

using RootT = openvdb::FloatTree::RootNodeType;
using Upper = RootT::ChildNodeType;
using Lower = Upper::ChildNodeType;
using Leaf = Lower::ChildNodeType;

/// log2 of the edge of the block of voxels that share the value found at tree depth \p depth
/// (ValueAccessor::getValueDepth: -1 background, 0 a root tile, 1 and 2 internal tiles).
int block_log2(int depth)
{
    if (depth <= 0) return int(Upper::TOTAL);
    if (depth == 1) return int(Lower::TOTAL);
    return int(Leaf::TOTAL);
}

/// Aligned cubes of edge 2^m that meet \p span, visited with \p fn(cube min); stops when fn
/// returns false.
template <class Fn> bool for_each_cube(const CoordBBox& span, int m, Fn&& fn)
{
    const Coord lo = align_down(span.min(), m), hi = align_down(span.max(), m);
    const int step = 1 << m;
    for (int z = lo.z(); z <= hi.z(); z += step)
        for (int y = lo.y(); y <= hi.y(); y += step)
            for (int x = lo.x(); x <= hi.x(); x += step)
                if (!fn(Coord(x, y, z))) return false;
    return true;
}

struct SpanScan {
    const SampleField& f;
    openvdb::FloatGrid::ConstAccessor& acc;
    const CoordBBox& span;
    SpanReading out;

    bool done() const { return out.stored || (out.positive && out.negative); }

    /// The cube of edge 2^m at \p q, met by span: one value when one tree block holds it all.
    void cube(const Coord& q, int m)
    {
        const Coord p = Coord::maxComponent(q, span.min()); // in the cube and the span
        const int depth = acc.getValueDepth(p);
        if (depth == int(openvdb::FloatTree::DEPTH) - 1) {
            out.stored = true; // an allocated leaf node: its samples vary
            return;
        }
        if (block_log2(depth) >= m) { // the aligned cube lies in the block that holds p's value
            (f.phi_of_value(acc.getValue(p)) > 0 ? out.positive : out.negative) = true;
            return;
        }
        const CoordBBox sub(q, q.offsetBy((1 << m) - 1));
        CoordBBox part = span;
        part.intersect(sub);
        for_each_cube(part, m - 1, [&](const Coord& c) {
            cube(c, m - 1);
            return !done();
        });
    }
};

} // namespace

SpanReading read_span(const SampleField& f, openvdb::FloatGrid::ConstAccessor& acc, const CoordBBox& span)
{
    SpanScan scan{f, acc, span, {}};
    CoordBBox read = span;
    if (!f.domain().isInside(span)) { // as SampleField::Reader::phi reads it
        (f.outside_phi() > 0 ? scan.out.positive : scan.out.negative) = true;
        read.intersect(f.domain());
    }
    if (!f.ring_reads_background() && !f.lattice().isInside(read)) {
        // The ring reads "outside" (sample_field.h), whatever the grid holds there.
        (f.outside_phi() > 0 ? scan.out.positive : scan.out.negative) = true;
        read.intersect(f.lattice());
    }
    if (read.empty()) return scan.out;
    int m = 0;
    while (m < int(Upper::TOTAL) && (1 << m) < std::max({read.dim().x(), read.dim().y(), read.dim().z()}))
        ++m;
    SpanScan part{f, acc, read, scan.out};
    for_each_cube(read, m, [&](const Coord& c) {
        part.cube(c, m);
        return !part.done();
    });
    return part.out;
}

std::size_t coarsen_far_field(AdaptiveGrid& g, const SampleField& f, int max_level, Interrupter* intr)
{
    if (g.max_level() > 0) throw InvalidInput("far field: the grid must be uniform");
    if (max_level < 1) return 0;
    max_level = std::min(max_level, AdaptiveGrid::kMaxLevel);
    const int root_level = std::min(max_level + 3, AdaptiveGrid::kMaxLevel);
    const CoordBBox& dom = g.domain();
    auto acc = f.grid_ptr()->getConstAccessor();
    std::size_t set = 0;

    auto emit = [&](const CellId& c) {
        if (c.level <= max_level) {
            g.set_leaf(c, true);
            ++set;
            return;
        }
        const int n = 1 << (c.level - max_level), s = 1 << max_level;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    g.set_leaf({c.origin.offsetBy(x * s, y * s, z * s), max_level}, true);
                    ++set;
                }
    };
    // Depth first from the roots: a cell is a leaf when it qualifies, else its children are
    // tried, down to level 1 (level-0 cells are leaves already). Bounded by the root count and
    // the depth root_level.
    auto place = [&](auto&& self, const CellId& c) -> void {
        if (!boxes_touch(c.nodes(), dom)) return;
        if (c.level <= int(Leaf::TOTAL) && acc.probeConstLeaf(c.origin)) return; // band: value cells
        if (g.inside(c) && read_span(f, acc, c.nodes()).one_sign()) {
            emit(c);
            return;
        }
        if (c.level <= 1) return;
        const int h = c.size() / 2;
        for (int m = 0; m < 8; ++m)
            self(self, CellId{c.origin.offsetBy((m & 1) * h, ((m >> 1) & 1) * h, ((m >> 2) & 1) * h), c.level - 1});
    };
    const Coord lo = align_down(dom.min(), root_level), hi = align_down(dom.max(), root_level);
    const int step = 1 << root_level;
    for (int z = lo.z(); z <= hi.z(); z += step)
        for (int y = lo.y(); y <= hi.y(); y += step) {
            if (intr && intr->wasInterrupted()) throw Cancelled("far field: interrupted");
            for (int x = lo.x(); x <= hi.x(); x += step)
                place(place, CellId{Coord(x, y, z), root_level});
        }
    return set;
}

} // namespace isodel::octree
