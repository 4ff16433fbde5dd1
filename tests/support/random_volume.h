#pragma once
// The random volumes of the property test (tests/corpus/test_verify_property.cpp), of many unit
// tests and of the QA sweep (tools/qa/random_sweep.cpp): one definition, since tests name the
// seeds that once broke the mesher and a second copy could drift from it.
#include <openvdb/openvdb.h>

#include <cmath>
#include <random>

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

} // namespace isodel::testing
