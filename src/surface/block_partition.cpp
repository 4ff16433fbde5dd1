#include "surface/block_partition.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace isodel::mesher {
namespace {

/// The domain's cells per axis (lower corners min .. max - 1), at least one.
std::array<int, 3> domain_cells(const openvdb::CoordBBox& d)
{
    std::array<int, 3> n{};
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, d.max()[a] - d.min()[a]);
    return n;
}

std::array<int, 3> lattice_dims(const std::vector<BlockSpec>& specs)
{
    return {specs.back().index[0] + 1, specs.back().index[1] + 1, specs.back().index[2] + 1};
}

std::size_t lattice_index(const std::array<int, 3>& dims, int x, int y, int z)
{
    return (std::size_t(z) * std::size_t(dims[1]) + std::size_t(y)) * std::size_t(dims[0]) + std::size_t(x);
}

/// The block at position \p x along axis \p a (and 0 along the others): boxes and own regions
/// along a depend on the position along a only.
const BlockSpec& along(const std::vector<BlockSpec>& specs, const std::array<int, 3>& dims, int a, int x)
{
    int p[3] = {0, 0, 0};
    p[a] = x;
    return specs[lattice_index(dims, p[0], p[1], p[2])];
}

/// The positions along axis \p a whose boxes meet [lo, hi) there, as [from, to] (empty when
/// from > to): a contiguous run, since the boxes' ends grow along the lattice, found by two
/// binary searches.
std::array<int, 2> boxes_meeting(const std::vector<BlockSpec>& specs, const std::array<int, 3>& dims, int a, double lo,
                                 double hi)
{
    const auto first_where = [&](auto&& pred) { // the first position where pred holds, or dims[a]
        int l = 0, h = dims[a];
        while (l < h) {
            const int mid = l + (h - l) / 2;
            if (pred(along(specs, dims, a, mid).box)) h = mid;
            else l = mid + 1;
        }
        return l;
    };
    return {first_where([&](const openvdb::CoordBBox& box) { return box.max()[a] >= lo; }),
            first_where([&](const openvdb::CoordBBox& box) { return !(box.min()[a] < hi); }) - 1};
}

/// Blocks per axis for \p count blocks on a domain of \p cells: the factoring whose cut faces
/// have the least area, every block at least kMinBlockVoxels cells wide; the first in the
/// enumeration order (fewest blocks along x, then y) on ties.
std::array<int, 3> factor_count(int count, const std::array<int, 3>& cells)
{
    const auto fits = [&](int n, int a) { return n == 1 || std::int64_t(n) * kMinBlockVoxels <= cells[a]; };
    std::array<int, 3> best{0, 0, 0};
    double best_area = HUGE_VAL;
    for (int nx = 1; nx <= count; ++nx) {
        if (count % nx || !fits(nx, 0)) continue;
        for (int ny = 1; ny <= count / nx; ++ny) {
            if ((count / nx) % ny || !fits(ny, 1)) continue;
            const int nz = count / nx / ny;
            if (!fits(nz, 2)) continue;
            const double area = double(nx - 1) * cells[1] * cells[2] + double(ny - 1) * cells[0] * cells[2] +
                                double(nz - 1) * cells[0] * cells[1];
            if (area < best_area) {
                best_area = area;
                best = {nx, ny, nz};
            }
        }
    }
    return best;
}

/// \p n slabs of \p slices slices (work per slice in \p work): cut k at the first slice whose
/// preceding work reaches k / n of the total (integer comparison, so the same everywhere), kept
/// kMinBlockVoxels from the previous cut and from the end. Offsets from the first slice, with 0
/// and the slice count at the ends.
std::vector<int> balanced_slabs(const std::vector<std::int64_t>& work, int n)
{
    const int slices = int(work.size());
    std::int64_t total = 0;
    for (std::int64_t w : work) total += w;
    std::vector<int> cut{0};
    std::int64_t before = 0; // the work of the slices before p
    int p = 0;
    for (int k = 1; k < n; ++k) {
        if (total > 0) {
            while (p < slices && before * n < std::int64_t(k) * total) before += work[std::size_t(p++)];
        } else {
            p = int(std::int64_t(k) * slices / n);
        }
        const int lo = cut.back() + kMinBlockVoxels, hi = slices - (n - k) * kMinBlockVoxels;
        const int at = std::clamp(p, lo, hi);
        // Keep the running sum at the cut actually made.
        while (p < at) before += work[std::size_t(p++)];
        while (p > at) before -= work[std::size_t(--p)];
        cut.push_back(at);
    }
    cut.push_back(slices);
    return cut;
}

} // namespace

BlockCuts cubic_cuts(const octree::SampleField& field, int block_voxels)
{
    if (block_voxels < 1) throw InvalidInput("block size must be at least one voxel");
    const std::array<int, 3> cells = domain_cells(field.domain());
    std::array<int, 3> n{};
    for (int a = 0; a < 3; ++a) n[a] = (cells[a] + block_voxels - 1) / block_voxels;
    const double count = double(n[0]) * n[1] * n[2];
    if (count > kMaxBlocks) {
        std::ostringstream os;
        os << "block size " << block_voxels << " cuts the domain into " << count << " blocks, more than " << kMaxBlocks
           << ": choose larger blocks";
        throw InvalidInput(os.str());
    }
    BlockCuts c;
    for (int a = 0; a < 3; ++a)
        for (int x = 0; x <= n[a]; ++x) c.at[a].push_back(field.domain().min()[a] + x * block_voxels);
    return c;
}

