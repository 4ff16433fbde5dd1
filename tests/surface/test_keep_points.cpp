// mesher::mesh_keeping_points (src/surface/final_points.h) returns the final point set E u G u N
// (for the benchmark's bare Delaunay row): one entry per inserted point, every vertex of M among
// them, and the same M as mesh_isosurface.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"
#include "surface/final_points.h"

#include <isodel/volume.h>

#include <set>

using namespace isodel;

TEST_CASE("mesh_keeping_points: the final point set E u G u N", "[mesher][points]")
{
    const auto grid = read_volume(std::string(ISODEL_TEST_DATA) + "/torus.vdb", ReadOptions()).grid;
    for (const bool snap : {false, true}) {
        MeshOptions mo;
        mo.isovalue = 0.0;
        mo.inside = Inside::Below;
        mo.eps_voxels = 0.5;
        mo.snap = snap;
        const MeshResult none = mesh_isosurface(*grid, mo);
        std::vector<std::array<double, 3>> points;
        const MeshResult r = mesher::mesh_keeping_points(*grid, mo, points);
        const auto& s = r.stats;
        INFO("snap " << snap);
        // Snapped E points are not inserted: their grid point, already in G, takes their place.
        CHECK(points.size() == s.e_points - s.snapped + s.g_points + s.bound_repairs + s.n_topology + s.n_geometry);
        const std::set<std::array<double, 3>> all(points.begin(), points.end());
        CHECK(all.size() == points.size());
        for (const auto& v : r.surface.vertices) CHECK(all.count(v) == 1);
        CHECK(r.surface.vertices == none.surface.vertices); // keeping the points changes nothing else
    }
}
