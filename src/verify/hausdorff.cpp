// Check 3: two-sided Hausdorff distance between M and Sigma, world and voxel units, max and RMS.
//
// M -> Sigma. Each triangle is sampled on a barycentric grid (vertices, edge points, interior
// points, spacing <= eps/4). For a sample p the distance d(p, Sigma) is bounded ABOVE by |p - q|
// for any q on Sigma; we take the best of two such q:
//   1. Newton projection of p along the world gradient of F (converges to |phi| ~ roundoff);
//   2. when 1. fails or gives more than eps/2 (where an overestimate could flip the verdict):
//      a local reference - marching tetrahedra at R = 8 in every crossed cell meeting the ball
//      B(p, d1) - the closest point on it to p, itself Newton-projected onto Sigma
//      (local_reference.h).
// Since both are points of Sigma, the reported values are upper bounds of d(p, Sigma): the
// reference contributes no error to a "pass" (only roundoff of the Newton tolerance, 1e-12 of
// the value range). What remains is sampling: sup over M <= max + sample_spacing.
//
// Sigma -> M. Sigma is sampled by the crossings of every Freudenthal sub-lattice edge at
// refinement R_h in every crossed cell, each Newton-projected onto Sigma; the distance to M is
// exact (CGAL AABB tree of M's triangles). sup over Sigma <= max + sample_spacing (the length
// of a sub-lattice diagonal, sqrt(3) voxel / R_h).
#include "verify/checks.h"

#include "verify/local_reference.h"
#include "verify/refined_lattice.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

namespace isodel::verify {
namespace {

struct Accum {
    std::size_t n = 0;
    double max = 0.0, sum2 = 0.0;
    Vec3d argmax{0.0};
    void add(double d, const Vec3d& at)
    {
        ++n;
        sum2 += d * d;
        if (d > max || n == 1) {
            max = d;
            argmax = at;
        }
    }
    void merge(const Accum& o)
    {
        if (o.n && (o.max > max || n == 0)) {
            max = o.max;
            argmax = o.argmax;
        }
        n += o.n;
        sum2 += o.sum2;
    }
    DistanceStats stats(double voxel, double spacing) const
    {
        DistanceStats s;
        s.samples = n;
        s.max = max;
        s.rms = n ? std::sqrt(sum2 / double(n)) : 0.0;
        s.max_voxels = max / voxel;
        s.rms_voxels = s.rms / voxel;
        s.argmax = {argmax[0], argmax[1], argmax[2]};
        s.sample_spacing = spacing;
        return s;
    }
};

} // namespace

HausdorffReport hausdorff(const TrilinearField& field, const SurfaceMesh& mesh, double eps, int sigma_refine)
{
    const auto t0 = std::chrono::steady_clock::now();
    HausdorffReport rep;
    rep.checked = true;
    const double voxel = field.voxel();
    rep.eps = eps;
    rep.eps_voxels = eps / voxel;
    const int Rh = sigma_refine > 0 ? sigma_refine
                                    : std::clamp(int(std::ceil(1.0 / rep.eps_voxels)), 4, 12);
    rep.sigma_refine = Rh;

    Coord base;
    const std::vector<Coord> cells = crossed_cells(field, base);
    const CrossedCellSet crossed(cells, base);

    auto vtx = [&](std::int32_t i) {
        const auto& v = mesh.vertices[std::size_t(i)];
        return Vec3d(v[0], v[1], v[2]);
    };

    // ---- Sigma -> M ----
    using K = CGAL::Simple_cartesian<double>; // distances only; no predicate decides topology here
    std::vector<K::Triangle_3> tris;
    for (const auto& t : mesh.triangles) {
        const Vec3d a = vtx(t[0]), b = vtx(t[1]), c = vtx(t[2]);
        tris.emplace_back(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]), K::Point_3(c[0], c[1], c[2]));
    }
    using Prim = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Prim>>;
    Accum s2m;
    if (!tris.empty()) {
        Tree tree(tris.cbegin(), tris.cend());
        tree.accelerate_distance_queries();
        struct Local {
            TrilinearField::Evaluator ev;
            CellRefiner refiner;
            Accum acc;
        };
        tbb::enumerable_thread_specific<Local> locals([&] { return Local{TrilinearField::Evaluator(field), CellRefiner(Rh), {}}; });
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 16), [&](const auto& r) {
            Local& L = locals.local();
            for (std::size_t i = r.begin(); i != r.end(); ++i)
                L.refiner.crossings(L.ev.reader(), cells[i], [&](const Vec3d& x) {
                    Vec3d y;
                    if (!L.ev.project(x, y)) return; // not on Sigma: not a valid sample
                    const Vec3d w = field.to_world(y);
                    const double d = std::sqrt(tree.squared_distance(K::Point_3(w[0], w[1], w[2])));
                    L.acc.add(d, w);
                });
        });
        for (auto& L : locals) s2m.merge(L.acc);
    }
    rep.surface_to_mesh = s2m.stats(voxel, std::sqrt(3.0) * voxel / Rh);

    // ---- M -> Sigma ----
    constexpr std::size_t kFallbackBudget = 2000000; // local searches are cheap (a few cells each)
    std::atomic<std::size_t> fallbacks{0}, unresolved{0};
    double spacing = 0.0;
    std::mutex spacing_mutex;
    struct Local2 {
        TrilinearField::Evaluator ev;
        LocalReference reference;
        Accum acc;
        double spacing = 0.0;
    };
    tbb::enumerable_thread_specific<Local2> locals2([&] { return Local2{TrilinearField::Evaluator(field), LocalReference(field, crossed), {}, 0.0}; });

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangles.size(), 64), [&](const auto& r) {
        Local2& L = locals2.local();
        for (std::size_t f = r.begin(); f != r.end(); ++f) {
            const auto& t = mesh.triangles[f];
            const Vec3d a = vtx(t[0]), b = vtx(t[1]), c = vtx(t[2]);
            const double longest = std::max({(b - a).length(), (c - b).length(), (a - c).length()});
            const int k = std::clamp(int(std::ceil(longest / (0.25 * eps))), 1, 16);
            L.spacing = std::max(L.spacing, longest / k);
            for (int i = 0; i <= k; ++i)
                for (int j = 0; i + j <= k; ++j) {
                    const Vec3d p = a + (b - a) * (double(i) / k) + (c - a) * (double(j) / k);
                    Vec3d y;
                    const bool ok = L.ev.project(field.to_index(p), y);
                    double d = ok ? (field.to_world(y) - p).length() : 1e300;
                    if ((!ok || d > 0.5 * eps) && fallbacks.fetch_add(1) < kFallbackBudget) {
                        const double radius = ok ? d : 2.0 * eps + 2.0 * voxel;
                        L.reference.search(p, radius, d);
                    }
                    if (d == 1e300) {
                        ++unresolved;
                        continue;
                    }
                    L.acc.add(d, p);
                }
        }
    });
    Accum m2s;
    for (auto& L : locals2) {
        m2s.merge(L.acc);
        std::lock_guard<std::mutex> lock(spacing_mutex);
        spacing = std::max(spacing, L.spacing);
    }
    rep.mesh_to_surface = m2s.stats(voxel, spacing);
    rep.fallback_queries = std::min<std::size_t>(fallbacks.load(), kFallbackBudget);
    rep.unresolved = unresolved.load();
    rep.passed = rep.unresolved == 0 && rep.mesh_to_surface.max <= eps && rep.surface_to_mesh.max <= eps &&
                 !mesh.triangles.empty();
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
}

} // namespace isodel::verify
