// Tet improvement (tet_improvement.h) in parallel: blocks of tets, each improved by the
// sequential Improver (tet_improver.h) on its own, merged in block order.
#include "volume/tet_improvement.h"

#include "volume/tet_improver.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace isodel::mesher {
namespace {

using tet_improver::Tet;
using tet_improver::V3;

/// One block's tets, improved on local numbering; what improve_blocks() needs to write them back.
struct BlockResult {
    std::vector<std::int32_t> global;     ///< global index of each original local vertex
    std::vector<std::int32_t> renumbered; ///< Improver::run's map, local -> output index or -1
    TetMesh out;                          ///< the improved tets (output indices)
    TetImprovementStats stats;
};

BlockResult improve_block(const TetMesh& mesh, const std::vector<std::uint32_t>& tets, std::size_t surface_vertices,
                          const TetImprovementParams& params)
{
    BlockResult r;
    for (std::uint32_t t : tets) r.global.insert(r.global.end(), mesh.tets[t].begin(), mesh.tets[t].end());
    // Local indices in global order: M's vertices (global < surface_vertices) come first, as
    // the Improver wants, and its order by vertex index is the global one.
    std::sort(r.global.begin(), r.global.end());
    r.global.erase(std::unique(r.global.begin(), r.global.end()), r.global.end());
    const auto local = [&](std::int32_t g) {
        return std::int32_t(std::lower_bound(r.global.begin(), r.global.end(), g) - r.global.begin());
    };
    TetMesh& sub = r.out;
    for (std::int32_t g : r.global) sub.vertices.push_back(mesh.vertices[std::size_t(g)]);
    for (std::uint32_t t : tets) {
        const Tet& x = mesh.tets[t];
        sub.tets.push_back({local(x[0]), local(x[1]), local(x[2]), local(x[3])});
        sub.tet_region.push_back(mesh.tet_region[t]);
    }
    const std::size_t fixed = std::size_t(local(std::int32_t(surface_vertices)));
    r.stats = tet_improver::Improver(sub, fixed, params.target_deg).run(params, &r.renumbered);
    return r;
}

/// Improves \p blocks (disjoint lists of tets) concurrently, then writes them back in block
/// order: moved vertices in place, removed ones marked in \p vertex_gone, new ones appended; each
/// block's tets replaced by its output.
void improve_blocks(TetMesh& mesh, const std::vector<std::vector<std::uint32_t>>& blocks, std::size_t surface_vertices,
                    const TetImprovementParams& params, std::vector<char>& vertex_gone, TetImprovementStats& total)
{
    std::vector<BlockResult> results(blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b)
            results[b] = improve_block(mesh, blocks[b], surface_vertices, params);
    });
    std::vector<char> tet_gone(mesh.tets.size(), 0);
    std::vector<Tet> tets;
    std::vector<std::int32_t> regions;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        BlockResult& r = results[b];
        for (std::uint32_t t : blocks[b]) tet_gone[t] = 1;
        std::vector<std::int32_t> to_global(r.out.vertices.size(), -1);
        for (std::size_t i = 0; i < r.renumbered.size(); ++i) {
            const std::int32_t o = r.renumbered[i];
            if (i < r.global.size()) {
                const auto g = std::size_t(r.global[i]);
                if (o < 0) {
                    vertex_gone[g] = 1;
                } else {
                    mesh.vertices[g] = r.out.vertices[std::size_t(o)];
                    to_global[std::size_t(o)] = std::int32_t(g);
                }
            } else if (o >= 0) {
                to_global[std::size_t(o)] = std::int32_t(mesh.vertices.size());
                mesh.vertices.push_back(r.out.vertices[std::size_t(o)]);
                vertex_gone.push_back(0);
            }
        }
        for (std::size_t t = 0; t < r.out.tets.size(); ++t) {
            Tet x = r.out.tets[t];
            for (auto& v : x) v = to_global[std::size_t(v)];
            tets.push_back(x);
            regions.push_back(r.out.tet_region[t]);
        }
        const TetImprovementStats& s = r.stats;
        total.vertices_moved += s.vertices_moved;
        total.vertices_removed += s.vertices_removed;
        total.flips_23 += s.flips_23;
        total.edges_removed += s.edges_removed;
        total.vertices_inserted += s.vertices_inserted;
        total.passes = std::max(total.passes, s.passes);
        r = BlockResult();
    }
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (!tet_gone[t]) {
            tets.push_back(mesh.tets[t]);
            regions.push_back(mesh.tet_region[t]);
        }
    mesh.tets = std::move(tets);
    mesh.tet_region = std::move(regions);
}

