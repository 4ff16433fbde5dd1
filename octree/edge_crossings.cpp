#include "octree/edge_crossings.h"

#include "octree/stored_tiles.h"
#include "octree/voxel_set.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>

namespace isodel::octree {
namespace {

// The samples are visited in blocks of 8^3 (OpenVDB's leaf size), and only in blocks where an
// edge can be crossed: where phi changes sign along an edge, its two samples differ in value,
// which happens only
//  (a) where a sample is stored in a leaf node (narrow bands, dense data),
//  (b) across the boundary of a tile (a constant value over its box, active or not),
//  (c) across the boundary of the domain or of the active box (the ring: sample_field.h), where
//      the samples beyond read "outside": crossed only where the sample inside is inside, i.e.
//      in a leaf, in a tile, or anywhere on the face if the background itself is inside.
// Everything else reads one constant (the background) on both ends of every edge. So the work
// follows the stored nodes and the tiles' faces, never the bounding box.
constexpr int kBlock = 8;

/// The block holding sample \p c (floor division: coordinates may be negative).
Coord block_of(const Coord& c)
{
    const auto down = [](int x) { return x >= 0 ? x / kBlock : -((kBlock - 1 - x) / kBlock); };
    return Coord(down(c.x()), down(c.y()), down(c.z()));
}

/// Collects the blocks whose samples may be the lower end of a crossed edge.
class CandidateBlocks {
public:
    explicit CandidateBlocks(const CoordBBox& lower_ends) : box_(lower_ends) {}

    /// The blocks of every lower end s of an edge with an end in \p b: b itself, and the samples
    /// one step below it on each axis (their edge leads into b).
    void add(CoordBBox b)
    {
        b.min() -= Coord(1);
        b.intersect(box_);
        if (b.empty()) return;
        const Coord lo = block_of(b.min()), hi = block_of(b.max());
        for (int z = lo.z(); z <= hi.z(); ++z)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int x = lo.x(); x <= hi.x(); ++x) blocks_.emplace_back(x, y, z);
    }
    /// The faces of tile \p b (a constant with phi of sign \p inside), by 8 x 8 patches, where
    /// the samples across may be on the other side of v. Tiles and leaves are aligned to the
    /// 8^3 blocks, so the block across a patch is one leaf (scanned by (a) already), or part of
    /// one tile or of the background, read at one sample, unless the domain or the active box
    /// cuts it (then it is scanned). Level sets keep their inside as large tiles side by side:
    /// their shared faces are never scanned.
    void add_tile_faces(const CoordBBox& b, bool inside, const SampleField& field, const SampleField::Reader& reader)
    {
        const openvdb::FloatTree& tree = field.grid().tree();
        for (int a = 0; a < 3; ++a) {
            const int u = (a + 1) % 3, v = (a + 2) % 3;
            for (const int side : {0, 1}) {
                const int at = side ? b.max()[a] : b.min()[a];
                for (int pu = b.min()[u]; pu <= b.max()[u]; pu += kBlock)
                    for (int pv = b.min()[v]; pv <= b.max()[v]; pv += kBlock) {
                        CoordBBox patch;
                        patch.min()[a] = patch.max()[a] = at;
                        patch.min()[u] = pu;
                        patch.max()[u] = std::min(pu + kBlock - 1, b.max()[u]);
                        patch.min()[v] = pv;
                        patch.max()[v] = std::min(pv + kBlock - 1, b.max()[v]);
                        CoordBBox across = patch;
                        across.min()[a] = across.max()[a] = at + (side ? 1 : -1);
                        const Coord n = across.min();
                        const bool uniform = field.lattice().isInside(across) && field.domain().isInside(across);
                        if (uniform && (tree.probeConstLeaf(n) || (reader.phi(n) > 0) == inside)) continue;
                        add(patch);
                    }
            }
        }
    }
    /// Sorted, without repeats: the order the blocks are scanned in does not matter (the points
    /// are sorted afterwards), but each is scanned once.
    std::vector<Coord> take()
    {
        std::sort(blocks_.begin(), blocks_.end());
        blocks_.erase(std::unique(blocks_.begin(), blocks_.end()), blocks_.end());
        return std::move(blocks_);
    }

private:
    CoordBBox box_;
    std::vector<Coord> blocks_;
};

std::vector<Coord> candidate_blocks(const SampleField& field, const CoordBBox& lower_ends)
{
    const openvdb::FloatTree& tree = field.grid().tree();
    CandidateBlocks out(lower_ends);
    // (a) the leaf nodes.
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) out.add(leaf->getNodeBoundingBox());
    // (b) the tiles (above the leaf level: a leaf's values are (a)) on the other side of v than
    // the background. A tile on the background's side can meet a sample of the other side only
    // in a leaf or in a tile of the other side, whose blocks are scanned anyway; skipping it
    // matters, since level sets keep huge tiles of the background value.
    const bool background_inside = field.phi_of_value(tree.background()) > 0;
    const SampleField::Reader reader(field);
    std::vector<CoordBBox> other_side_tiles;
    // Only tiles meeting the lower ends grown by one can add a block or meet a face of (c).
    CoordBBox near = lower_ends;
    near.expand(1);
    for_each_stored_tile(tree, near, [&](const CoordBBox& b, float value, bool) {
        if ((field.phi_of_value(value) > 0) == background_inside) return;
        out.add_tile_faces(b, !background_inside, field, reader);
        other_side_tiles.push_back(b);
    });
    // (c) the faces of the domain and of the active box, where the sample inside may be inside:
    // everywhere if the background is, else in leaves (a) and in the tiles of (b).
    for (const CoordBBox& region : {field.domain(), field.lattice()})
        for (int a = 0; a < 3; ++a)
            for (const int at : {region.min()[a], region.max()[a]}) {
                CoordBBox face = region;
                face.min()[a] = face.max()[a] = at;
                if (background_inside) {
                    out.add(face);
                    continue;
                }
                for (CoordBBox t : other_side_tiles) {
                    t.intersect(face);
                    if (!t.empty()) out.add(t);
                }
            }
    return out.take();
}

