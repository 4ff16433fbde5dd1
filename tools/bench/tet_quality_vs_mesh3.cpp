// tet_quality_vs_mesh3: the comparison of DELVOLMESH's tetrahedra with CGAL Mesh_3 (with
// perturb and exude) on the same volume at the same eps. Both mesh the inside of {F = v} for the
// trilinear interpolant F (Mesh_3 through an implicit domain that evaluates F exactly as isodel
// does, octree/segment_walk.h's phi_at), with facet_distance = eps; Mesh_3's other criteria are
// the usual ones (facet angle 25 deg, radius-edge 3, sizes 2 voxels). Prints one row per volume:
// tets, min/max dihedral angle (one routine for both meshes; isodel's also before its
// improvement step), tets with an angle under 10 degrees, tets outside [12, 165] degrees (and,
// of isodel's, those with no face on M), seconds.
//
//   tet_quality_vs_mesh3 [--facet-angle DEG] [--tet-dihedral MIN MAX] [--snap] [--compare-uniform]
//                        FILE ISO [FILE ISO ...]      (eps = 0.5 voxel; inside from the grid class)
#include <isodel/mesh.h>
#include <isodel/volume.h>

#include "octree/sample_field.h"
#include "octree/segment_walk.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using V3 = std::array<double, 3>;

