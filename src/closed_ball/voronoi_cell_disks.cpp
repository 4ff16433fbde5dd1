#include "closed_ball/voronoi_cell_disks.h"

#include "octree/cell_function.h"

#include "closed_ball/cell_surface_euler.h"
#include "delaunay/circumcenter.h"
#include "delaunay/vertex_star.h"
#include "octree/box_cells.h"
#include "octree/box_sign.h"
#include "octree/cell_interpolant.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace isodel::mesher {
namespace {

using openvdb::Coord;
using openvdb::Vec3d;

/// Boxes are split down to 1/16 of a voxel; a vertex gets at most kMaxBoxes evaluated. Both bound
/// the work of evaluating a Voronoi cell that stays unsettled (the Euler characteristic fallback
/// decides); the parts that settle without evaluation (beyond a plane, or of one sign) cost one
/// test per cell of the cell's bounding box.
constexpr int kMaxDepth = 4;
constexpr std::size_t kMaxBoxes = 1 << 14;
/// A failed direction is replaced by the axis of the normals seen so far, up to kDirections
/// times: a crease (F' is only C0 across the slab boundaries, at 90 degrees or more) is a graph
/// over the plane normal to the bisector of its two sheets, not over the tangent plane of either.
constexpr int kDirections = 4;
constexpr std::size_t kMaxNormals = 256;
/// Sub-lattice of the Euler characteristic fallback (cell_surface_euler.h).
constexpr int kEulerSamplesPerVoxel = 16;

/// The certificate for one Voronoi cell (see the header).
class CellCertificate {
public:
    CellCertificate(const octree::SampleField::Reader& reader, const Vec3d& p_world, const VoronoiCellPlanes& cell)
        : reader_(reader), field_(reader.field()), p_(p_world), cell_(cell)
    {
    }

    /// The direction to start from: grad F at phi(p), the normal of Sigma where p's preimage
    /// lies, index space (zero at a critical point on Sigma). Not grad F' at p: p usually lies
    /// in a slab (an E point on a grid edge lies in two of them, a snapped grid point in three),
    /// where F' is constant across the slab's axis, so grad F' keeps only the other components
    /// (an E point's: the edge's alone). Where Sigma' crosses a lattice plane normal to the
    /// edge inside Vor(p), it is a wall in that plane's slab, parallel to the edge: a direction
    /// along the edge fails there. A cell several voxels wide (coarse leaves) holds such walls,
    /// and its run then spends the box budget (kMaxBoxes) before a later direction certifies it.
    /// Any direction is sound (the certificate proves a graph over whatever d it is given);
    /// grad F' is the fallback where grad F vanishes.
    Vec3d normal_at_p() const
    {
        const Vec3d pi = field_.world_to_index(p_);
        const Coord pc(int(std::floor(pi[0])), int(std::floor(pi[1])), int(std::floor(pi[2])));
        const octree::CellFunction cf = octree::cell_function(reader_, pc);
        const Vec3d l = pi - pc.asVec3d();
        const Vec3d g = cf.sample_gradient(l[0], l[1], l[2]);
        return g.lengthSqr() > 0 ? g : cf.gradient(l[0], l[1], l[2]);
    }

    /// Runs the certificate for direction \p d on the index-space box [lo, hi] (the bounding
    /// box of Vor(p)).
    void run(const Vec3d& lo, const Vec3d& hi, const Vec3d& d)
    {
        d_ = d;
        settled_ = true;
        boxes_ = 0;
        best_d2_ = 0;
        best_.reset();
        normals_.clear();
        octree::for_each_cell_part(lo, hi, [&](const Coord& c, const Vec3d& a, const Vec3d& b) {
            if (!(a[0] < b[0] && a[1] < b[1] && a[2] < b[2])) return;
            // A part of the bounding box beyond one of Vor(p)'s planes settles at once: F' is
            // never read there. The budget counts only boxes that are evaluated, so that a
            // Voronoi cell many voxels wide (coarse leaves) is not refused for its size alone.
            if (cell_.misses_box_surely(c.asVec3d() + a, c.asVec3d() + b)) return;
            // F' is trilinear on each of the cell's slab/core boxes (face_slabs.h).
            double corner[8];
            const octree::CellFunction cf = octree::cell_function(reader_, c, corner);
            // Where F' keeps one sign on the whole part (box_sign.h's margin), every box of it
            // settles on its corner signs: it is not expanded and evaluated.
            if (octree::sign_on_cell_box(cf, corner, a, b) != 0) return;
            octree::for_each_piece(cf.slabs(), a, b, [&](int ix, int iy, int iz, const Vec3d& pa, const Vec3d& pb) {
                if (pa[0] < pb[0] && pa[1] < pb[1] && pa[2] < pb[2]) box(cf.piece(ix, iy, iz), c, pa, pb, 0);
            });
        });
    }

