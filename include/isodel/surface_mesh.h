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

/// Writes a tetrahedral mesh; the format follows the extension: .mesh (Medit ASCII: vertices,
/// triangles with ref 1, tetrahedra with their region ref), .vtu (VTK XML, raw appended binary,
/// cell data "region"; the surface triangles are not cells), .msh (Gmsh 4.1 ASCII: physical
/// groups 1 "inside", 2 "outside" (volumes) and 3 "surface"). Written atomically like
/// write_surface_mesh. \throw InvalidInput unknown extension (names the file); \throw IoError.
void write_tet_mesh(const std::string& path, const TetMesh& mesh);

/// Reads a Medit .mesh tetrahedral mesh (vertices, triangles, tetrahedra with region refs).
/// \throw InvalidInput not .mesh, malformed (message names the file); IoError unreadable.
TetMesh read_tet_mesh(const std::string& path);

/// True when \p path ends in an extension write_tet_mesh accepts.
bool is_tet_mesh_path(const std::string& path);

/// Reads a surface mesh written by isodel or another tool (.ply ascii/binary, .obj, .off, .stl).
/// STL vertices are merged by exact position.
/// \throw InvalidInput, IoError
SurfaceMesh read_surface_mesh(const std::string& path);

} // namespace isodel