/// Smallest and largest dihedral angle (degrees) of the tetrahedron p.
std::pair<double, double> dihedral_range(const std::array<V3, 4>& p)
{
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    auto sub = [](const V3& a, const V3& b) { return V3{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
    auto cross = [](const V3& a, const V3& b) {
        return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    double lo = 180, hi = 0;
    for (const auto& e : kEdges) {
        const V3 ev = sub(p[e[1]], p[e[0]]);
        const V3 n1 = cross(ev, sub(p[e[2]], p[e[0]])), n2 = cross(ev, sub(p[e[3]], p[e[0]]));
        const double c = std::clamp(dot(n1, n2) / std::sqrt(dot(n1, n1) * dot(n2, n2)), -1.0, 1.0);
        const double d = std::acos(c) * 180.0 / M_PI;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    return {lo, hi};
}

/// --tet-dihedral MIN MAX: MeshOptions::tet_min_dihedral_deg and tet_max_dihedral_deg (off).
struct DihedralRange {
    double min_deg = 0, max_deg = 180;
};
DihedralRange g_range;

/// --snap: MeshOptions::snap (isodel mesh --snap), off by default.
bool g_snap = false;

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// isodel's inside tets with every sample as G' (--uniform-tets): count, tets under 10 degrees, seconds.
struct UniformRun {
    std::size_t tets = 0, bad = 0;
    double seconds = 0;
};

UniformRun run_uniform(const isodel::Volume& vol, double iso, double facet_angle)
{
    const auto t0 = std::chrono::steady_clock::now();
    isodel::MeshOptions mo;
    mo.isovalue = iso;
    mo.inside = vol.default_inside;
    mo.eps_voxels = 0.5;
    mo.tets = isodel::TetRegion::Inside;
    mo.tet_spacing = isodel::TetSpacing::Uniform;
    mo.snap = g_snap;
    mo.facet_angle_deg = facet_angle;
    mo.tet_min_dihedral_deg = g_range.min_deg;
    mo.tet_max_dihedral_deg = g_range.max_deg;
    const isodel::MeshResult r = isodel::mesh_isosurface(*vol.grid, mo);
    UniformRun u{r.tets.tets.size(), 0, seconds_since(t0)};
    for (const auto& t : r.tets.tets)
        u.bad += dihedral_range({r.tets.vertices[t[0]], r.tets.vertices[t[1]], r.tets.vertices[t[2]],
                                 r.tets.vertices[t[3]]}).first < 10;
    return u;
}

void run(const std::string& file, double iso, double facet_angle, bool compare_uniform)
{
    const isodel::Volume vol = isodel::read_volume(file);
    const isodel::octree::SampleField field(vol.grid, iso, vol.default_inside);
    const double eps = 0.5 * field.min_voxel_edge();

    // isodel DELVOLMESH, inside region.
    auto t0 = std::chrono::steady_clock::now();
    isodel::MeshOptions mo;
    mo.isovalue = iso;
    mo.inside = vol.default_inside;
    mo.eps_voxels = 0.5;
    mo.tets = isodel::TetRegion::Inside;
    mo.snap = g_snap;
    mo.facet_angle_deg = facet_angle;
    mo.tet_min_dihedral_deg = g_range.min_deg;
    mo.tet_max_dihedral_deg = g_range.max_deg;
    const isodel::MeshResult r = isodel::mesh_isosurface(*vol.grid, mo);
    const double t_isodel = seconds_since(t0);
    double lo_i = 180, hi_i = 0;
    std::size_t bad_i = 0, bad_m = 0; // tets with a dihedral angle under 10 degrees
    std::size_t out_i = 0, out_m = 0; // ... outside the target range [12, 165] degrees
    std::size_t free_i = 0;           // ... of isodel's out, those with no face on M
    std::set<std::array<std::int32_t, 3>> m_faces;
    for (auto f : r.tets.triangles) {
        std::sort(f.begin(), f.end());
        m_faces.insert(f);
    }
    const auto faces_on_m = [&](const std::array<std::int32_t, 4>& t) {
        int n = 0;
        for (int j = 0; j < 4; ++j) {
            std::array<std::int32_t, 3> f{t[(j + 1) & 3], t[(j + 2) & 3], t[(j + 3) & 3]};
            std::sort(f.begin(), f.end());
            n += m_faces.count(f) != 0;
        }
        return n;
    };
    for (const auto& t : r.tets.tets) {
        const auto [lo, hi] = dihedral_range({r.tets.vertices[t[0]], r.tets.vertices[t[1]], r.tets.vertices[t[2]],
                                              r.tets.vertices[t[3]]});
        bad_i += lo < 10;
        const bool out = lo < 12 || hi > 165;
        out_i += out;
        free_i += out && faces_on_m(t) == 0;
        lo_i = std::min(lo_i, lo);
        hi_i = std::max(hi_i, hi);
    }

    // CGAL Mesh_3 on the same F: negative inside, as Labeled_mesh_domain_3 wants.
    t0 = std::chrono::steady_clock::now();
    const isodel::octree::SampleField::Reader reader(field);
    auto f = [&](const K::Point_3& p) {
        const auto q = field.world_to_index({p.x(), p.y(), p.z()});
        return -isodel::octree::phi_at(reader, q);
    };
    openvdb::CoordBBox box = field.domain();
    const auto lo_w = field.index_to_world(box.min().asVec3d()), hi_w = field.index_to_world(box.max().asVec3d());
    const K::Point_3 centre((lo_w[0] + hi_w[0]) / 2, (lo_w[1] + hi_w[1]) / 2, (lo_w[2] + hi_w[2]) / 2);
    const double r2 = 0.26 * ((hi_w - lo_w).lengthSqr()) + 4 * eps * eps;
    namespace params = CGAL::parameters;
    Domain domain = Domain::create_implicit_mesh_domain(f, K::Sphere_3(centre, r2),
                                                        params::relative_error_bound = 1e-6);
    const double h = 2 * field.min_voxel_edge();
    Criteria criteria(params::facet_angle = 25, params::facet_size = h, params::facet_distance = eps,
                      params::cell_radius_edge_ratio = 3, params::cell_size = h);
    C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::perturb(), params::exude());
    const double t_mesh3 = seconds_since(t0);
    double lo_m = 180, hi_m = 0;
    for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
        std::array<V3, 4> p;
        for (int j = 0; j < 4; ++j) {
            const auto q = c3t3.triangulation().point(c, j);
            p[j] = {q.x(), q.y(), q.z()};
        }
        const auto [lo, hi] = dihedral_range(p);
        bad_m += lo < 10;
        out_m += lo < 12 || hi > 165;
        lo_m = std::min(lo_m, lo);
        hi_m = std::max(hi_m, hi);
    }
    std::printf("%-34s %9zu %9.4f %9.4f %9.4f %7zu %7zu %7zu %4d %7.1f | %9zu %9.4f %9.4f %7zu %7zu %7.1f",
                file.substr(file.rfind('/') + 1).c_str(), r.tets.tets.size(), r.stats.tets.min_dihedral_deg_delaunay,
                lo_i, hi_i, bad_i, out_i, free_i, r.stats.tet_sliver_runs, t_isodel,
                std::size_t(c3t3.number_of_cells_in_complex()), lo_m, hi_m, bad_m, out_m, t_mesh3);
    if (compare_uniform) {
        const UniformRun u = run_uniform(vol, iso, facet_angle);
        std::printf(" | %9zu %7zu %7.1f", u.tets, u.bad, u.seconds);
    }
    std::printf("\n");
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    // --facet-angle DEG: isodel refines M's triangles to that angle first (isodel mesh
    // --facet-angle), as Mesh_3's facet_angle = 25 does for its own surface.
    // --tet-dihedral MIN MAX: isodel frees the tets M pins down outside that range (isodel mesh
    // --tet-min-dihedral, --tet-max-dihedral).
    // --snap: isodel snaps E points around a sample to it (isodel mesh --snap).
    // --compare-uniform: also isodel with every sample as G' (--uniform-tets), in the same run.
    double facet_angle = 0;
    bool compare_uniform = false;
    int first = 1;
    for (bool more = true; more && first < argc;) {
        const std::string a = argv[first];
        if (a == "--facet-angle" && first + 1 < argc) {
            facet_angle = std::stod(argv[first + 1]);
            first += 2;
        } else if (a == "--tet-dihedral" && first + 2 < argc) {
            g_range = {std::stod(argv[first + 1]), std::stod(argv[first + 2])};
            first += 3;
        } else if (a == "--snap") {
            g_snap = true;
            ++first;
        } else if (a == "--compare-uniform") {
            compare_uniform = true;
            ++first;
        } else {
            more = false;
        }
    }
    if (argc - first < 2 || (argc - first) % 2 != 0) {
        std::fprintf(stderr, "usage: tet_quality_vs_mesh3 [--facet-angle DEG] [--tet-dihedral MIN MAX] [--snap] [--compare-uniform] FILE ISO [FILE ISO ...]\n");
        return 2;
    }
    // isodel: min_Del is the Delaunay tets' smallest angle, min_dih/max_dih after improvement
    // (src/volume/tet_improvement.h); <10deg counts tets with a dihedral angle under 10 degrees;
    // free counts the tets of out with no face on M: M does not hold them, the improvement left them.
    std::printf("isodel facet angle: %s\n", facet_angle > 0 ? std::to_string(facet_angle).c_str() : "none");
    std::printf("isodel snap: %s\n", g_snap ? "on" : "off");
    std::printf("isodel tet dihedral range: %g .. %g (off at 0 .. 180); out: tets outside [12, 165] degrees\n",
                g_range.min_deg, g_range.max_deg);
    std::printf("%-34s %9s %9s %9s %9s %7s %7s %7s %4s %7s | %9s %9s %9s %7s %7s %7s", "volume (eps 0.5 voxel, inside)",
                "isodel", "min_Del", "min_dih", "max_dih", "<10deg", "out", "free", "runs", "s", "Mesh_3", "min_dih", "max_dih",
                "<10deg", "out", "s");
    if (compare_uniform) std::printf(" | %9s %7s %7s", "uniform", "<10deg", "s");
    std::printf("\n");
    for (int i = first; i + 1 < argc; i += 2) {
        try {
            run(argv[i], std::stod(argv[i + 1]), facet_angle, compare_uniform);
        } catch (const std::exception& e) {
            std::printf("%-40s failed: %s\n", argv[i], e.what());
        }
    }
    return 0;
}
