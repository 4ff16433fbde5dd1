// one_sign_on_box (octree/box_sign.h) certifies that F' keeps one sign on a box: whenever it
// says so, no point of the box read through phi_at may have the other sign (checked on dense
// and random samples of boxes spanning several cells, with and without face slabs); and for a
// box inside one cell whose eight corners have the sign by a clear margin it must say so.
#include "octree/box_sign.h"
#include "octree/segment_walk.h"

#include <catch2/catch.hpp>

#include <random>

using namespace isodel::octree;

namespace {

/// A ball of radius 4 around (6, 6, 6) with noise on [0, 12]^3: boxes far from the sphere keep
/// one sign, boxes across it do not, and the noise makes cells with mixed corners.
openvdb::FloatGrid::Ptr noisy_ball()
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-0.6f, 0.6f);
    auto g = openvdb::FloatGrid::create(-1.f);
    auto acc = g->getAccessor();
    for (int z = 0; z <= 12; ++z)
        for (int y = 0; y <= 12; ++y)
            for (int x = 0; x <= 12; ++x) {
                const float r = std::sqrt(float((x - 6) * (x - 6) + (y - 6) * (y - 6) + (z - 6) * (z - 6)));
                acc.setValueOn(Coord(x, y, z), 4.f - r + u(rng));
            }
    return g;
}

struct Tally {
    int certified = 0, wrong = 0;
};

void check_boxes(const SampleField& field, Tally& in, Tally& out)
{
    const SampleField::Reader reader(field);
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> pos(0.5, 10.5), size(0.0, 2.5), t(0.0, 1.0);
    std::bernoulli_distribution flat(0.15);
    for (int trial = 0; trial < 3000; ++trial) {
        Vec3d lo, hi;
        for (int k = 0; k < 3; ++k) {
            lo[k] = pos(rng);
            hi[k] = lo[k] + (flat(rng) ? 0.0 : size(rng));
        }
        if (trial % 7 == 0) lo[trial % 3] = std::floor(lo[trial % 3]); // a box side on a grid plane
        for (const bool inside : {true, false}) {
            if (!one_sign_on_box(reader, lo, hi, inside)) continue;
            Tally& tally = inside ? in : out;
            ++tally.certified;
            bool ok = true;
            auto probe = [&](const Vec3d& p) {
                const double phi = phi_at(reader, p);
                ok &= inside ? phi >= 0 : phi < 0;
            };
            const int n = 6;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j)
                    for (int k = 0; k <= n; ++k)
                        probe(lo + Vec3d(i * (hi[0] - lo[0]), j * (hi[1] - lo[1]), k * (hi[2] - lo[2])) / double(n));
            for (int r = 0; r < 200; ++r)
                probe(Vec3d(lo[0] + t(rng) * (hi[0] - lo[0]), lo[1] + t(rng) * (hi[1] - lo[1]),
                            lo[2] + t(rng) * (hi[2] - lo[2])));
            if (!ok) ++tally.wrong;
        }
    }
}

} // namespace

TEST_CASE("one sign on a box: a certified box has no point of the other sign", "[octree][box_sign]")
{
    const auto g = noisy_ball();
    for (const double h : {0.0, 0.02, 0.2}) {
        SampleField field(g, 0.0, isodel::Inside::Above);
        field.set_face_slabs(FaceSlabs{h});
        Tally in, out;
        check_boxes(field, in, out);
        INFO("h = " << h << ": certified inside " << in.certified << ", outside " << out.certified);
        CHECK(in.wrong == 0);
        CHECK(out.wrong == 0);
        // Not vacuous: both signs are certified on many boxes, spanning several cells.
        CHECK(in.certified > 200);
        CHECK(out.certified > 200);
    }
}

TEST_CASE("one sign on a box: a box in one cell with clear corner signs is certified", "[octree][box_sign]")
{
    const auto g = noisy_ball();
    for (const double h : {0.0, 0.02}) {
        SampleField field(g, 0.0, isodel::Inside::Above);
        field.set_face_slabs(FaceSlabs{h});
        const SampleField::Reader reader(field);
        std::mt19937 rng(23);
        std::uniform_int_distribution<int> cell(0, 11);
        std::uniform_real_distribution<double> t(0.0, 1.0);
        int clear = 0, certified = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            const Vec3d c(cell(rng), cell(rng), cell(rng));
            Vec3d lo, hi;
            for (int k = 0; k < 3; ++k) {
                const double a = t(rng), b = t(rng);
                lo[k] = c[k] + std::min(a, b);
                hi[k] = c[k] + std::max(a, b);
                if (hi[k] >= c[k] + 1) hi[k] = std::nextafter(c[k] + 1, 0.0); // stay in the cell
            }
            // Its corners, read straight through phi_at; on one cell F' is extremal at them.
            double mn = 1e300, mx = -1e300;
            for (int i = 0; i < 8; ++i) {
                const double phi = phi_at(reader, Vec3d(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]));
                mn = std::min(mn, phi);
                mx = std::max(mx, phi);
            }
            const bool inside = mn > 1e-3, outside = mx < -1e-3;
            if (!inside && !outside) continue;
            ++clear;
            if (one_sign_on_box(reader, lo, hi, inside)) ++certified;
        }
        INFO("h = " << h);
        CHECK(clear > 500);
        CHECK(certified == clear);
    }
}