    bool settled() const { return settled_; }
    const std::optional<Vec3d>& farthest_point() const { return best_; } ///< world coordinates
    /// Unit normals (index space) of Sigma at the points found in unsettled leaves in Vor(p).
    const std::vector<Vec3d>& leaf_normals() const { return normals_; }

private:
    /// \p known: F at the box's corners when the parent box has them (its 3 x 3 x 3 lattice).
    void box(const octree::Trilinear& f, const Coord& cell, const Vec3d& lo, const Vec3d& hi, int depth,
             const double* known = nullptr)
    {
        if (++boxes_ > kMaxBoxes) {
            settled_ = false;
            return;
        }
        Vec3d X[8];
        double F[8];
        int inside = 0;
        for (int k = 0; k < 8; ++k) {
            X[k] = Vec3d(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]);
            F[k] = known ? known[k] : f(X[k][0], X[k][1], X[k][2]);
            inside += F[k] >= 0; // phi >= 0 is inside (segment_walk.h's convention)
        }
        if (inside == 0 || inside == 8) return;
        // The gradients only where Sigma may pass, and only until one corner fails.
        int along = 0;
        while (along < 8 && d_.dot(f.gradient(X[along][0], X[along][1], X[along][2])) > 0) ++along;
        if (along == 8) return;
        if (cell_.misses_box(cell.asVec3d() + lo, cell.asVec3d() + hi)) return;
        if (depth == kMaxDepth) {
            settled_ = false;
            leaf_points(f, cell, X, F);
            return;
        }
        const Vec3d m = 0.5 * (lo + hi);
        // F on the lattice {lo, m, hi}^3 of the children's corners, each point evaluated once
        // (27 evaluations instead of 64; the same coordinates, so the same values): on axis d,
        // child k's corner j is lo, m or hi as bit d of k plus bit d of j is 0, 1 or 2.
        const double axis[3][3] = {{lo[0], m[0], hi[0]}, {lo[1], m[1], hi[1]}, {lo[2], m[2], hi[2]}};
        double G[27];
        for (int i = 0; i < 27; ++i) {
            const int ix = i % 3, iy = i / 3 % 3, iz = i / 9;
            G[i] = ix != 1 && iy != 1 && iz != 1 ? F[ix / 2 | (iy / 2) << 1 | (iz / 2) << 2]
                                                  : f(axis[0][ix], axis[1][iy], axis[2][iz]);
        }
        for (int k = 0; k < 8; ++k) {
            const Vec3d a(k & 1 ? m[0] : lo[0], k & 2 ? m[1] : lo[1], k & 4 ? m[2] : lo[2]);
            const Vec3d b(k & 1 ? hi[0] : m[0], k & 2 ? hi[1] : m[1], k & 4 ? hi[2] : m[2]);
            double C[8];
            for (int j = 0; j < 8; ++j)
                C[j] = G[(k & 1) + (j & 1) + 3 * ((k >> 1 & 1) + (j >> 1 & 1)) + 9 * ((k >> 2 & 1) + (j >> 2 & 1))];
            box(f, cell, a, b, depth + 1, C);
        }
    }

