// DELVOLMESH (paper Section 4.1) on small volumes: a sphere built in code and the bundled
// torus.vdb. Every tet positively oriented, inside volume == volume enclosed by M (1e-9
// relative), the inside region's boundary == M triangle for triangle, region tags, the outside
// region filling the grid's box, thread-count independence, and the flood-fill labels against
// the sign of F at the circumcentres.
#include <catch2/catch.hpp>

#include "support/mesher_test_support.h"
#include "support/volume_mesh_checks.h"

#include "octree/sample_field.h"
#include "octree/segment_walk.h"

#include <isodel/volume.h>

using namespace isodel;

namespace {

const openvdb::Vec3d kCentre(12.37, 12.11, 12.53);

openvdb::FloatGrid::Ptr sphere_grid()
{
    // 26^3 samples at voxel 0.5: index box [0, 25], so the outside box is [-2, 27] (29 voxels).
    return testing::make_grid(26, 0.5, openvdb::Vec3d(1.0, -2.0, 0.5),
                              [](const openvdb::Vec3d& x) { return testing::sphere_f(x, kCentre, 7.2); });
}

MeshResult mesh_tets(const openvdb::FloatGrid& grid, double iso, Inside inside, TetRegion region, int threads = 0,
                     bool improve = true, TetSpacing spacing = TetSpacing::Graded)
{
    MeshOptions mo;
    mo.tet_spacing = spacing;
    mo.isovalue = iso;
    mo.inside = inside;
    mo.eps_voxels = 0.5;
    mo.threads = threads;
    mo.tets = region;
    mo.improve_tets = improve;
    return mesh_isosurface(grid, mo);
}

std::array<double, 3> circumcentre(const std::array<double, 3>& p0, const std::array<double, 3>& p1,
                                   const std::array<double, 3>& p2, const std::array<double, 3>& p3)
{
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = p1[k] - p0[k];
        b[k] = p2[k] - p0[k];
        c[k] = p3[k] - p0[k];
    }
    auto cross = [](const double* u, const double* v, double* w) {
        w[0] = u[1] * v[2] - u[2] * v[1];
        w[1] = u[2] * v[0] - u[0] * v[2];
        w[2] = u[0] * v[1] - u[1] * v[0];
    };
    auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
    double bc[3], ca[3], ab[3];
    cross(b, c, bc);
    cross(c, a, ca);
    cross(a, b, ab);
    const double den = 2 * dot(a, bc);
    std::array<double, 3> r;
    for (int k = 0; k < 3; ++k) r[k] = p0[k] + (dot(a, a) * bc[k] + dot(b, b) * ca[k] + dot(c, c) * ab[k]) / den;
    return r;
}

} // namespace

TEST_CASE("volume mesh: sphere, inside region", "[mesher][volume_mesh]")
{
    const auto grid = sphere_grid();
    const MeshResult r =
        mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Inside, 0, /*improve=*/false, TetSpacing::Uniform);
    testing::require_volume_mesh(r, TetRegion::Inside, "sphere inside");
    CHECK(r.stats.tets.tets_outside == 0);
    CHECK(r.stats.tets.g_prime > 0);
    // The ball's volume, to within what eps = 0.5 voxel allows (a shell of 0.25 world units).
    const double R = 7.2 * 0.5, ball = 4.0 / 3.0 * M_PI * R * R * R;
    CHECK(std::abs(r.stats.tets.volume_inside - ball) < 4 * M_PI * R * R * 0.25);
    CHECK(r.stats.tets.min_dihedral_deg > 0);
    CHECK(r.stats.tets.max_dihedral_deg < 180);
    // Delaunay tets of grid points only are pieces of lattice cubes (src/volume/tet_quality.h).
    CHECK(r.stats.tets.min_dihedral_deg_off_surface >= 35.26);
    CHECK(r.stats.tets.max_radius_edge_off_surface <= 0.8661);
    CHECK(r.stats.seconds.count("tets") == 1);
    CHECK(testing::Json::parse(to_json(r.stats)).at("tets").contains("min_dihedral_deg"));
}

