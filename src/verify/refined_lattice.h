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
// Near-critical data: a saddle of F whose value is within delta of v opens or closes a neck of
// radius ~sqrt(delta) voxel, which a uniform lattice resolves only once 1/R^2 << delta (random
// volumes hold saddles within 1e-5 of v). The lattice therefore also gets planes through every
// near-critical point (SlabPlanes): the saddle is then a lattice vertex whose sign is exact, and
// around it the quadratic part of F dominates the link, so the PL neck opens or closes with F's.
// Planes are global per slab of cells, so shared faces are subdivided alike and every sub-box is
// still an exact trilinear piece of F.
//
// Sub-lattice values are computed by successive linear interpolation along x, then y, then z,
// in the form (1-t) a + t b: at t = 0 or 1 this returns a or b exactly, so a point on a face or
// edge shared by two cells gets bit-identical values from both cells (consistent signs).
#include "verify/trilinear_field.h"

#include <isodel/errors.h>

#include <algorithm>
#include <array>
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
/// crossing points on them (index space; zero from CellRefiner::run<false>, which skips them).
struct RefTriangle {
    std::uint64_t key[3];
    Vec3d pos[3];
};

/// Extra sub-lattice planes: extra[axis][s] holds sorted coordinates in (0, 1) of planes in the
/// slab of cells whose lowest corner along \p axis is base[axis] + s.
struct SlabPlanes {
    std::array<std::vector<std::vector<double>>, 3> extra;
    /// Number of planes added (over all slabs and axes).
    std::size_t count() const;
};

/// Marching tetrahedra over one cell at refinement R (plus any SlabPlanes). Reusable (keeps its
/// buffers).
class CellRefiner {
public:
    /// \p planes, if not null, must outlive the refiner; \p base is crossed_cells()'s.
    explicit CellRefiner(int R, const SlabPlanes* planes = nullptr, const Coord& base = Coord(0));
    int refine() const { return R_; }
    /// After run() or crossings(): the global sub-lattice index of the cell's first plane along
    /// \p axis, and the cell's number of planes along it.
    std::int64_t origin(int axis) const { return g_[std::size_t(axis)]; }
    int planes(int axis) const { return n_[axis]; }
    /// Samples the cell with lowest corner \p cell (corner phi from \p reader), then calls
    /// emit(const RefTriangle&) for every triangle (edge keys relative to the constructor's base).
    /// With \p kPositions false the triangles' pos are zero (topology needs only keys).
    template <bool kPositions = true, class Emit>
    void run(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit);
    /// Sub-lattice crossing points only (no triangles), each edge once per cell; for sampling Sigma.
    template <class Emit>
    void crossings(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit);

private:
    void sample(const octree::SampleField::Reader& reader, const Coord& cell);
    /// Fills lines_ from v_ (after sample()).
    void scan_lines();
    double val(int x, int y, int z) const { return v_[std::size_t(x + n_[0] * (y + n_[1] * z))]; }
    Vec3d at(int x, int y, int z) const { return Vec3d(t_[0][std::size_t(x)], t_[1][std::size_t(y)], t_[2][std::size_t(z)]); }
    int R_;
    const SlabPlanes* planes_;
    Coord base_;
    std::array<std::vector<std::int64_t>, 3> offset_; // global sub-lattice index of each slab's first plane
    std::array<std::vector<double>, 3> t_;            // this cell's plane coordinates, 0 ... 1
    std::array<std::int64_t, 3> g_{};                 // this cell's global sub-lattice offset
    int n_[3] = {0, 0, 0};                            // planes per axis (sub-cells + 1)
    std::vector<double> v_;
    /// Signs along one x-line of the sub-lattice: the sign (phi >= 0) of its first and last
    /// values and the first and last x with sign(v[x]) != sign(v[x + 1]) (n_[0] - 1 and -1 when
    /// the line keeps one sign). F is linear along the line, so it changes sign at most once up
    /// to rounding; the rule reads the computed values, so rounding cannot fool it.
    struct LineSigns {
        int first_change, last_change;
        bool first_in, last_in;
    };
    std::vector<LineSigns> lines_; // index y + n_[1] * z
};

