// Fuzz target: the Medit .mesh reader `isodel verify --tets` uses (src/io/read_tet_mesh.cpp).
#include "fuzz_input.h"

#include <isodel/surface_mesh.h>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const isodel::fuzz::InputFile file(data, size, ".mesh");
    isodel::fuzz::expect_clean_refusal(file.path(), [&] {
        const isodel::TetMesh m = isodel::read_tet_mesh(file.path());
        const auto n = std::int64_t(m.vertices.size());
        isodel::fuzz::require(m.tet_region.size() == m.tets.size(), "a region per tetrahedron");
        for (const auto& t : m.tets)
            for (int c = 0; c < 4; ++c) isodel::fuzz::require(t[c] >= 0 && t[c] < n, "tet index out of range");
        for (const auto& t : m.triangles)
            for (int c = 0; c < 3; ++c) isodel::fuzz::require(t[c] >= 0 && t[c] < n, "triangle index out of range");
        for (const auto& p : m.vertices)
            for (int c = 0; c < 3; ++c) isodel::fuzz::require(std::isfinite(p[c]), "non-finite vertex");
    });
    return 0;
}