/// The crossed edges whose lower end lies in block \p b (and in \p lower_ends), in the order
/// z, y, x, axis.
void scan_block(const SampleField::Reader& reader, const Coord& b, const CoordBBox& lower_ends,
                std::vector<EdgePoint>& out)
{
    const Coord origin(b.x() * kBlock, b.y() * kBlock, b.z() * kBlock);
    CoordBBox box(origin, origin.offsetBy(kBlock - 1));
    box.intersect(lower_ends);
    for (int z = box.min().z(); z <= box.max().z(); ++z)
        for (int y = box.min().y(); y <= box.max().y(); ++y)
            for (int x = box.min().x(); x <= box.max().x(); ++x) {
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
                    out.push_back({pos, s, axis, t});
                }
            }
}

} // namespace

EdgeCrossings edge_crossings(const SampleField& field, const BlockProgress& progress)
{
    // Every edge with an end in the domain; edges wholly outside it are never crossed. Lower
    // ends s run over the domain grown by one, less its last layer on each axis.
    CoordBBox lower_ends = field.domain();
    lower_ends.expand(1);
    lower_ends.max() -= Coord(1);
    const std::vector<Coord> blocks = candidate_blocks(field, lower_ends);

    // In batches, so that progress is reported and cancellation heard on the calling thread;
    // found[i] belongs to block i whatever thread scans it.
    std::vector<std::vector<EdgePoint>> found(blocks.size());
    const std::size_t batch = std::max<std::size_t>(4096, blocks.size() / 64);
    for (std::size_t first = 0; first < blocks.size(); first += batch) {
        const std::size_t last = std::min(blocks.size(), first + batch);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 16), [&](const auto& r) {
            const SampleField::Reader reader(field);
            for (std::size_t i = r.begin(); i != r.end(); ++i) scan_block(reader, blocks[i], lower_ends, found[i]);
        });
        if (progress) progress(last, blocks.size());
    }
    EdgeCrossings out;
    std::size_t n = 0;
    for (const auto& v : found) n += v.size();
    out.points.reserve(n);
    for (auto& v : found) out.points.insert(out.points.end(), v.begin(), v.end());
    // The order of a scan of the whole box, z slowest, then y, x, axis: E's ids follow it, and
    // every later decision is keyed by ids, so the mesh is the same whatever blocks were read.
    // Keys are unique (one point per edge), so the parallel sort's result is the sorted order.
    tbb::parallel_sort(out.points.begin(), out.points.end(), [](const EdgePoint& p, const EdgePoint& q) {
        const std::array<int, 4> a{{p.lower.z(), p.lower.y(), p.lower.x(), p.axis}};
        const std::array<int, 4> b{{q.lower.z(), q.lower.y(), q.lower.x(), q.axis}};
        return a < b;
    });
    // The four cells around an edge reach one below its lower end on the other two axes.
    const CoordBBox bounds = union_of_boxes(out.points.size(), [&](std::size_t i) {
        return CoordBBox(out.points[i].lower.offsetBy(-1), out.points[i].lower);
    });
    out.crossed_cells = voxel_set(out.points.size(), 4, bounds, [&](std::size_t i, auto& cells) {
        const EdgePoint& p = out.points[i];
        for (const Coord& cell : cells_around_edge(p.lower, p.axis)) cells.setValueOn(cell);
    }).coords;
    return out;
}

} // namespace isodel::octree