/// tet_improver::quality of \p x, a tet of \p mesh.
double tet_quality(const TetMesh& mesh, const Tet& x)
{
    return tet_improver::quality(mesh.vertices[std::size_t(x[0])], mesh.vertices[std::size_t(x[1])],
                                 mesh.vertices[std::size_t(x[2])], mesh.vertices[std::size_t(x[3])]);
}

/// The smallest tet_improver::smallest_angle_quality over the tets of \p mesh (kBest when it
/// has none).
double worst_smallest_angle(const TetMesh& mesh)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.tets.size(), 4096), tet_improver::kBest,
        [&](const auto& r, double w) {
            for (std::size_t t = r.begin(); t != r.end(); ++t) {
                const Tet& x = mesh.tets[t];
                w = std::min(w, tet_improver::smallest_angle_quality(
                                    mesh.vertices[std::size_t(x[0])], mesh.vertices[std::size_t(x[1])],
                                    mesh.vertices[std::size_t(x[2])], mesh.vertices[std::size_t(x[3])]));
            }
            return w;
        },
        [](double a, double b) { return std::min(a, b); });
}

/// Per tet: 1 when its quality is below \p target (the Improver's bad tets).
std::vector<char> find_bad_tets(const TetMesh& mesh, double target)
{
    std::vector<char> bad(mesh.tets.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.tets.size(), 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) bad[t] = tet_quality(mesh, mesh.tets[t]) < target;
    });
    return bad;
}

/// A tet and the block of one sweep's grid that holds it.
struct BlockedTet {
    std::array<std::int64_t, 3> block;
    std::uint32_t tet;
    bool operator<(const BlockedTet& o) const { return block < o.block || (block == o.block && tet < o.tet); }
};

/// The tets of \p mesh with their blocks in sweep \p sweep (0 or 1), sorted by block.
std::vector<BlockedTet> tets_by_block(const TetMesh& mesh, double block_size, int sweep)
{
    // Each tet's block: the cube holding its centroid, the second sweep's grid shifted by
    // half a side. Then the tets sorted by block (ties by index): each block a range.
    const double shift = 0.5 * sweep * block_size;
    std::vector<BlockedTet> items(mesh.tets.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.tets.size(), 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            BlockedTet& it = items[t];
            it.tet = std::uint32_t(t);
            for (int k = 0; k < 3; ++k) {
                double c = 0;
                for (std::int32_t v : mesh.tets[t]) c += mesh.vertices[std::size_t(v)][k];
                it.block[k] = std::int64_t(std::floor((0.25 * c + shift) / block_size));
            }
        }
    });
    tbb::parallel_sort(items.begin(), items.end());
    return items;
}

/// The blocks of \p items (sorted by block) that hold a bad tet, each as its tets in index order;
/// blocks without one have nothing to improve.
std::vector<std::vector<std::uint32_t>> blocks_with_bad_tets(const std::vector<BlockedTet>& items,
                                                             const std::vector<char>& bad)
{
    std::vector<std::vector<std::uint32_t>> blocks;
    for (std::size_t i = 0; i < items.size();) {
        std::size_t j = i;
        bool any_bad = false;
        while (j < items.size() && items[j].block == items[i].block) any_bad |= bad[items[j++].tet] != 0;
        if (any_bad) {
            blocks.emplace_back();
            for (std::size_t k = i; k < j; ++k) blocks.back().push_back(items[k].tet);
        }
        i = j;
    }
    return blocks;
}

