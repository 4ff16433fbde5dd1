// Fuzz target: the surface mesh readers `isodel verify` uses (src/io/read_surface_mesh.cpp).
// The first byte picks the extension (.ply, .obj, .off, .stl); the rest is the file.
#include "fuzz_input.h"

#include <isodel/surface_mesh.h>

#include <array>
#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 1) return 0;
    static const std::array<const char*, 4> extensions{".ply", ".obj", ".off", ".stl"};
    const isodel::fuzz::InputFile file(data + 1, size - 1, extensions[data[0] % extensions.size()]);
    isodel::fuzz::expect_clean_refusal(file.path(), [&] {
        const isodel::SurfaceMesh m = isodel::read_surface_mesh(file.path());
        const auto n = std::int64_t(m.vertices.size());
        for (const auto& t : m.triangles)
            for (int c = 0; c < 3; ++c) isodel::fuzz::require(t[c] >= 0 && t[c] < n, "triangle index out of range");
        for (const auto& p : m.vertices)
            for (int c = 0; c < 3; ++c) isodel::fuzz::require(std::isfinite(p[c]), "non-finite vertex");
    });
    return 0;
}
