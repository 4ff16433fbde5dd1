// Check 4: every triangle abc of M is a face of a Delaunay triangulation of V(M), i.e. some
// closed ball has a, b, c on its boundary and no vertex of M in its interior.
//
// Fast path: abc is a facet of CGAL's Del(V(M)) (EPICK: exact predicates, symbolic perturbation
// for cospherical points) -> certified. Otherwise (cospherical grid-derived points make CGAL pick
// one of several valid triangulations) we decide the empty-ball question exactly:
//   the centres of spheres through a, b, c are the line c(l) = c0 + l n (c0 the circumcentre of
//   abc, n = (b - a) x (c - a)); a point q is not inside the ball iff
//       |c(l) - q|^2 >= |c(l) - a|^2   <=>   2 n.(a - q) l >= |c0 - a|^2 - |c0 - q|^2,
//   a closed half-line in l (or, when n.(a - q) = 0, a condition independent of l). An empty ball
//   exists iff the intersection over all q is non-empty. Arithmetic: EPECK (exact rationals).
// Which q: we start with the DT neighbours of a, b and c (the only points that can make abc a
// non-facet locally), take the smallest ball allowed by them (l closest to 0 in the feasible
// interval), and check that ball against EVERY vertex of M inside its bounding box (a uniform grid
// finds them; points outside the box are certainly outside the ball). Any violator is added to the
// constraints and we repeat. So "empty ball" is only reported with a witness ball checked against
// all points, and "no empty ball" only with an infeasible set of real constraints: both exact.
// Limitation (documented): each triangle is judged on its own; whether all of M's triangles fit
// in ONE Delaunay triangulation (e.g. both diagonals of a cocircular quad) is not checked.
#include "verify/checks.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace isodel::verify {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::int32_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;

/// Uniform grid over points for box queries.
class PointGrid {
public:
    explicit PointGrid(const std::vector<std::array<double, 3>>& pts) : pts_(pts)
    {
        for (int a = 0; a < 3; ++a) {
            lo_[a] = 1e300;
            hi_[a] = -1e300;
        }
        for (const auto& p : pts)
            for (int a = 0; a < 3; ++a) {
                lo_[a] = std::min(lo_[a], p[a]);
                hi_[a] = std::max(hi_[a], p[a]);
            }
        const double diag = std::sqrt((hi_[0] - lo_[0]) * (hi_[0] - lo_[0]) + (hi_[1] - lo_[1]) * (hi_[1] - lo_[1]) +
                                      (hi_[2] - lo_[2]) * (hi_[2] - lo_[2]));
        h_ = std::max(diag / std::cbrt(double(std::max<std::size_t>(pts.size(), 1))) * 2.0, 1e-300);
        for (std::size_t i = 0; i < pts.size(); ++i) cells_[key(cell(pts[i][0], 0), cell(pts[i][1], 1), cell(pts[i][2], 2))].push_back(std::int32_t(i));
    }
    /// Calls f(index) for every point in the box [c - r, c + r].
    template <class F>
    void box(const double c[3], double r, F&& f) const
    {
        long lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = cell(std::max(c[a] - r, lo_[a]), a);
            hi[a] = cell(std::min(c[a] + r, hi_[a]), a);
            if (c[a] + r < lo_[a] || c[a] - r > hi_[a]) return;
        }
        for (long k = lo[2]; k <= hi[2]; ++k)
            for (long j = lo[1]; j <= hi[1]; ++j)
                for (long i = lo[0]; i <= hi[0]; ++i) {
                    auto it = cells_.find(key(i, j, k));
                    if (it == cells_.end()) continue;
                    for (std::int32_t p : it->second) {
                        const auto& q = pts_[std::size_t(p)];
                        if (std::abs(q[0] - c[0]) <= r && std::abs(q[1] - c[1]) <= r && std::abs(q[2] - c[2]) <= r) f(p);
                    }
                }
    }

private:
    long cell(double x, int a) const { return long(std::floor((x - lo_[a]) / h_)); }
    static std::uint64_t key(long i, long j, long k)
    {
        return (std::uint64_t(i) << 42) ^ (std::uint64_t(j) << 21) ^ std::uint64_t(k);
    }
    const std::vector<std::array<double, 3>>& pts_;
    double lo_[3], hi_[3], h_;
    std::unordered_map<std::uint64_t, std::vector<std::int32_t>> cells_;
};