    /// The points of Sigma on the unsettled leaf's edges (F is linear along them) that lie in
    /// Vor(p); keeps the farthest from p.
    void leaf_points(const octree::Trilinear& f, const Coord& cell, const Vec3d X[8], const double F[8])
    {
        static const int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                          {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (const auto& e : kEdges) {
            const double f0 = F[e[0]], f1 = F[e[1]];
            if ((f0 >= 0) == (f1 >= 0)) continue;
            const Vec3d x = X[e[0]] + (f0 / (f0 - f1)) * (X[e[1]] - X[e[0]]);
            if (!cell_.contains(cell.asVec3d() + x)) continue;
            const Vec3d w = field_.index_to_world(cell.asVec3d() + x);
            const double d2 = (w - p_).lengthSqr();
            if (d2 > best_d2_) {
                best_d2_ = d2;
                best_ = w;
            }
            const Vec3d n = f.gradient(x[0], x[1], x[2]);
            if (normals_.size() < kMaxNormals && n.lengthSqr() > 0) normals_.push_back(n.unit());
        }
    }

    const octree::SampleField::Reader& reader_;
    const octree::SampleField& field_;
    Vec3d p_;
    const VoronoiCellPlanes& cell_;
    Vec3d d_;
    bool settled_ = true;
    std::size_t boxes_ = 0;
    double best_d2_ = 0;
    std::optional<Vec3d> best_;
    std::vector<Vec3d> normals_;
};

/// A direction d with d . n as large as possible in the worst case over the unit vectors \p n
/// (the axis of their smallest enclosing cone), approximated by walking from \p d toward the
/// worst-covered normal with shrinking steps (Badoiu and Clarkson's core-set iteration).
Vec3d cone_axis(const std::vector<Vec3d>& n, Vec3d d)
{
    d = d.unit();
    for (int k = 0; k < 64; ++k) {
        std::size_t worst = 0;
        for (std::size_t i = 1; i < n.size(); ++i)
            if (d.dot(n[i]) < d.dot(n[worst])) worst = i;
        const Vec3d next = d + n[worst] * (1.0 / (k + 2));
        if (!(next.lengthSqr() > 0)) break;
        d = next.unit();
    }
    return d;
}

struct CellGeometry {
    std::vector<Cell_handle> cells; ///< incident cells: their circumcentres are Vor(p)'s vertices
    std::vector<Vec3d> neighbours;  ///< world
    Vec3d lo, hi;                   ///< index-space bounding box of the Voronoi vertices
    double extent = 0;              ///< largest distance from p to a Voronoi vertex, world

    /// Bounding box and extent from the circumcentres; false if Vor(p) is unbounded.
    bool measure(const Delaunay& dt, const octree::SampleField& field, const Point& p)
    {
        lo = Vec3d(INFINITY);
        hi = Vec3d(-INFINITY);
        for (const Cell_handle& c : cells) {
            if (dt.is_infinite(c)) return false;
            const Point cc = robust_circumcenter(c);
            extent = std::max(extent, std::sqrt(CGAL::squared_distance(cc, p)));
            const Vec3d q = field.world_to_index(to_vdb(cc));
            lo = Vec3d(std::min(lo[0], q[0]), std::min(lo[1], q[1]), std::min(lo[2], q[2]));
            hi = Vec3d(std::max(hi[0], q[0]), std::max(hi[1], q[1]), std::max(hi[2], q[2]));
        }
        return true;
    }
};

} // namespace

