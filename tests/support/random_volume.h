#pragma once
// The random volumes of the property test (tests/corpus/test_verify_property.cpp), of many unit
// tests and of the QA sweep (tools/qa/random_sweep.cpp): one definition, since tests name the
// seeds that once broke the mesher and a second copy could drift from it.
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace isodel::testing {

/// n^3 samples uniform in [-1, 1] drawn from std::mt19937(seed) in x-fastest order at index
/// points 1..n, padded by one layer of -1 (as the manifest's random volumes), voxel size 1;
/// quantized: values in {-1, -0.5, 0, 0.5, 1}, so many samples equal the isovalue 0.
inline openvdb::FloatGrid::Ptr random_volume(int n, unsigned seed, bool quantized)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    auto grid = openvdb::FloatGrid::create(-1.0f);
    auto xf = openvdb::math::Transform::createLinearTransform(1.0);
    xf->postTranslate(openvdb::Vec3d(0.0));
    grid->setTransform(xf);
    auto acc = grid->getAccessor();
    for (int k = 0; k < n + 2; ++k)
        for (int j = 0; j < n + 2; ++j)
            for (int i = 0; i < n + 2; ++i) {
                double v = -1.0;
                if (i != 0 && j != 0 && k != 0 && i != n + 1 && j != n + 1 && k != n + 1) {
                    v = U(rng);
                    if (quantized) v = std::round(v * 2.0) / 2.0;
                }
                acc.setValueOn(openvdb::Coord(i, j, k), float(v));
            }
    return grid;
}

/// A smooth random volume: m^3 control values uniform in [-1, 1] from std::mt19937(seed),
/// interpolated trilinearly onto a lattice \p factor times finer (index points 1 .. (m - 1) *
/// factor + 1), padded by one layer of -1, voxel size 1. Its cells are trilinear on blocks of
/// factor^3 voxels, so an octree can coarsen it where a noise volume has no two alike cells.
inline openvdb::FloatGrid::Ptr random_smooth_volume(int m, int factor, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<double> c(std::size_t(m) * m * m);
    for (double& v : c) v = U(rng);
    const auto ctrl = [&](int i, int j, int k) { return c[(std::size_t(k) * m + j) * m + i]; };
    const int n = (m - 1) * factor + 1;
    auto grid = openvdb::FloatGrid::create(-1.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(1.0));
    auto acc = grid->getAccessor();
    for (int k = 0; k < n + 2; ++k)
        for (int j = 0; j < n + 2; ++j)
            for (int i = 0; i < n + 2; ++i) {
                double v = -1.0;
                if (i != 0 && j != 0 && k != 0 && i != n + 1 && j != n + 1 && k != n + 1) {
                    const int p[3] = {i - 1, j - 1, k - 1};
                    int q[3];
                    double t[3];
                    for (int a = 0; a < 3; ++a) {
                        q[a] = std::min(p[a] / factor, m - 2);
                        t[a] = double(p[a] - q[a] * factor) / factor;
                    }
                    v = 0;
                    for (int corner = 0; corner < 8; ++corner) {
                        double w = 1;
                        for (int a = 0; a < 3; ++a) w *= (corner >> a) & 1 ? t[a] : 1 - t[a];
                        v += w * ctrl(q[0] + (corner & 1), q[1] + ((corner >> 1) & 1), q[2] + ((corner >> 2) & 1));
                    }
                }
                acc.setValueOn(openvdb::Coord(i, j, k), float(v));
            }
    return grid;
}

} // namespace isodel::testing