/// Exact empty-ball decision for triangle (ia, ib, ic); see the file comment.
bool has_empty_ball(const std::vector<std::array<double, 3>>& V, const PointGrid& grid, std::int32_t ia,
                    std::int32_t ib, std::int32_t ic, std::vector<std::int32_t> candidates)
{
    auto P = [&](std::int32_t i) {
        const auto& p = V[std::size_t(i)];
        return EK::Point_3(p[0], p[1], p[2]);
    };
    const EK::Point_3 a = P(ia), b = P(ib), c = P(ic);
    const EK::Point_3 c0 = CGAL::circumcenter(a, b, c);
    const EK::Vector_3 n = CGAL::cross_product(b - a, c - a);
    const EK::FT ra2 = CGAL::squared_distance(c0, a);
    std::optional<EK::FT> L, U;
    bool infeasible = false;
    auto constrain = [&](std::int32_t iq) {
        const EK::Point_3 q = P(iq);
        const EK::FT alpha = 2 * (n * (a - q));
        const EK::FT beta = ra2 - CGAL::squared_distance(c0, q);
        if (CGAL::is_zero(alpha)) {
            if (CGAL::is_positive(beta)) infeasible = true; // coplanar, strictly inside the circle
        } else if (CGAL::is_positive(alpha)) {
            const EK::FT l = beta / alpha;
            if (!L || l > *L) L = l;
        } else {
            const EK::FT l = beta / alpha;
            if (!U || l < *U) U = l;
        }
        if (L && U && *L > *U) infeasible = true;
    };
    for (std::int32_t q : candidates)
        if (q != ia && q != ib && q != ic) constrain(q);
    for (std::size_t round = 0; round <= V.size() && !infeasible; ++round) {
        // Smallest admissible ball: l in [L, U] closest to 0.
        EK::FT l = 0;
        if (L && *L > l) l = *L;
        if (U && *U < l) l = *U;
        const EK::Point_3 centre = c0 + l * n;
        const double cd[3] = {CGAL::to_double(centre.x()), CGAL::to_double(centre.y()), CGAL::to_double(centre.z())};
        const double r = std::sqrt(CGAL::to_double(ra2 + l * l * n.squared_length()));
        // The box only needs to contain the exact ball: pad for the rounding of centre and r.
        const double margin = 1e-6 * (r + std::abs(cd[0]) + std::abs(cd[1]) + std::abs(cd[2])) + 1e-300;
        std::int32_t violator = -1;
        grid.box(cd, r + margin, [&](std::int32_t iq) {
            if (violator >= 0 || iq == ia || iq == ib || iq == ic) return;
            const EK::Point_3 q = P(iq);
            if (CGAL::squared_distance(centre, q) < CGAL::squared_distance(centre, a)) violator = iq;
        });
        if (violator < 0) return true; // witness ball checked against every point
        constrain(violator);
    }
    return false;
}

} // namespace

DelaunayReport delaunay_conformity(const SurfaceMesh& mesh)
{
    const auto t0 = std::chrono::steady_clock::now();
    DelaunayReport rep;
    rep.checked = true;
    rep.triangles = mesh.triangles.size();
    const auto& V = mesh.vertices;
    std::vector<std::pair<K::Point_3, std::int32_t>> pts;
    pts.reserve(V.size());
    for (std::size_t i = 0; i < V.size(); ++i) pts.emplace_back(K::Point_3(V[i][0], V[i][1], V[i][2]), std::int32_t(i));
    DT dt(pts.begin(), pts.end()); // spatially sorted insertion
    std::vector<DT::Vertex_handle> handle(V.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) handle[std::size_t(v->info())] = v;
    for (std::size_t i = 0; i < V.size(); ++i) {
        if (handle[i] != DT::Vertex_handle()) continue;
        // A duplicate position: CGAL kept another index; find its vertex.
        DT::Locate_type lt;
        int li, lj;
        auto c = dt.locate(pts[i].first, lt, li, lj);
        if (lt == DT::VERTEX) handle[i] = c->vertex(li);
    }
    PointGrid grid(V);
    for (const auto& t : mesh.triangles) {
        const auto va = handle[std::size_t(t[0])], vb = handle[std::size_t(t[1])], vc = handle[std::size_t(t[2])];
        auto fail = [&](std::size_t& counter) {
            ++counter;
            if (rep.examples.size() < 10) rep.examples.push_back({t[0], t[1], t[2]});
        };
        if (va == vb || vb == vc || va == vc || va == DT::Vertex_handle() || vb == DT::Vertex_handle() ||
            vc == DT::Vertex_handle() || CGAL::collinear(va->point(), vb->point(), vc->point())) {
            fail(rep.degenerate);
            continue;
        }
        DT::Cell_handle c;
        int i, j, k;
        if (dt.is_facet(va, vb, vc, c, i, j, k)) {
            ++rep.dt_facets;
            continue;
        }
        std::vector<DT::Vertex_handle> adj;
        for (auto v : {va, vb, vc}) dt.finite_adjacent_vertices(v, std::back_inserter(adj));
        std::vector<std::int32_t> cand;
        for (auto v : adj) cand.push_back(v->info());
        std::sort(cand.begin(), cand.end());
        cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
        if (has_empty_ball(V, grid, t[0], t[1], t[2], std::move(cand))) ++rep.empty_ball_exact;
        else fail(rep.non_delaunay);
    }
    rep.passed = rep.non_delaunay == 0 && rep.degenerate == 0;
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
}

} // namespace isodel::verify
