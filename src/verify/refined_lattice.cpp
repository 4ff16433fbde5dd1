#include "verify/refined_lattice.h"

#include <isodel/errors.h>

#include <algorithm>

namespace isodel::verify {

std::vector<Coord> crossed_cells(const TrilinearField& field, Coord& base)
{
    // Every sample beyond domain() reads outside_phi(), so cells whose 8 corners all lie beyond
    // it are uniform; the cells that can be mixed have lowest corner in [dom.min - 1, dom.max].
    const auto& dom = field.samples().domain();
    const Coord lo = dom.min().offsetBy(-1), hi = dom.max().offsetBy(1); // sample box
    const std::int64_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
    if (nx * ny * nz > (std::int64_t(1) << 32))
        throw InvalidInput("verify: domain too large for the dense reference scan");
    base = lo;
    // Only signs matter here: one bit per sample.
    std::vector<std::uint8_t> inside(std::size_t(nx * ny * nz));
    octree::SampleField::Reader reader(field.samples());
    for (std::int64_t k = 0; k < nz; ++k)
        for (std::int64_t j = 0; j < ny; ++j)
            for (std::int64_t i = 0; i < nx; ++i)
                inside[std::size_t(i + nx * (j + ny * k))] =
                    reader.phi(Coord(int(lo[0] + i), int(lo[1] + j), int(lo[2] + k))) >= 0.0;
    std::vector<Coord> cells;
    for (std::int64_t k = 0; k + 1 < nz; ++k)
        for (std::int64_t j = 0; j + 1 < ny; ++j)
            for (std::int64_t i = 0; i + 1 < nx; ++i) {
                int n = 0;
                for (int c = 0; c < 8; ++c)
                    n += inside[std::size_t((i + (c & 1)) + nx * ((j + ((c >> 1) & 1)) + ny * (k + ((c >> 2) & 1))))];
                if (n != 0 && n != 8) cells.emplace_back(int(lo[0] + i), int(lo[1] + j), int(lo[2] + k));
            }
    return cells;
}

std::size_t SlabPlanes::count() const
{
    std::size_t n = 0;
    for (const auto& axis : extra)
        for (const auto& slab : axis) n += slab.size();
    return n;
}

CellRefiner::CellRefiner(int R, const SlabPlanes* planes, const Coord& base) : R_(R), planes_(planes), base_(base)
{
    if (R < 1 || R > 128) throw InvalidInput("verify: refinement must be in [1, 128]");
    for (int a = 0; a < 3; ++a) {
        // offset_[a][s]: planes of the slabs before s (R each, plus their extra planes).
        const std::size_t slabs = planes ? planes->extra[std::size_t(a)].size() : 0;
        offset_[std::size_t(a)].assign(slabs + 1, 0);
        for (std::size_t sl = 0; sl < slabs; ++sl)
            offset_[std::size_t(a)][sl + 1] =
                offset_[std::size_t(a)][sl] + R + std::int64_t(planes->extra[std::size_t(a)][sl].size());
    }
}

void CellRefiner::sample(const octree::SampleField::Reader& reader, const Coord& cell)
{
    // This cell's planes: k/R, merged with the slab's extra planes.
    for (int a = 0; a < 3; ++a) {
        const auto& off = offset_[std::size_t(a)];
        const std::int64_t slab = std::int64_t(cell[a] - base_[a]);
        const std::int64_t last = std::int64_t(off.size()) - 1;
        // Cells before the first slab or past the last (the ring around the lattice) continue the
        // plane numbering with R planes per cell; only slabs in [0, last] have an offset stored.
        if (slab < 0) g_[std::size_t(a)] = off[0] + slab * R_;
        else if (slab <= last) g_[std::size_t(a)] = off[std::size_t(slab)];
        else g_[std::size_t(a)] = off[std::size_t(last)] + (slab - last) * R_;
        auto& t = t_[std::size_t(a)];
        t.clear();
        for (int k = 0; k <= R_; ++k) t.push_back(double(k) / R_);
        if (planes_ && slab >= 0 && slab < last) {
            const auto& extra = planes_->extra[std::size_t(a)][std::size_t(slab)];
            std::vector<double> merged(t.size() + extra.size());
            std::merge(t.begin(), t.end(), extra.begin(), extra.end(), merged.begin());
            t = std::move(merged);
        }
        n_[a] = int(t.size());
    }
    v_.resize(std::size_t(n_[0]) * std::size_t(n_[1]) * std::size_t(n_[2]));
    double c[8];
    reader.cell_corners(cell, c); // index i + 2j + 4k
    // x first, then y, then z; (1-t) a + t b is exact at t = 0 and t = 1 (see header).
    const int nx = n_[0], ny = n_[1], nz = n_[2];
    std::vector<double> ex(4 * std::size_t(nx)); // the 4 x-edges, indexed by (j + 2k)
    for (int e = 0; e < 4; ++e)
        for (int x = 0; x < nx; ++x) {
            const double t = t_[0][std::size_t(x)];
            ex[std::size_t(e * nx + x)] = (1.0 - t) * c[2 * e] + t * c[2 * e + 1];
        }
    for (int z = 0; z < nz; ++z) {
        const double tz = t_[2][std::size_t(z)];
        for (int y = 0; y < ny; ++y) {
            const double ty = t_[1][std::size_t(y)];
            for (int x = 0; x < nx; ++x) {
                const double y0 = (1.0 - ty) * ex[std::size_t(0 * nx + x)] + ty * ex[std::size_t(1 * nx + x)];
                const double y1 = (1.0 - ty) * ex[std::size_t(2 * nx + x)] + ty * ex[std::size_t(3 * nx + x)];
                v_[std::size_t(x + nx * (y + ny * z))] = (1.0 - tz) * y0 + tz * y1;
            }
        }
    }
}

void CellRefiner::scan_lines()
{
    const int nx = n_[0], ny = n_[1], nz = n_[2];
    lines_.resize(std::size_t(ny) * std::size_t(nz));
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y) {
            const double* v = &v_[std::size_t(nx) * std::size_t(y + ny * z)];
            LineSigns& line = lines_[std::size_t(y + ny * z)];
            line.first_change = nx - 1;
            line.last_change = -1;
            for (int x = 0; x + 1 < nx; ++x)
                if ((v[x] >= 0.0) != (v[x + 1] >= 0.0)) {
                    line.first_change = std::min(line.first_change, x);
                    line.last_change = x;
                }
            line.first_in = v[0] >= 0.0;
            line.last_in = v[nx - 1] >= 0.0;
        }
}

} // namespace isodel::verify
