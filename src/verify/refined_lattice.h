#pragma once
// Internal to verify: exact refinement of the trilinear interpolant and marching tetrahedra.
//
// Why this is a faithful reference for Sigma: the trilinear interpolant restricted to a sub-cube of
// an R x refined cell is again trilinear, with corner values equal to F at the sub-lattice points,
// so resampling loses nothing. On the refined lattice we extract the zero set of the piecewise
// linear interpolant on the Freudenthal (6 tetrahedra, common diagonal (0,0,0)-(1,1,1)) subdivision
// of every sub-cube. That subdivision is translation invariant, so neighbouring sub-cubes and
// neighbouring cells agree on shared faces and the result is a closed 2-manifold whatever the
// signs (phi >= 0 is "inside" at sub-lattice points, consistently; vertices are identified
// combinatorially by sub-lattice edge, so an exact zero never glues two sheets).
// As R grows the PL surface converges to Sigma; when R and 2R give the same topology we take it.
//
// Sub-lattice values are computed by successive linear interpolation along x, then y, then z,
// in the form (1-t) a + t b: at t = 0 or 1 this returns a or b exactly, so a point on a face or
// edge shared by two cells gets bit-identical values from both cells (consistent signs).
#include "verify/trilinear_field.h"

#include <cstdint>
#include <vector>

namespace isodel::verify {

/// Lowest corners of the unit cells whose 8 sample phi values do not all have the same sign
/// (a trilinear function takes its extreme values at cell corners, so no other cell meets Sigma).
/// Covers the domain ring: cells reaching beyond SampleField::domain() read outside_phi().
/// \p base receives the lowest corner of the scanned box (all cells are >= base).
std::vector<Coord> crossed_cells(const TrilinearField& field, Coord& base);

/// One sub-lattice edge: lower end (global sub-lattice coordinates, >= 0) and direction bits
/// (1 = x, 2 = y, 4 = z; 7 Freudenthal directions), packed into 63 bits.
inline std::uint64_t edge_key(std::int64_t x, std::int64_t y, std::int64_t z, unsigned dir)
{
    return (std::uint64_t(x) << 43) | (std::uint64_t(y) << 23) | (std::uint64_t(z) << 3) | dir;
}

/// A marching-tetrahedra triangle: three sub-lattice edge keys and the linear-interpolated
/// crossing points on them (index space).
struct RefTriangle {
    std::uint64_t key[3];
    Vec3d pos[3];
};

/// Marching tetrahedra over one cell at refinement R. Reusable (keeps its buffers).
class CellRefiner {
public:
    explicit CellRefiner(int R);
    int refine() const { return R_; }
    /// Samples the cell with lowest corner \p cell (corner phi from \p reader), then calls
    /// emit(const RefTriangle&) for every triangle. \p base: see crossed_cells().
    template <class Emit>
    void run(const octree::SampleField::Reader& reader, const Coord& cell, const Coord& base, Emit&& emit);
    /// Sub-lattice crossing points only (no triangles), each edge once per cell; for sampling Sigma.
    template <class Emit>
    void crossings(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit);

private:
    void sample(const octree::SampleField::Reader& reader, const Coord& cell);
    double val(int x, int y, int z) const { return v_[x + n_ * (y + n_ * z)]; }
    int R_, n_;
    std::vector<double> v_;
};

// ---- implementation (templates) ----

template <class Emit>
void CellRefiner::run(const octree::SampleField::Reader& reader, const Coord& cell, const Coord& base, Emit&& emit)
{
    sample(reader, cell);
    // Freudenthal tetrahedra: chains 0 -> e_a -> e_a + e_b -> 7 over the 6 axis orders.
    static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                    {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
    const std::int64_t gx = std::int64_t(cell[0] - base[0]) * R_;
    const std::int64_t gy = std::int64_t(cell[1] - base[1]) * R_;
    const std::int64_t gz = std::int64_t(cell[2] - base[2]) * R_;
    double cv[8];
    bool in[8];
    for (int z = 0; z < R_; ++z)
        for (int y = 0; y < R_; ++y)
            for (int x = 0; x < R_; ++x) {
                int nin = 0;
                for (int n = 0; n < 8; ++n) {
                    cv[n] = val(x + (n & 1), y + ((n >> 1) & 1), z + ((n >> 2) & 1));
                    in[n] = cv[n] >= 0.0;
                    nin += in[n];
                }
                if (nin == 0 || nin == 8) continue;
                // Edge between nested corner masks u < v (u subset of v): lower end u, direction u^v.
                auto vertex = [&](int u, int v, std::uint64_t& key, Vec3d& pos) {
                    if ((u & v) != u) std::swap(u, v);
                    key = edge_key(gx + x + (u & 1), gy + y + ((u >> 1) & 1), gz + z + ((u >> 2) & 1),
                                   unsigned(u ^ v));
                    const double a = cv[u], b = cv[v];
                    const double t = a / (a - b);
                    const Vec3d pu(x + (u & 1), y + ((u >> 1) & 1), z + ((u >> 2) & 1));
                    const Vec3d pv(x + (v & 1), y + ((v >> 1) & 1), z + ((v >> 2) & 1));
                    const Vec3d p = pu + (pv - pu) * t;
                    pos = Vec3d(cell[0] + p[0] / R_, cell[1] + p[1] / R_, cell[2] + p[2] / R_);
                };
                for (const auto& tet : kTets) {
                    int ins[4], outs[4], ni = 0, no = 0;
                    for (int q = 0; q < 4; ++q) (in[tet[q]] ? ins[ni++] : outs[no++]) = tet[q];
                    if (ni == 0 || ni == 4) continue;
                    RefTriangle t;
                    if (ni == 1 || ni == 3) {
                        const int lone = ni == 1 ? ins[0] : outs[0];
                        const int* o = ni == 1 ? outs : ins;
                        for (int q = 0; q < 3; ++q) vertex(lone, o[q], t.key[q], t.pos[q]);
                        emit(t);
                    } else {
                        std::uint64_t k[4];
                        Vec3d p[4];
                        vertex(ins[0], outs[0], k[0], p[0]);
                        vertex(ins[0], outs[1], k[1], p[1]);
                        vertex(ins[1], outs[1], k[2], p[2]);
                        vertex(ins[1], outs[0], k[3], p[3]);
                        t = {{k[0], k[1], k[2]}, {p[0], p[1], p[2]}};
                        emit(t);
                        t = {{k[0], k[2], k[3]}, {p[0], p[2], p[3]}};
                        emit(t);
                    }
                }
            }
}

template <class Emit>
void CellRefiner::crossings(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit)
{
    sample(reader, cell);
    static const int kDirs[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0},
                                    {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    for (int z = 0; z <= R_; ++z)
        for (int y = 0; y <= R_; ++y)
            for (int x = 0; x <= R_; ++x) {
                const double a = val(x, y, z);
                for (const auto& d : kDirs) {
                    const int X = x + d[0], Y = y + d[1], Z = z + d[2];
                    if (X > R_ || Y > R_ || Z > R_) continue;
                    const double b = val(X, Y, Z);
                    if ((a >= 0) == (b >= 0)) continue;
                    const double t = a / (a - b);
                    emit(Vec3d(cell[0] + (x + t * d[0]) / R_, cell[1] + (y + t * d[1]) / R_,
                               cell[2] + (z + t * d[2]) / R_));
                }
            }
}

} // namespace isodel::verify
