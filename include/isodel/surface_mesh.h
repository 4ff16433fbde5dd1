#pragma once
/// \file surface_mesh.h
/// Plain triangle and tetrahedral mesh arrays (world coordinates), as libigl's V/F matrices.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace isodel {

/// A triangle mesh: #V vertex positions (world units) and #F triangles indexing them.
/// Triangles are oriented counter-clockwise seen from outside (normals point to the outside region).
struct SurfaceMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<std::int32_t, 3>> triangles;
};

/// A tetrahedral mesh: #V vertices, #T positively oriented tetrahedra, a region tag per tet
/// (1 inside, 2 outside) and the boundary triangles (the surface mesh) with their tag.
struct TetMesh {
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<std::int32_t, 4>> tets;
    std::vector<std::int32_t> tet_region;
    std::vector<std::array<std::int32_t, 3>> triangles;
};

/// Writes a surface mesh; the format follows the extension: .ply (binary little-endian),
/// .obj, .off, .stl (binary). Written to a temporary name in the same folder, then renamed.
/// \throw InvalidInput unknown extension; \throw IoError on write failure.
void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh);

/// Reads a surface mesh written by isodel or another tool (.ply ascii/binary, .obj, .off, .stl).
/// STL vertices are merged by exact position.
/// \throw InvalidInput, IoError
SurfaceMesh read_surface_mesh(const std::string& path);

} // namespace isodel
