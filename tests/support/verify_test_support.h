#pragma once
// Helpers for the verify tests: analytic volumes built in memory, a correct mesh of a sphere built
// independently of isodel (points on Sigma by bisection with OpenVDB's own trilinear sampler, then
// their convex hull, whose facets are Delaunay facets of the point set), manifest reading.
#include <isodel/surface_mesh.h>

#include "support/json.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include "support/random_volume.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

namespace isodel::testing {

/// Dense grid of dims samples at index (0..dims-1), f given in index space, voxel size and origin
/// mapped by a linear transform.
inline openvdb::FloatGrid::Ptr make_grid(int n, double voxel, const openvdb::Vec3d& origin,
                                         const std::function<double(const openvdb::Vec3d&)>& f,
                                         float background = -1.0f)
{
    auto grid = openvdb::FloatGrid::create(background);
    auto xf = openvdb::math::Transform::createLinearTransform(voxel);
    xf->postTranslate(origin);
    grid->setTransform(xf);
    auto acc = grid->getAccessor();
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) acc.setValueOn(openvdb::Coord(i, j, k), float(f(openvdb::Vec3d(i, j, k))));
    return grid;
}

inline double sphere_f(const openvdb::Vec3d& x, const openvdb::Vec3d& c, double r) { return r - (x - c).length(); }

inline double torus_f(const openvdb::Vec3d& x, const openvdb::Vec3d& c, double R, double r)
{
    const openvdb::Vec3d d = x - c;
    const double q = std::sqrt(d[0] * d[0] + d[1] * d[1]) - R;
    return r - std::sqrt(q * q + d[2] * d[2]);
}

/// A closed mesh of the star-shaped level set {F = 0} (F > 0 inside, around index point \p centre):
/// Fibonacci directions, Sigma found by bisection of OpenVDB's BoxSampler (trilinear) along each
/// ray, radially jittered by +-jitter voxel (general position), convex hull (outward oriented).
inline SurfaceMesh star_hull_mesh(const openvdb::FloatGrid& grid, const openvdb::Vec3d& centre, int npts,
                                  double jitter, unsigned seed = 1)
{
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-jitter, jitter);
    auto acc = grid.getConstAccessor();
    std::vector<K::Point_3> pts;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < npts; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / npts, rr = std::sqrt(1 - z * z), th = golden * i;
        const openvdb::Vec3d dir(rr * std::cos(th), rr * std::sin(th), z);
        double lo = 0.0, hi = 1.0;
        auto F = [&](double t) { return openvdb::tools::BoxSampler::sample(acc, centre + dir * t); };
        while (F(hi) > 0) hi *= 2;
        for (int it = 0; it < 80; ++it) {
            const double m = 0.5 * (lo + hi);
            (F(m) > 0 ? lo : hi) = m;
        }
        const openvdb::Vec3d w = grid.transform().indexToWorld(centre + dir * (0.5 * (lo + hi) + U(rng)));
        pts.emplace_back(w[0], w[1], w[2]);
    }
    CGAL::Surface_mesh<K::Point_3> sm;
    CGAL::convex_hull_3(pts.begin(), pts.end(), sm);
    SurfaceMesh m;
    for (auto v : sm.vertices()) {
        const auto& p = sm.point(v);
        m.vertices.push_back({p.x(), p.y(), p.z()});
    }
    for (auto f : sm.faces()) {
        std::array<std::int32_t, 3> t{};
        int q = 0;
        for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[std::size_t(q++)] = std::int32_t(v.idx());
        m.triangles.push_back(t);
    }
    return m;
}

inline std::string shared_data() { return ISODEL_SHARED_DATA; }

/// The manifest (an array), or a null value if ../shared/data is absent.
inline Json read_manifest()
{
    const std::string path = shared_data() + "/manifest.json";
    if (!std::ifstream(path)) return {};
    return read_json_file(path);
}

inline openvdb::FloatGrid::Ptr read_vdb(const std::string& path, const std::string& name)
{
    openvdb::io::File file(path);
    file.open();
    auto base = name.empty() ? file.readGrid(file.beginName().gridName()) : file.readGrid(name);
    file.close();
    return openvdb::gridPtrCast<openvdb::FloatGrid>(base);
}

} // namespace isodel::testing
