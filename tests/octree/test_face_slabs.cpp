// Sigma' = {F o phi = v} (octree/face_slabs.h, cell_function.h): phi and its preimages, F' per
// slab/core box, and the segment walk and phi_at reading F' in mesh space.
#include "support/adaptive_random.h"

#include "octree/cell_function.h"
#include "octree/segment_walk.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace isodel::octree;

namespace {

/// F o phi at a mesh-space point, straight from the definition (no pieces).
double f_prime(const SampleField::Reader& reader, const FaceSlabs& slabs, const Vec3d& x)
{
    const Vec3d s = slabs.to_sample(x);
    const Coord c(int(std::floor(s[0])), int(std::floor(s[1])), int(std::floor(s[2])));
    double corner[8];
    reader.cell_corners(c, corner);
    return isodel::octree::Trilinear::from_corners(corner)(s[0] - c[0], s[1] - c[1], s[2] - c[2]);
}

} // namespace

TEST_CASE("face slabs: phi collapses each slab onto its plane and stretches the core", "[octree][face_slabs]")
{
    const FaceSlabs s{0.05};
    CHECK(s.to_sample(3.0) == 3.0);
    CHECK(s.to_sample(3.04) == 3.0);
    CHECK(s.to_sample(2.96) == 3.0);
    CHECK(s.to_sample(3.05) == Approx(3.0));
    CHECK(s.to_sample(3.5) == Approx(3.5));
    CHECK(s.to_sample(3.95) == Approx(4.0));
    // Preimages: off the planes unique and in the core, on a plane the slab's middle.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-5, 5);
    for (int i = 0; i < 1000; ++i) {
        const double x = U(rng);
        const double m = s.from_sample(x);
        CHECK(s.to_sample(m) == Approx(x).margin(1e-12));
        const double l = m - std::floor(m);
        CHECK(l >= s.h - 1e-12);
        CHECK(l <= 1 - s.h + 1e-12);
    }
    CHECK(s.from_sample(-2.0) == -2.0);
    // h = 0 is the identity.
    const FaceSlabs id;
    CHECK(id.to_sample(1.2345) == 1.2345);
    CHECK(id.from_sample(1.2345) == 1.2345);
}

TEST_CASE("face slabs: F' is trilinear on each slab/core box and agrees with F o phi", "[octree][face_slabs]")
{
    auto grid = testing::random_samples(4, 3);
    SampleField field(grid, 0.0, isodel::Inside::Above);
    field.set_face_slabs(FaceSlabs{0.07});
    const SampleField::Reader reader(field);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0, 1);
    double worst = 0, worst_grad = 0;
    for (int i = 0; i < 2000; ++i) {
        const Coord c(1, 1, 1);
        const Vec3d l(U(rng), U(rng), U(rng));
        const CellFunction cf = cell_function(reader, c);
        const FaceSlabs& s = cf.slabs();
        const isodel::octree::Trilinear piece = cf.piece(s.piece_of(l[0]), s.piece_of(l[1]), s.piece_of(l[2]));
        const double direct = f_prime(reader, s, c.asVec3d() + l);
        worst = std::max({worst, std::abs(piece(l[0], l[1], l[2]) - direct), std::abs(cf(l[0], l[1], l[2]) - direct)});
        // The gradient: central differences inside the box.
        const Vec3d g = cf.gradient(l[0], l[1], l[2]);
        const Vec3d gp = piece.gradient(l[0], l[1], l[2]);
        worst_grad = std::max(worst_grad, (g - gp).length());
        // Across a slab F' does not change.
        if (s.piece_of(l[0]) != 1) CHECK(g[0] == 0);
    }
    CHECK(worst < 1e-12);
    CHECK(worst_grad < 1e-9);
    // phi_at reads F' in mesh space.
    for (int i = 0; i < 200; ++i) {
        const Vec3d x(1 + 2 * U(rng), 1 + 2 * U(rng), 1 + 2 * U(rng));
        CHECK(phi_at(reader, x) == Approx(f_prime(reader, field.face_slabs(), x)).margin(1e-12));
    }
}

TEST_CASE("face slabs: the segment walk finds every sign change of F' (dense sampling as reference)", "[octree][face_slabs]")
{
    // Random samples (a sign change in nearly every cell) and a smooth field, where most cells
    // a segment passes keep one sign and the walk skips their pieces (segment_walk.cpp's
    // keeps_sign): the signs it carries past them must stay right to the end.
    for (const bool smooth : {false, true})
    for (const double h : {0.0, 0.01, 0.1}) {
        auto grid = testing::random_samples(6, 5, smooth);
        INFO("h = " << h << ", smooth " << smooth);
        SampleField field(grid, 0.0, isodel::Inside::Above);
        field.set_face_slabs(FaceSlabs{h});
        const SampleField::Reader reader(field);
        std::mt19937 rng(13);
        std::uniform_real_distribution<double> U(0.5, 4.5);
        int compared = 0, with_roots = 0;
        for (int i = 0; i < 300; ++i) {
            const Vec3d a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng));
            const auto sc = segment_crossings(reader, a, b, 64);
            REQUIRE(!sc.overflow);
            // Dense samples: the sign changes between consecutive samples must match the roots
            // found in those intervals (odd count <=> a sign change), and each root is on Sigma'.
            const int n = 20000;
            std::size_t r = 0;
            bool prev = f_prime(reader, field.face_slabs(), a) >= 0;
            CHECK(prev == sc.inside_at_start);
            bool ok = true;
            for (int k = 1; k <= n; ++k) {
                const double t = double(k) / n;
                const bool cur = f_prime(reader, field.face_slabs(), a + t * (b - a)) >= 0;
                int roots = 0;
                while (r < sc.t.size() && sc.t[r] <= t) {
                    ++roots;
                    ++r;
                }
                if ((roots % 2 == 1) != (cur != prev)) ok = false;
                prev = cur;
            }
            CHECK(ok);
            CHECK(prev == sc.inside_at_end);
            for (double t : sc.t) CHECK(std::abs(f_prime(reader, field.face_slabs(), a + t * (b - a))) < 1e-9);
            ++compared;
            with_roots += !sc.t.empty();
        }
        CHECK(compared == 300);
        CHECK(with_roots > (smooth ? 50 : 100));
    }
}

TEST_CASE("face slabs: the mesher's slab width keeps Sigma' within 0.035 eps of Sigma on any lattice", "[octree][face_slabs]")
{
    auto grid = testing::random_samples(3, 9);
    // Cubic voxels of edge 0.5: h = eps / 50 in voxels, shift sqrt(3) h voxel edges.
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
    {
        SampleField field(grid, 0.0, isodel::Inside::Above);
        const double eps = 0.25; // world: half a voxel
        field.set_face_slabs(field.face_slabs_for_eps_world(eps));
        CHECK(field.face_slabs().h == Approx(0.01));
        CHECK(field.face_slab_shift() == Approx(std::sqrt(3.0) * 0.01 * 0.5));
        CHECK(field.face_slab_shift() <= SampleField::kMaxSlabShift * eps);
    }
    // Voxels 1 x 1 x 50: eps/50 in the smallest edge would move Sigma' by ~eps along z; the
    // slabs narrow instead.
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.setToScale(openvdb::Vec3d(1, 1, 50));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
    SampleField field(grid, 0.0, isodel::Inside::Above);
    const double eps = 0.5;
    field.set_face_slabs(field.face_slabs_for_eps_world(eps));
    CHECK(field.face_slabs().h < 0.01);
    CHECK(field.face_slabs().h > 0);
    CHECK(field.face_slab_shift() == Approx(SampleField::kMaxSlabShift * eps));
}