TEST_CASE("volume mesh: sphere, both regions fill the grid's box", "[mesher][volume_mesh]")
{
    const auto grid = sphere_grid();
    // Uniform G': the box [-2, 27]. Graded: its extent grown to a multiple of 8 voxels, [-2, 30].
    const bool uniform = GENERATE(true, false);
    const TetSpacing spacing = uniform ? TetSpacing::Uniform : TetSpacing::Graded;
    INFO((uniform ? "uniform" : "graded"));
    const MeshResult r = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Both, 0, true, spacing);
    testing::require_volume_mesh(r, TetRegion::Both, "sphere both");
    const double box = std::pow((uniform ? 29 : 32) * 0.5, 3);
    CHECK(std::abs(r.stats.tets.volume_inside + r.stats.tets.volume_outside - box) <= 1e-9 * box);
    CHECK(r.stats.tets.tets_inside > 0);
    CHECK(r.stats.tets.tets_outside > 0);

    const MeshResult o = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Outside, 0, true, spacing);
    testing::require_volume_mesh(o, TetRegion::Outside, "sphere outside");
    CHECK(o.stats.tets.tets_inside == 0);
    CHECK(std::abs(o.stats.tets.volume_outside + o.stats.tets.volume_enclosed_by_surface - box) <= 1e-9 * box);
    // The same surface whatever the region: G' never changes M.
    CHECK(o.surface.triangles == r.surface.triangles);
}

TEST_CASE("volume mesh: graded G' keeps M and the volumes with fewer tets than uniform G'", "[mesher][volume_mesh]")
{
    // A sphere of radius 16 voxels: deep enough inside for the 2 and 4 voxel lattices.
    const auto grid = testing::make_grid(40, 1.0, openvdb::Vec3d(0.0),
                                         [](const openvdb::Vec3d& x) { return testing::sphere_f(x, {19.3, 19.6, 19.2}, 16.0); });
    const MeshResult u = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Inside, 0, true, TetSpacing::Uniform);
    const MeshResult g = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Inside, 0, true, TetSpacing::Graded);
    testing::require_volume_mesh(u, TetRegion::Inside, "sphere uniform");
    testing::require_volume_mesh(g, TetRegion::Inside, "sphere graded");
    CHECK(g.surface.vertices == u.surface.vertices);
    CHECK(g.surface.triangles == u.surface.triangles);
    CHECK(std::abs(g.stats.tets.volume_inside - u.stats.tets.volume_inside) <= 1e-9 * u.stats.tets.volume_inside);
    INFO("tets uniform " << u.stats.tets.tets_inside << " graded " << g.stats.tets.tets_inside << "; G' uniform "
                          << u.stats.tets.g_prime << " graded " << g.stats.tets.g_prime);
    // Most tets have a vertex on M (its shell of E and G is the same either way); G' is what shrinks.
    CHECK(g.stats.tets.g_prime < 0.5 * double(u.stats.tets.g_prime));
    CHECK(g.stats.tets.tets_inside < 0.8 * double(u.stats.tets.tets_inside));
    // The Delaunay tets where the lattices meet are no longer cube pieces (35.26 degrees; points of
    // both lattices can be cospherical, and slivers come out of such sets); the improvement lifts
    // them to no worse than the uniform mesh's tets off M.
    INFO("off M: uniform " << u.stats.tets.min_dihedral_deg_off_surface << " graded " << g.stats.tets.min_dihedral_deg_off_surface);
    CHECK(g.stats.tets.min_dihedral_deg_off_surface >= u.stats.tets.min_dihedral_deg_off_surface - 1e-9);
    // The worst tets are M's (all four vertices on it), which G' does not touch.
    CHECK(g.stats.tets.min_dihedral_deg >= u.stats.tets.min_dihedral_deg - 1e-9);
    // A smaller tet_size gives more tets; a smaller grading too.
    MeshOptions mo;
    mo.eps_voxels = 0.5;
    mo.inside = Inside::Above;
    mo.tets = TetRegion::Inside;
    mo.tet_size = 2.0;
    const MeshResult small = mesh_isosurface(*grid, mo);
    CHECK(small.surface.triangles == u.surface.triangles);
    CHECK(small.stats.tets.tets_inside > g.stats.tets.tets_inside);
    CHECK(small.stats.tets.tets_inside < u.stats.tets.tets_inside);
    mo.tet_size = 0;
    mo.tet_grading = 0.25;
    const MeshResult gentle = mesh_isosurface(*grid, mo);
    CHECK(gentle.stats.tets.tets_inside > g.stats.tets.tets_inside);
    testing::require_volume_mesh(gentle, TetRegion::Inside, "sphere gentle grading");
}