CrossingSlices crossing_slices(const openvdb::CoordBBox& domain, const std::vector<octree::EdgePoint>& crossings)
{
    const std::array<int, 3> cells = domain_cells(domain);
    const openvdb::Coord o = domain.min();
    CrossingSlices out;
    for (int a = 0; a < 3; ++a) {
        out[a].assign(std::size_t(cells[a]), 0);
        for (const octree::EdgePoint& e : crossings) ++out[a][std::size_t(std::clamp(e.lower[a] - o[a], 0, cells[a] - 1))];
    }
    return out;
}

BlockCuts balanced_cuts(const octree::SampleField& field, int count, const std::vector<octree::EdgePoint>& crossings)
{
    return balanced_cuts(field.domain(), count, crossing_slices(field.domain(), crossings));
}

BlockCuts balanced_cuts(const openvdb::CoordBBox& domain, int count, const CrossingSlices& slices)
{
    if (count < 1 || count > kMaxBlocks)
        throw InvalidInput("block count must be in [1, " + std::to_string(int(kMaxBlocks)) + "] (got " +
                           std::to_string(count) + ")");
    const std::array<int, 3> cells = domain_cells(domain);
    const std::array<int, 3> n = factor_count(count, cells);
    if (n[0] == 0) {
        std::ostringstream os;
        os << "block count " << count << " does not cut the domain of " << cells[0] << "x" << cells[1] << "x"
           << cells[2] << " cells into blocks at least " << kMinBlockVoxels << " cells wide: choose fewer blocks";
        throw InvalidInput(os.str());
    }
    BlockCuts c;
    for (int a = 0; a < 3; ++a) {
        if (slices[a].size() != std::size_t(cells[a]))
            throw InvalidInput("balanced_cuts: the crossing counts do not match the domain's cells");
        for (int x : balanced_slabs(slices[a], n[a])) c.at[a].push_back(domain.min()[a] + x);
    }
    return c;
}

std::vector<BlockSpec> blocks_of(const BlockCuts& cuts, const std::array<int, 3>& collar)
{
    const std::array<int, 3> n = {int(cuts.at[0].size()) - 1, int(cuts.at[1].size()) - 1, int(cuts.at[2].size()) - 1};
    std::vector<BlockSpec> out;
    out.reserve(std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]));
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                BlockSpec b;
                b.index = {x, y, z};
                const int index[3] = {x, y, z};
                openvdb::Coord lo, hi;
                for (int a = 0; a < 3; ++a) {
                    lo[a] = cuts.at[a][std::size_t(index[a])];
                    hi[a] = cuts.at[a][std::size_t(index[a]) + 1];
                    b.own_lo[a] = index[a] == 0 ? -HUGE_VAL : lo[a];
                    b.own_hi[a] = index[a] == n[a] - 1 ? HUGE_VAL : hi[a];
                }
                b.core = openvdb::CoordBBox(lo, hi.offsetBy(-1));
                // Samples of the core's cells are lo .. hi; the collar grows them.
                b.box = openvdb::CoordBBox(lo.offsetBy(-collar[0], -collar[1], -collar[2]),
                                           hi.offsetBy(collar[0], collar[1], collar[2]));
                out.push_back(b);
            }
    return out;
}

std::vector<std::size_t> neighbours(const std::vector<BlockSpec>& specs, std::size_t i)
{
    const std::array<int, 3> dims = lattice_dims(specs);
    const BlockSpec& b = specs[i];
    // Per axis the positions whose boxes meet b's own region (own_lo <= q < own_hi) there.
    std::array<std::array<int, 2>, 3> run;
    for (int a = 0; a < 3; ++a) run[a] = boxes_meeting(specs, dims, a, b.own_lo[a], b.own_hi[a]);
    std::vector<std::size_t> out;
    for (int z = run[2][0]; z <= run[2][1]; ++z)
        for (int y = run[1][0]; y <= run[1][1]; ++y)
            for (int x = run[0][0]; x <= run[0][1]; ++x) {
                const std::size_t j = lattice_index(dims, x, y, z);
                if (j != i) out.push_back(j);
            }
    return out;
}

std::vector<double> block_work(const std::vector<BlockSpec>& specs, const std::vector<octree::EdgePoint>& crossings)
{
    std::vector<double> work(specs.size(), 1.0);
    const std::array<int, 3> dims = lattice_dims(specs);
    for (const octree::EdgePoint& e : crossings) {
        // The boxes holding the sample e.lower: those meeting [q, q + 1) along each axis.
        std::array<std::array<int, 2>, 3> run;
        for (int a = 0; a < 3; ++a) run[a] = boxes_meeting(specs, dims, a, e.lower[a], e.lower[a] + 1.0);
        for (int z = run[2][0]; z <= run[2][1]; ++z)
            for (int y = run[1][0]; y <= run[1][1]; ++y)
                for (int x = run[0][0]; x <= run[0][1]; ++x) work[lattice_index(dims, x, y, z)] += 1;
    }
    return work;
}

} // namespace isodel::mesher
