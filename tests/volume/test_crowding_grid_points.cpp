// Grid points next to M removed after meshing (src/volume/crowding_grid_points.h): the
// certificate that a Voronoi cell misses Sigma is sound (checked against dense sampling of the
// cell), it passes where the protective layer keeps Sigma away, and it fails where Sigma enters.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"

#include "volume/crowding_grid_points.h"
#include "closed_ball/restricted_facets.h"

#include <random>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// Sigma = the plane x = 2.3; grid points of a 6^3 grid and the E points (2.3, y, z), except
/// the one at (y, z) = (2, 2), which leaves a hole in front of the sample (2, 2, 2).
struct PlaneSetup {
    openvdb::FloatGrid::Ptr grid = testing::make_grid(6, 1.0, openvdb::Vec3d(0.0),
                                                      [](const openvdb::Vec3d& x) { return x[0] - 2.3; });
    octree::SampleField field{grid, 0.0, Inside::Above};
    Delaunay dt;
    PlaneSetup()
    {
        std::uint32_t id = 0;
        for (int z = 0; z < 6; ++z)
            for (int y = 0; y < 6; ++y) {
                for (int x = 0; x < 6; ++x) dt.insert(Point(x, y, z))->info() = VertexInfo{id++, PointKind::Grid};
                if (!(y == 2 && z == 2)) dt.insert(Point(2.3, y, z))->info() = VertexInfo{id++, PointKind::Edge};
            }
    }
    Vertex_handle grid_vertex(int x, int y, int z) const { return dt.nearest_vertex(Point(x, y, z)); }
};

} // namespace

TEST_CASE("crowding grid points: the Voronoi-cell certificate is sound", "[mesher][tets]")
{
    const PlaneSetup s;
    const octree::SampleField::Reader reader(s.field);
    std::mt19937 rng(7);
    int certified = 0;
    for (auto v = s.dt.finite_vertices_begin(); v != s.dt.finite_vertices_end(); ++v) {
        if (v->info().kind != PointKind::Grid) continue;
        std::vector<Cell_handle> cells;
        s.dt.incident_cells(v, std::back_inserter(cells));
        if (!voronoi_cell_misses_sigma(s.dt, v, cells, reader)) continue;
        ++certified;
        // Dense sampling of the cell: every point nearest to v is on v's side of the plane.
        const bool inside = v->point().x() >= 2.3;
        std::uniform_real_distribution<double> U(-0.6, 0.6);
        for (int k = 0; k < 2000; ++k) {
            const Point q(v->point().x() + U(rng), v->point().y() + U(rng), v->point().z() + U(rng));
            if (s.dt.nearest_vertex(q) != Vertex_handle(v)) continue;
            INFO(v->point() << " sample " << q);
            CHECK((q.x() >= 2.3) == inside);
        }
    }
    CHECK(certified > 0);
    // The sample facing the hole in E: its cell reaches x = 2.5 > 2.3, Sigma enters it.
    const Vertex_handle hole = s.grid_vertex(2, 2, 2);
    std::vector<Cell_handle> cells;
    s.dt.incident_cells(hole, std::back_inserter(cells));
    CHECK_FALSE(voronoi_cell_misses_sigma(s.dt, hole, cells, reader));
}

TEST_CASE("crowding grid points: removal takes the certified neighbours of M only", "[mesher][tets]")
{
    PlaneSetup s;
    const std::size_t before = s.dt.number_of_vertices();
    // Samples at x = 2 are 0.3 from their E point, x = 3 are 0.7: reach 0.35 takes x = 2 only,
    // and not (2, 2, 2), whose cell meets Sigma.
    const std::vector<Vertex_handle> crowding = crowding_grid_points(s.dt, s.field, 0.35);
    const std::size_t removed = crowding.size();
    for (std::size_t i = 1; i < crowding.size(); ++i) CHECK(crowding[i - 1]->info().id < crowding[i]->info().id);
    FacetCache cache;
    cache.remove(s.dt, crowding);
    CHECK(removed > 0);
    CHECK(s.dt.number_of_vertices() == before - removed);
    CHECK(s.dt.is_valid());
    const Vertex_handle kept = s.dt.nearest_vertex(Point(2, 2, 2));
    CHECK(kept->point() == Point(2, 2, 2));
    CHECK(removed <= 35); // of the 36 samples at x = 2
    int at3 = 0;
    for (auto v = s.dt.finite_vertices_begin(); v != s.dt.finite_vertices_end(); ++v)
        at3 += v->info().kind == PointKind::Grid && v->point().x() == 3.0;
    CHECK(at3 == 36);
}