/// Clears \p bad for the bad tets that the sweeps already gave every move.
void drop_tets_tried_in_a_sweep(const TetMesh& mesh, double block_size, std::vector<char>& bad)
{
    // A bad tet that sat well inside its block in one of the sweeps (three of its longest
    // edges from every face) had every move tried there: only the others seed the last
    // block, which is serial work (or its pieces, below), so keeping it small matters, and
    // a tet that already had every move tried in a sweep seldom gains from another try.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.tets.size(), 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            if (!bad[t]) continue;
            const Tet& x = mesh.tets[t];
            V3 c{0, 0, 0};
            double longest = 0;
            for (int i = 0; i < 4; ++i) {
                const V3& p = mesh.vertices[std::size_t(x[i])];
                for (int k = 0; k < 3; ++k) c[k] += 0.25 * p[k];
                for (int j = i + 1; j < 4; ++j)
                    longest = std::max(longest, tet_improver::norm(tet_improver::sub(p, mesh.vertices[std::size_t(x[j])])));
            }
            const double margin = 3 * longest;
            for (int sweep = 0; sweep < 2 && bad[t]; ++sweep) {
                bool inside = true;
                for (int k = 0; k < 3; ++k) {
                    const double u = c[k] + 0.5 * sweep * block_size;
                    const double off = u - std::floor(u / block_size) * block_size;
                    inside &= off >= margin && block_size - off >= margin;
                }
                if (inside) bad[t] = 0;
            }
        }
    });
}

/// Per tet: 1 when it lies within two vertex rings of a tet marked in \p bad (every vertex of
/// such a tet and of its neighbours then has its whole star among the marked tets).
std::vector<char> two_ring_tets(const TetMesh& mesh, const std::vector<char>& bad)
{
    std::vector<char> near(mesh.vertices.size(), 0), in(mesh.tets.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (bad[t])
            for (std::int32_t v : mesh.tets[t]) near[std::size_t(v)] = 1;
    for (int ring = 0; ring < 2; ++ring) {
        for (std::size_t t = 0; t < mesh.tets.size(); ++t)
            for (std::int32_t v : mesh.tets[t]) in[t] |= near[std::size_t(v)];
        for (std::size_t t = 0; t < mesh.tets.size(); ++t)
            if (in[t])
                for (std::int32_t v : mesh.tets[t]) near[std::size_t(v)] = 1;
    }
    return in;
}

/// Union-find root of \p v (with path halving).
std::uint32_t find_root(std::vector<std::uint32_t>& root, std::uint32_t v)
{
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
}

/// The tets marked in \p in, split into the pieces that share no vertex.
std::vector<std::vector<std::uint32_t>> vertex_disjoint_pieces(const TetMesh& mesh, const std::vector<char>& in)
{
    std::vector<std::uint32_t> root(mesh.vertices.size());
    for (std::size_t v = 0; v < root.size(); ++v) root[v] = std::uint32_t(v);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (in[t])
            for (int i = 1; i < 4; ++i) {
                const std::uint32_t a = find_root(root, std::uint32_t(mesh.tets[t][0])),
                                    b = find_root(root, std::uint32_t(mesh.tets[t][std::size_t(i)]));
                if (a != b) root[std::max(a, b)] = std::min(a, b);
            }
    // Pieces in the order of their first tet, each tet list in index order: the blocks and
    // their merge order are functions of the mesh alone (determinism).
    std::vector<std::int64_t> piece_of_root(mesh.vertices.size(), -1);
    std::vector<std::vector<std::uint32_t>> pieces;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!in[t]) continue;
        std::int64_t& piece = piece_of_root[find_root(root, std::uint32_t(mesh.tets[t][0]))];
        if (piece < 0) {
            piece = std::int64_t(pieces.size());
            pieces.emplace_back();
        }
        pieces[std::size_t(piece)].push_back(std::uint32_t(t));
    }
    return pieces;
}

