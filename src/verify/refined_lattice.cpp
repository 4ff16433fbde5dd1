#include "verify/refined_lattice.h"

#include <isodel/errors.h>

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
    const std::int64_t extent = std::max({nx, ny, nz});
    if (extent * 64 >= (std::int64_t(1) << 20))
        throw InvalidInput("verify: volume too large for the 20-bit sub-lattice edge keys");
    return cells;
}

CellRefiner::CellRefiner(int R) : R_(R), n_(R + 1), v_(std::size_t(n_) * n_ * n_)
{
    if (R < 1 || R > 64) throw InvalidInput("verify: refinement must be in [1, 64]");
}

void CellRefiner::sample(const octree::SampleField::Reader& reader, const Coord& cell)
{
    double c[8];
    reader.cell_corners(cell, c); // index i + 2j + 4k
    // x first, then y, then z; (1-t) a + t b is exact at t = 0 and t = 1 (see header).
    std::vector<double> ex(4 * std::size_t(n_)); // the 4 x-edges, indexed by (j + 2k)
    for (int e = 0; e < 4; ++e)
        for (int x = 0; x <= R_; ++x) {
            const double t = double(x) / R_;
            ex[std::size_t(e * n_ + x)] = (1.0 - t) * c[2 * e] + t * c[2 * e + 1];
        }
    for (int z = 0; z <= R_; ++z) {
        const double tz = double(z) / R_;
        for (int y = 0; y <= R_; ++y) {
            const double ty = double(y) / R_;
            for (int x = 0; x <= R_; ++x) {
                const double y0 = (1.0 - ty) * ex[std::size_t(0 * n_ + x)] + ty * ex[std::size_t(1 * n_ + x)];
                const double y1 = (1.0 - ty) * ex[std::size_t(2 * n_ + x)] + ty * ex[std::size_t(3 * n_ + x)];
                v_[std::size_t(x + n_ * (y + n_ * z))] = (1.0 - tz) * y0 + tz * y1;
            }
        }
    }
}

} // namespace isodel::verify
