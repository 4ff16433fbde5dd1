// The disk certificate of CBP_VC (src/closed_ball/voronoi_cell_disks.h) proves Vor(p) n Sigma'
// a graph over a direction d, and starts from Sigma's normal at p's preimage. Not from grad F'
// at p: an E point lies on a grid edge, inside two face slabs, where grad F' keeps only the
// edge's component, and wherever Sigma' crosses a lattice plane normal to the edge inside Vor(p)
// it is a wall parallel to the edge. A Voronoi cell several voxels wide (a cell of a coarse
// leaf) holds such walls, and a run along the edge spends its box budget there first.
#include <catch2/catch.hpp>

#include "closed_ball/voronoi_cell_disks.h"
#include "delaunay/delaunay.h"
#include "octree/sample_field.h"

#include <openvdb/openvdb.h>

using namespace isodel;
using namespace isodel::mesher;

namespace {

/// F = (x - 8.3) + 0.8 (y - 8) + 0.6 (z - 8) sampled on 0..16 per axis: Sigma a tilted plane
/// through (8.3, 8, 8), which lies on the x-edge from (8, 8, 8).
openvdb::FloatGrid::Ptr tilted_plane()
{
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(-100.0f);
    auto acc = grid->getAccessor();
    for (int z = 0; z <= 16; ++z)
        for (int y = 0; y <= 16; ++y)
            for (int x = 0; x <= 16; ++x)
                acc.setValue(openvdb::Coord(x, y, z), float((x - 8.3) + 0.8 * (y - 8) + 0.6 * (z - 8)));
    return grid;
}

} // namespace

TEST_CASE("disk certificate: a Voronoi cell three voxels wide around an E point certifies with its first direction",
          "[mesher][closed_ball]")
{
    octree::SampleField field(tilted_plane(), 0.0, Inside::Above);
    field.set_face_slabs(octree::FaceSlabs{0.1});

    // p and the 26 points of a lattice of spacing 3 around it: Vor(p) is the cube p +- 1.5, which
    // holds the lattice planes x = 7, 8 and 9, each crossed by Sigma inside it.
    Delaunay dt;
    std::uint32_t id = 0;
    const Point p(8.3, 8, 8);
    const Vertex_handle vp = dt.insert(p);
    vp->info() = VertexInfo{id++, PointKind::Edge};
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (x || y || z) dt.insert(Point(8.3 + 3 * x, 8 + 3 * y, 8 + 3 * z))->info() = VertexInfo{id++, PointKind::Grid};
    REQUIRE(dt.number_of_vertices() == 27);

    std::vector<Vertex_handle> pending{vp};
    VoronoiCellDiskStats stats;
    const std::vector<Candidate> found = voronoi_cell_disk_violations(dt, field, pending, 0.1, &stats);
    CHECK(found.empty());
    CHECK(pending.empty());
    CHECK(stats.certified == 1);
    // Starting from grad F' at p (the edge's direction alone) took a second direction here.
    CHECK(stats.directions == 1);
}