/// The last block (see improve_tets), as the blocks to improve it as: its vertex-disjoint
/// pieces, or one block when params.split_last_block is off.
std::vector<std::vector<std::uint32_t>> last_block(const TetMesh& mesh, const TetImprovementParams& params,
                                                   double target)
{
    std::vector<char> bad = find_bad_tets(mesh, target);
    drop_tets_tried_in_a_sweep(mesh, params.block_size, bad);
    const std::vector<char> in = two_ring_tets(mesh, bad);
    // The block falls apart into pieces that share no vertex (the bad tets lie in clusters
    // along M): each piece is a block of its own, improved concurrently. Nothing a move reads
    // or changes crosses between pieces (a face or an edge of two tets is a shared vertex,
    // and a vertex moves or goes only with its whole star in the block), and the Improver
    // visits the bad tets of each piece in the same relative order either way; once a piece
    // stops changing, a further pass changes nothing in it (smoothing and insertion remember
    // their failures, the other moves are functions of the unchanged tets). So the pieces
    // end with the tets the single block gave; only the numbering of new vertices differs.
    // (As one block it would be serial work, while the sweeps before it run in parallel.)
    std::vector<std::vector<std::uint32_t>> last = vertex_disjoint_pieces(mesh, in);
    if (!params.split_last_block && last.size() > 1) {
        for (std::size_t i = 1; i < last.size(); ++i) last[0].insert(last[0].end(), last[i].begin(), last[i].end());
        std::sort(last[0].begin(), last[0].end());
        last.resize(1);
    }
    return last;
}

/// Takes the vertices marked in \p vertex_gone out of the numbering, keeping the others' order.
void drop_removed_vertices(TetMesh& mesh, const std::vector<char>& vertex_gone)
{
    std::vector<std::int32_t> renumber(mesh.vertices.size(), -1);
    std::size_t n = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!vertex_gone[v]) {
            renumber[v] = std::int32_t(n);
            mesh.vertices[n++] = mesh.vertices[v];
        }
    mesh.vertices.resize(n);
    for (auto& x : mesh.tets)
        for (auto& v : x) v = renumber[std::size_t(v)];
}

} // namespace

TetImprovementStats improve_tets(TetMesh& mesh, std::size_t surface_vertices, const TetImprovementParams& params)
{
    if (!(params.block_size > 0)) return tet_improver::Improver(mesh, surface_vertices, params.target_deg).run(params);

    const double target = -std::cos(params.target_deg * tet_improver::kPi / 180.0);
    TetImprovementStats total;
    const double worst = worst_smallest_angle(mesh);
    total.min_dihedral_before_deg = mesh.tets.empty() ? 0 : tet_improver::degrees(worst);

    // Two sweeps of blocks, each block improved on its own and concurrently: the second grid is
    // shifted by half a side, so that few bad tets sit on a block boundary in both sweeps.
    std::vector<char> vertex_gone(mesh.vertices.size(), 0);
    for (int sweep = 0; sweep < 2; ++sweep) {
        const std::vector<BlockedTet> items = tets_by_block(mesh, params.block_size, sweep);
        const std::vector<char> bad = find_bad_tets(mesh, target);
        improve_blocks(mesh, blocks_with_bad_tets(items, bad), surface_vertices, params, vertex_gone, total);
    }

    // What the block boundaries held back: one last block, the tets within two vertex rings of
    // those bad tets (every vertex of such a tet and of its neighbours then has its whole star
    // in it), improved as its vertex-disjoint pieces.
    const std::vector<std::vector<std::uint32_t>> last = last_block(mesh, params, target);
    total.last_block_pieces = last.size();
    if (!last.empty()) improve_blocks(mesh, last, surface_vertices, params, vertex_gone, total);

    // Removed vertices leave the numbering (M's keep theirs: none of them is ever removed).
    drop_removed_vertices(mesh, vertex_gone);
    return total;
}

} // namespace isodel::mesher