// ---- implementation (templates) ----

template <bool kPositions, class Emit>
void CellRefiner::run(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit)
{
    sample(reader, cell);
    // Freudenthal tetrahedra: chains 0 -> e_a -> e_a + e_b -> 7 over the 6 axis orders.
    static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                    {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
    const std::int64_t gx = g_[0], gy = g_[1], gz = g_[2];
    for (int a = 0; a < 3; ++a) // edge keys hold 20 bits per coordinate (crossings() needs none)
        if (g_[std::size_t(a)] < 0 || g_[std::size_t(a)] + n_[a] >= (std::int64_t(1) << 20))
            throw InvalidInput("verify: volume too large for the 20-bit sub-lattice edge keys at this refinement");
    scan_lines();
    double cv[8];
    bool in[8];
    const int nx = n_[0], ny = n_[1];
    for (int z = 0; z + 1 < n_[2]; ++z)
        for (int y = 0; y + 1 < n_[1]; ++y) {
            // The row of sub-cubes between the 4 x-lines (y|y+1, z|z+1): a sub-cube left of every
            // line's first sign change (right of every last one) is uniform when the 4 lines start
            // (end) with one sign, so only [begin, end) can hold mixed sub-cubes. This skips no
            // mixed sub-cube (it reads the same computed values), so the triangles and their order
            // are those of the full scan.
            const LineSigns* l[4] = {&lines_[std::size_t(y + ny * z)], &lines_[std::size_t(y + 1 + ny * z)],
                                     &lines_[std::size_t(y + ny * (z + 1))], &lines_[std::size_t(y + 1 + ny * (z + 1))]};
            int first = nx - 1, last = -1;
            bool same_first = true, same_last = true;
            for (const LineSigns* line : l) {
                first = std::min(first, line->first_change);
                last = std::max(last, line->last_change);
                same_first = same_first && line->first_in == l[0]->first_in;
                same_last = same_last && line->last_in == l[0]->last_in;
            }
            const int begin = same_first ? first : 0, end = same_last ? last + 1 : nx - 1;
            for (int x = begin; x < end; ++x) {
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
                    if (!kPositions) {
                        pos = Vec3d(0.0);
                        return;
                    }
                    const double a = cv[u], b = cv[v];
                    const double t = a / (a - b);
                    const Vec3d pu = at(x + (u & 1), y + ((u >> 1) & 1), z + ((u >> 2) & 1));
                    const Vec3d pv = at(x + (v & 1), y + ((v >> 1) & 1), z + ((v >> 2) & 1));
                    const Vec3d p = pu + (pv - pu) * t;
                    pos = Vec3d(cell[0] + p[0], cell[1] + p[1], cell[2] + p[2]);
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
}

template <class Emit>
void CellRefiner::crossings(const octree::SampleField::Reader& reader, const Coord& cell, Emit&& emit)
{
    sample(reader, cell);
    static const int kDirs[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0},
                                    {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    for (int z = 0; z < n_[2]; ++z)
        for (int y = 0; y < n_[1]; ++y)
            for (int x = 0; x < n_[0]; ++x) {
                const double a = val(x, y, z);
                for (const auto& d : kDirs) {
                    const int X = x + d[0], Y = y + d[1], Z = z + d[2];
                    if (X >= n_[0] || Y >= n_[1] || Z >= n_[2]) continue;
                    const double b = val(X, Y, Z);
                    if ((a >= 0) == (b >= 0)) continue;
                    const double t = a / (a - b);
                    const Vec3d pa = at(x, y, z), pb = at(X, Y, Z);
                    emit(Vec3d(cell[0], cell[1], cell[2]) + pa + (pb - pa) * t);
                }
            }
}

} // namespace isodel::verify