TEST_CASE("volume mesh: bundled torus.vdb (level set, inside below)", "[mesher][volume_mesh]")
{
    const Volume vol = read_volume(std::string(ISODEL_TEST_DATA) + "/torus.vdb");
    const MeshResult r = mesh_tets(*vol.grid, 0.0, vol.default_inside, TetRegion::Both);
    testing::require_volume_mesh(r, TetRegion::Both, "torus.vdb both");
    const MeshResult s = mesh_tets(*vol.grid, 0.0, vol.default_inside, TetRegion::None);
    CHECK(s.tets.tets.empty());
    CHECK(s.surface.triangles == r.surface.triangles);
    CHECK(s.surface.vertices == r.surface.vertices);
}

TEST_CASE("tet improvement keeps M, the regions and the volumes, and lifts the worst angles",
          "[mesher][volume_mesh][tet_improvement]")
{
    const Volume vol = read_volume(std::string(ISODEL_TEST_DATA) + "/torus.vdb");
    const auto grid = sphere_grid();
    struct Case {
        const openvdb::FloatGrid* grid;
        Inside inside;
        TetRegion region;
        const char* what;
    };
    for (const Case& c : {Case{grid.get(), Inside::Above, TetRegion::Both, "sphere both"},
                          Case{grid.get(), Inside::Above, TetRegion::Inside, "sphere inside"},
                          Case{vol.grid.get(), vol.default_inside, TetRegion::Both, "torus.vdb both"}}) {
        const MeshResult del = mesh_tets(*c.grid, 0.0, c.inside, c.region, 0, false);
        const MeshResult imp = mesh_tets(*c.grid, 0.0, c.inside, c.region, 0, true);
        INFO(c.what << ": Delaunay " << del.stats.tets.min_dihedral_deg << " deg, " << del.stats.tets.tets_below_10deg
                    << " under 10; improved " << imp.stats.tets.min_dihedral_deg << " deg, "
                    << imp.stats.tets.tets_below_10deg << " under 10");
        testing::require_volume_mesh(del, c.region, std::string(c.what) + " Delaunay");
        testing::require_volume_mesh(imp, c.region, std::string(c.what) + " improved");
        // M is the same mesh, and the improved inside region still has M as its boundary
        // (require_volume_mesh) and the same volume.
        CHECK(imp.surface.vertices == del.surface.vertices);
        CHECK(imp.surface.triangles == del.surface.triangles);
        CHECK(std::abs(imp.stats.tets.volume_inside - del.stats.tets.volume_inside) <=
              1e-9 * (1 + del.stats.tets.volume_inside));
        CHECK(std::abs(imp.stats.tets.volume_outside - del.stats.tets.volume_outside) <=
              1e-9 * (1 + del.stats.tets.volume_outside));
        // What it starts from is the Delaunay mesh, and it only ever improves.
        CHECK(imp.stats.tets.min_dihedral_deg_delaunay == Approx(del.stats.tets.min_dihedral_deg).margin(1e-6));
        CHECK(del.stats.tets.vertices_moved + del.stats.tets.flips + del.stats.tets.vertices_removed +
                  del.stats.tets.vertices_inserted ==
              0);
        CHECK(imp.stats.tets.vertices_moved + imp.stats.tets.flips + imp.stats.tets.vertices_removed > 0);
        CHECK(imp.stats.tets.min_dihedral_deg >= del.stats.tets.min_dihedral_deg);
        CHECK(imp.stats.tets.tets_below_10deg < del.stats.tets.tets_below_10deg);
        CHECK(imp.stats.tets.vertices == imp.tets.vertices.size());
    }
}

