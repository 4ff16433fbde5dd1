// The tet improver's quality (src/volume/tet_improver.h: dihedral angles from the four face
// normals) equals the smallest dihedral angle computed independently, from the two normals
// e x (p2 - p0), e x (p3 - p0) at each edge e as measure_tet_quality does, on random,
// inverted, needle, sliver and flat tetrahedra. measure_tet_quality, which runs over fixed runs of
// tets in parallel, gives the same statistics with 1 and 2 threads and the counts of a serial
// recount.
#include <catch2/catch.hpp>

#include "volume/tet_improvement.h"
#include "volume/tet_improver.h"
#include "volume/tet_quality.h"

#include <isodel/mesh.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

using namespace isodel::mesher;

namespace {

using V3 = std::array<double, 3>;

/// Smallest dihedral angle in degrees, two normals per edge (\p largest: the largest instead).
double reference_min_dihedral(const std::array<V3, 4>& p, bool largest = false)
{
    const auto sub = [](const V3& a, const V3& b) { return V3{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
    const auto cross = [](const V3& a, const V3& b) {
        return V3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    const auto dot = [](const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    double best = largest ? 0 : 180;
    for (const auto& e : kEdges) {
        const V3 ev = sub(p[e[1]], p[e[0]]);
        const V3 n1 = cross(ev, sub(p[e[2]], p[e[0]])), n2 = cross(ev, sub(p[e[3]], p[e[0]]));
        const double den = std::sqrt(dot(n1, n1) * dot(n2, n2));
        if (!(den > 0)) return 0;
        const double angle = std::acos(std::clamp(dot(n1, n2) / den, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
        best = largest ? std::max(best, angle) : std::min(best, angle);
    }
    return best;
}

} // namespace

TEST_CASE("tet quality: face-normal dihedral angles equal the two-normals-per-edge formula", "[mesher][tets]")
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const auto check = [](const std::array<V3, 4>& p) {
        const double got = min_dihedral_deg(p[0], p[1], p[2], p[3]);
        const double want = reference_min_dihedral(p);
        INFO(p[0][0] << "," << p[0][1] << "," << p[0][2] << " / " << p[1][0] << "," << p[1][1] << "," << p[1][2] << " / "
                     << p[2][0] << "," << p[2][1] << "," << p[2][2] << " / " << p[3][0] << "," << p[3][1] << "," << p[3][2]);
        CHECK(got == Approx(want).margin(1e-6));
        // Either orientation: swapping two vertices gives the same angles.
        CHECK(min_dihedral_deg(p[1], p[0], p[2], p[3]) == Approx(want).margin(1e-6));
    };
    int flat_or_thin = 0;
    for (int i = 0; i < 20000; ++i) {
        std::array<V3, 4> p;
        for (auto& v : p) v = {u(rng), u(rng), u(rng)};
        switch (i % 4) {
        case 1: // sliver: the fourth vertex near the plane of the other three
            for (int k = 0; k < 3; ++k) p[3][k] = 0.5 * (p[0][k] + p[2][k]) + 0.5 * (p[1][k] - p[0][k]) + 1e-3 * u(rng);
            break;
        case 2: // needle: two vertices very close
            for (int k = 0; k < 3; ++k) p[1][k] = p[0][k] + 1e-4 * u(rng);
            break;
        case 3: // spread over nine orders of magnitude of position
            for (auto& v : p)
                for (double& x : v) x = 1e6 + x;
            break;
        default: break;
        }
        flat_or_thin += reference_min_dihedral(p) < 5;
        check(p);
    }
    CHECK(flat_or_thin > 2000);
    // A regular tetrahedron: arccos(1/3); a flat one (four coplanar points) and a repeated
    // vertex: 0.
    const double s = std::sqrt(2.0);
    check({V3{1, 0, -1 / s}, V3{-1, 0, -1 / s}, V3{0, 1, 1 / s}, V3{0, -1, 1 / s}});
    CHECK(min_dihedral_deg({1, 0, -1 / s}, {-1, 0, -1 / s}, {0, 1, 1 / s}, {0, -1, 1 / s}) ==
          Approx(std::acos(1.0 / 3.0) * 180 / 3.14159265358979323846));
    CHECK(min_dihedral_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}) == 0);
    CHECK(min_dihedral_deg({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}) == 0);
}

TEST_CASE("tet quality statistics: the same with 1 and 2 threads, and a serial recount's", "[mesher][tets]")
{
    // 100 k random tets over 3 k vertices (several of measure_tet_quality's runs), two regions;
    // the first 500 vertices are M's.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    isodel::TetMesh m;
    for (int i = 0; i < 3000; ++i) m.vertices.push_back({u(rng), u(rng), u(rng)});
    std::uniform_int_distribution<std::int32_t> pick(0, 2999);
    for (int t = 0; t < 100000; ++t) {
        std::array<std::int32_t, 4> x;
        do {
            for (auto& v : x) v = pick(rng);
        } while (x[0] == x[1] || x[0] == x[2] || x[0] == x[3] || x[1] == x[2] || x[1] == x[3] || x[2] == x[3]);
        m.tets.push_back(x);
        m.tet_region.push_back(1 + (t % 3 == 0));
    }
    const std::size_t nm = 500;
    isodel::TetStats one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        measure_tet_quality(m, nm, one);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        measure_tet_quality(m, nm, two);
    }
    CHECK(one.volume_inside == two.volume_inside); // bit for bit
    CHECK(one.volume_outside == two.volume_outside);
    CHECK(one.min_dihedral_deg == two.min_dihedral_deg);
    CHECK(one.max_radius_edge == two.max_radius_edge);
    CHECK(one.dihedral_histogram == two.dihedral_histogram);
    CHECK(one.tets_below_10deg == two.tets_below_10deg);

    std::size_t inside = 0, touching = 0, below10 = 0;
    double vin = 0, worst = 180, worst_off = 180;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        std::array<V3, 4> p;
        bool touches = false;
        for (int j = 0; j < 4; ++j) {
            p[std::size_t(j)] = m.vertices[std::size_t(m.tets[t][std::size_t(j)])];
            touches |= std::size_t(m.tets[t][std::size_t(j)]) < nm;
        }
        const double a = reference_min_dihedral(p);
        worst = std::min(worst, a);
        below10 += a < 10;
        touching += touches;
        if (!touches) worst_off = std::min(worst_off, a);
        if (m.tet_region[t] == 1) {
            ++inside;
            vin += signed_tet_volume(p[0], p[1], p[2], p[3]);
        }
    }
    CHECK(one.tets_inside == inside);
    CHECK(one.tets_outside == m.tets.size() - inside);
    CHECK(one.tets_touching_surface == touching);
    CHECK(one.tets_below_10deg == below10);
    CHECK(one.min_dihedral_deg == Approx(worst).margin(1e-9));
    CHECK(one.min_dihedral_deg_off_surface == Approx(worst_off).margin(1e-9));
    CHECK(one.volume_inside == Approx(vin).epsilon(1e-12));
    std::size_t angles = 0;
    for (const std::size_t n : one.dihedral_histogram) angles += n;
    CHECK(angles == 6 * m.tets.size());
}

TEST_CASE("tet quality: the improver's measure is the smallest angle or 180 degrees minus the largest",
          "[mesher][tets]")
{
    // The improver works on the tets whose measure is under its target (15 degrees): a cap with a
    // fair smallest angle and a largest angle near 180 degrees is one of them.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 5000; ++i) {
        std::array<V3, 4> p;
        for (auto& v : p) v = {u(rng), u(rng), u(rng)};
        const double lo = reference_min_dihedral(p), hi = reference_min_dihedral(p, true);
        const double got = tet_improver::degrees(tet_improver::quality(p[0], p[1], p[2], p[3]));
        CHECK(got == Approx(std::min(lo, 180 - hi)).margin(1e-6));
        CHECK(tet_improver::degrees(tet_improver::smallest_angle_quality(p[0], p[1], p[2], p[3])) ==
              Approx(lo).margin(1e-6));
    }
    const std::array<V3, 4> cap{V3{-0.813, -0.738, -0.588}, V3{0.263, 0.87, -0.838}, V3{-0.047, 0.671, -0.854},
                                V3{0.062, 0.451, -0.651}};
    CHECK(reference_min_dihedral(cap) > 15);
    CHECK(reference_min_dihedral(cap, true) > 165);
    CHECK(tet_improver::degrees(tet_improver::quality(cap[0], cap[1], cap[2], cap[3])) < 15);
}
