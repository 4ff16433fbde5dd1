// The thin-neck dumbbell (../shared/data/analytic): OpenVDB's marching cubes (volumeToMesh) tears
// the neck apart; isodel keeps the one component of genus 0 the trilinear level set has, and
// verify certifies the mesh.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include <openvdb/tools/VolumeToMesh.h>

#include <numeric>

using namespace isodel;

namespace {

/// Connected components of a polygon soup sharing vertex indices.
int component_count(std::size_t nv, const std::vector<std::vector<std::uint32_t>>& polys)
{
    std::vector<std::size_t> parent(nv);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](std::size_t a) {
        while (parent[a] != a) a = parent[a] = parent[parent[a]];
        return a;
    };
    std::vector<char> used(nv, 0);
    for (const auto& p : polys)
        for (std::size_t k = 0; k < p.size(); ++k) {
            used[p[k]] = 1;
            parent[find(p[k])] = find(p[0]);
        }
    int n = 0;
    for (std::size_t i = 0; i < nv; ++i) n += used[i] && find(i) == i;
    return n;
}

} // namespace

TEST_CASE("thin neck: marching cubes splits it, isodel keeps one component", "[mesher][thin-neck]")
{
    const std::string path = testing::shared_data() + "/analytic/dumbbell_thin_neck.vdb";
    if (!testing::shared_file_present(path)) return;
    auto grid = testing::read_vdb(path, "");

    // Marching cubes, the speed floor users compare against.
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0);
    std::vector<std::vector<std::uint32_t>> polys;
    for (const auto& t : tris) polys.push_back({t[0], t[1], t[2]});
    for (const auto& q : quads) polys.push_back({q[0], q[1], q[2], q[3]});
    const int mc_components = component_count(points.size(), polys);
    INFO("volumeToMesh: " << mc_components << " components");
    CHECK(mc_components > 1);

    const auto r = testing::mesh_and_verify(*grid, 0.0, Inside::Below, 0.5);
    INFO(r.report.summary());
    CHECK(r.genera == std::vector<int>{0});
    CHECK(r.report.passed());
}