TEST_CASE("tet improvement with vertex insertion: no sliver left between good triangles of M",
          "[mesher][volume_mesh][tet_improvement]")
{
    // With M's triangles kept above 25 degrees (--facet-angle), what bounds the smallest dihedral
    // angle is the improvement itself. Without vertex insertion the torus keeps slivers of a
    // hundredth of a degree or less (two faces on M, or a face on M and two vertices off it),
    // which no smoothing or flip can fix; with it, the hill-climbing smoothing and the insertion
    // candidates next to short edges, the torus clears with margin the bounds checked here:
    // smallest angle 4 degrees, and at most 1 tet in 10000 under 10 degrees.
    const Volume vol = read_volume(std::string(ISODEL_TEST_DATA) + "/torus.vdb");
    MeshOptions mo;
    mo.isovalue = 0.0;
    mo.inside = vol.default_inside;
    mo.eps_voxels = 0.5;
    mo.tets = TetRegion::Both;
    mo.facet_angle_deg = 25;
    const MeshResult r = mesh_isosurface(*vol.grid, mo);
    testing::require_volume_mesh(r, TetRegion::Both, "torus.vdb both, facet angle 25");
    const auto& t = r.stats.tets;
    INFO("min dihedral " << t.min_dihedral_deg << " deg (Delaunay " << t.min_dihedral_deg_delaunay << "), "
                         << t.tets_below_10deg << " of " << t.tets_inside + t.tets_outside << " under 10 deg, "
                         << t.vertices_inserted << " vertices inserted");
    CHECK(t.vertices_inserted > 0);
    CHECK(t.min_dihedral_deg_delaunay < 1.0); // the Delaunay tets do have slivers
    CHECK(t.min_dihedral_deg >= 4.0);
    CHECK(t.tets_below_10deg * 10000 < t.tets_inside + t.tets_outside);
}

TEST_CASE("volume mesh: same tetrahedra with 1 and 2 threads", "[mesher][volume_mesh][determinism]")
{
    const auto grid = sphere_grid();
    const MeshResult a = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Both, 1);
    const MeshResult b = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Both, 2);
    CHECK(a.tets.vertices == b.tets.vertices);
    CHECK(a.tets.tets == b.tets.tets);
    CHECK(a.tets.tet_region == b.tets.tet_region);
}

TEST_CASE("volume mesh: flood-fill labels agree with the sign of F at the circumcentres",
          "[mesher][volume_mesh]")
{
    // Labels are decided on the Delaunay tets (the improvement only keeps them).
    const auto grid = sphere_grid();
    const MeshResult r = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Both, 0, /*improve=*/false);
    // The mesher meshes Sigma' (octree/face_slabs.h): F read through its slabs at eps 0.5 voxel.
    octree::SampleField field(grid, 0.0, Inside::Above);
    field.set_face_slabs(octree::face_slabs_for_eps(0.5));
    const octree::SampleField::Reader reader(field);
    std::size_t disagree = 0;
    for (std::size_t i = 0; i < r.tets.tets.size(); ++i) {
        const auto& q = r.tets.tets[i];
        const auto cc = circumcentre(r.tets.vertices[q[0]], r.tets.vertices[q[1]], r.tets.vertices[q[2]],
                                     r.tets.vertices[q[3]]);
        const double phi = octree::phi_at(reader, field.world_to_index({cc[0], cc[1], cc[2]}));
        if ((phi > 0 ? 1 : 2) != r.tets.tet_region[i]) ++disagree;
    }
    INFO(disagree << " of " << r.tets.tets.size() << " tets labelled against the sign of F at their circumcentre");
    CHECK(disagree == 0);
}

TEST_CASE("volume mesh checks catch broken meshes", "[mesher][volume_mesh]")
{
    // The acceptance checks themselves must be able to fail: break a good mesh three ways.
    const auto grid = sphere_grid();
    const MeshResult good = mesh_tets(*grid, 0.0, Inside::Above, TetRegion::Inside);
    REQUIRE(good.tets.tets.size() > 10);
    MeshResult flipped = good;
    std::swap(flipped.tets.tets[5][2], flipped.tets.tets[5][3]);
    CHECK(testing::check_volume_mesh(flipped, TetRegion::Inside).non_positive == 1);
    MeshResult holed = good;
    holed.tets.tets.erase(holed.tets.tets.begin() + 7);
    holed.tets.tet_region.erase(holed.tets.tet_region.begin() + 7);
    const auto c = testing::check_volume_mesh(holed, TetRegion::Inside);
    CHECK_FALSE(c.boundary_ok);
    CHECK(std::abs(c.volume_inside - c.enclosed) > 1e-9 * c.enclosed);
    MeshResult retagged = good;
    retagged.tets.tet_region[3] = 2;
    CHECK_FALSE(testing::check_volume_mesh(retagged, TetRegion::Inside).tags_ok);
}