std::vector<Candidate> voronoi_cell_disk_violations(const Delaunay& dt, const octree::SampleField& field,
                                                    std::vector<Vertex_handle>& pending, double min_extent,
                                                    VoronoiCellDiskStats* stats)
{
    // The cells and neighbours around each vertex, gathered in parallel (gather_star: no shared
    // visit marks) right before its certificate, in scratch lists each thread reuses. The
    // neighbours are sorted by id: VoronoiCellPlanes clips in their order, so the rounded
    // results must not depend on how the triangulation stores the star. (Gathered into lists
    // of all pending vertices first, the stars would cost memory for every vertex at once and
    // a second pass over them, cold in the cache.)
    enum class Verdict { Certified, Sampled, Violated, Unresolved };
    std::vector<Verdict> verdict(pending.size(), Verdict::Certified);
    std::vector<std::uint8_t> tried(pending.size(), 0); // directions per vertex
    std::vector<std::optional<Candidate>> found(pending.size());
    tbb::enumerable_thread_specific<octree::SampleField::Reader> readers([&] { return octree::SampleField::Reader(field); });
    struct Scratch {
        CellGeometry geo;
        std::vector<std::pair<std::uint32_t, Vertex_handle>> nbs; // (id, vertex)
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 16), [&](const auto& r) {
        auto& reader = readers.local();
        auto& [g, nbs] = scratch.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const Vertex_handle v = pending[i];
            gather_star(v, g.cells);
            nbs.clear();
            for (const Cell_handle& c : g.cells)
                for (int k = 0; k < 4; ++k)
                    if (c->vertex(k) != v && !dt.is_infinite(c->vertex(k)))
                        nbs.push_back({c->vertex(k)->info().id, c->vertex(k)});
            std::sort(nbs.begin(), nbs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
            nbs.erase(std::unique(nbs.begin(), nbs.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                      nbs.end());
            g.neighbours.clear();
            for (const auto& [id, w] : nbs) g.neighbours.push_back(to_vdb(w->point()));
            g.extent = 0;
            if (!g.measure(dt, field, v->point())) { // a hole in G: the voxel-bound repair's business
                verdict[i] = Verdict::Unresolved;
                continue;
            }
            const VoronoiCellPlanes planes(field, to_vdb(v->point()), g.neighbours);
            CellCertificate cert(reader, to_vdb(v->point()), planes);
            Vec3d d = cert.normal_at_p();
            if (!(d.lengthSqr() > 0)) {
                verdict[i] = Verdict::Unresolved; // a critical point on Sigma: no normal to start from
                continue;
            }
            std::vector<Vec3d> normals{d.unit()};
            bool certified = false;
            for (int k = 0; k < kDirections && !certified; ++k) {
                cert.run(g.lo, g.hi, d);
                ++tried[i];
                certified = cert.settled();
                if (certified || !cert.farthest_point()) break;
                for (const Vec3d& n : cert.leaf_normals())
                    if (normals.size() < kMaxNormals) normals.push_back(n);
                d = cone_axis(normals, d);
                // No hemisphere holds the normals seen: no direction can certify the cell.
                if (std::any_of(normals.begin(), normals.end(), [&](const Vec3d& n) { return !(d.dot(n) > 0); })) break;
            }
            if (certified) continue;
            // Not a graph over any direction tried (a fold, the tip of a thin tube, a blob around
            // one sample): count the topology of a sample instead. chi = sum over components of
            // 2 - 2 genus - boundaries, so chi < 0 means a handle (or a component with three or
            // more boundary curves); chi 0 and 2 (two boundaries, two components) pass, left to
            // the other checks: a second boundary curve is what CBP_VC's one-curve test
            // (closed_ball.cpp) and the Voronoi edge and facet tests already see, and this check
            // exists only for the handle they cannot see (paper Theorem 5 does not cover it), so
            // inserting here for chi != 1 too would only add points the paper's rules do not ask
            // for. A handle the sample shows but no point can split (none found in the cell,
            // or the cell under min_extent) stays pending and counts as unresolved.
            const int chi = sampled_euler_characteristic(reader, planes, g.lo, g.hi, kEulerSamplesPerVoxel);
            if (chi >= 0) {
                verdict[i] = Verdict::Sampled;
                continue;
            }
            if (!cert.farthest_point() || g.extent < min_extent) {
                verdict[i] = Verdict::Unresolved;
                continue;
            }
            verdict[i] = Verdict::Violated;
            const Vec3d& w = *cert.farthest_point();
            const Point q(w[0], w[1], w[2]);
            found[i] = Candidate{q, PointKind::Topology, std::sqrt(CGAL::squared_distance(q, v->point())),
                                 FacetKey{{v->info().id, 0, 0}}, v->info().id};
        }
    });
    std::vector<Candidate> out;
    std::vector<Vertex_handle> still;
    VoronoiCellDiskStats s;
    for (std::size_t i = 0; i < pending.size(); ++i) {
        s.directions += tried[i];
        if (verdict[i] == Verdict::Certified || verdict[i] == Verdict::Sampled) {
            ++(verdict[i] == Verdict::Certified ? s.certified : s.sampled);
            continue;
        }
        still.push_back(pending[i]);
        if (verdict[i] == Verdict::Unresolved) ++s.unresolved;
        else out.push_back(*found[i]);
    }
    pending.swap(still);
    if (stats) *stats = s;
    return out;
}

} // namespace isodel::mesher
