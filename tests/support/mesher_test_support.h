#pragma once
// Helpers for the mesher tests: mesh a manifest volume and certify the result with isodel verify
// (an independent reference topology, exact Hausdorff bounds, exact Delaunay conformity).
#include "support/skip.h"
#include "support/verify_test_support.h"

#include <catch2/catch.hpp>

#include <fstream>

#include <isodel/mesh.h>
#include <isodel/verify.h>

#include <algorithm>
#include <initializer_list>
#include <string>
#include <vector>

namespace isodel::testing {

struct MeshAndVerify {
    MeshResult mesh;
    VerifyReport report;
    std::vector<int> genera; ///< of M, sorted
};

/// Meshes with \p mo (isovalue, inside and eps_voxels set) and verifies at the same settings.
inline MeshAndVerify mesh_and_verify(const openvdb::FloatGrid& grid, const MeshOptions& mo)
{
    MeshAndVerify out;
    out.mesh = mesh_isosurface(grid, mo);
    VerifyOptions vo;
    vo.isovalue = mo.isovalue;
    vo.inside = mo.inside;
    vo.eps_voxels = mo.eps_voxels;
    out.report = verify_surface(grid, out.mesh.surface, vo);
    for (const auto& c : out.mesh.stats.components) out.genera.push_back(c.genus);
    std::sort(out.genera.begin(), out.genera.end());
    return out;
}

inline MeshAndVerify mesh_and_verify(const openvdb::FloatGrid& grid, double iso, Inside inside, double eps_voxels,
                                     int threads = 0)
{
    MeshOptions mo;
    mo.isovalue = iso;
    mo.inside = inside;
    mo.eps_voxels = eps_voxels;
    mo.threads = threads;
    return mesh_and_verify(grid, mo);
}

inline std::vector<int> expected_genera(const Json& entry)
{
    std::vector<int> g;
    for (const auto& v : entry.at("expected_topology").at("genus")) g.push_back(v.get<int>());
    std::sort(g.begin(), g.end());
    return g;
}

/// The manifest entry of \p file, or null.
inline const Json* manifest_entry(const Json& manifest, const std::string& file)
{
    for (const auto& e : manifest)
        if (json_string(e, "file") == file) return &e;
    return nullptr;
}

inline Inside inside_of(const Json& entry)
{
    return json_string(entry, "inside") == "below" ? Inside::Below : Inside::Above;
}

/// Whether \p path (a file of ../shared/data) exists; if not, the test says so and counts as
/// skipped: `if (!testing::shared_file_present(path)) return;`.
inline bool shared_file_present(const std::string& path)
{
    if (std::ifstream(path)) return true;
    mark_skipped();
    WARN("skipped: " << path << " not found (../shared/data absent)");
    return false;
}

/// A crop of literal samples: samples[z][y][x] at index origin + (x, y, z), every other sample -1
/// (inside = above 0 closes every level set inside the box).
template <int NZ, int NY, int NX>
openvdb::FloatGrid::Ptr samples_in_box(const double (&samples)[NZ][NY][NX], openvdb::Coord origin)
{
    auto grid = openvdb::FloatGrid::create(-1.f);
    auto acc = grid->getAccessor();
    for (int z = 0; z < NZ; ++z)
        for (int y = 0; y < NY; ++y)
            for (int x = 0; x < NX; ++x) acc.setValueOn(origin.offsetBy(x, y, z), float(samples[z][y][x]));
    return grid;
}

/// Meshes \p grid at v = 0 (inside above) at each eps and requires a certified mesh (determined
/// reference, every check passed) whose sorted genera are \p genera.
inline void require_certified(const openvdb::FloatGrid& grid, std::initializer_list<double> eps_voxels,
                              const std::vector<int>& genera)
{
    for (double eps : eps_voxels) {
        INFO("eps " << eps << " voxel");
        const auto r = mesh_and_verify(grid, 0.0, Inside::Above, eps);
        INFO(r.report.summary());
        CHECK(r.report.reference.determined);
        CHECK(r.report.passed());
        CHECK(r.genera == genera);
    }
}

} // namespace isodel::testing
