#pragma once
// Internal: improving the worst tetrahedra of DELVOLMESH's output without touching M.
//
// The bad elements of Del(E u G u N u G') all touch M (tet_quality.h): E points sit anywhere on
// their grid edges, so a grid point or a second surface point can lie almost in the plane of
// three others. Delaunay refinement cannot help there (a circumcentre inside a surface Delaunay
// ball would change M), so, like Mesh_3's perturb and exude, this step gives up the Delaunay
// property of the tetrahedra (not of M) for their shape. It is local, greedy and only ever
// improves (after Klingner & Shewchuk, "Aggressive tetrahedral mesh improvement", 2007):
//   - vertex smoothing: a vertex that is not M's and not on the region's outer boundary moves
//     to the best of a few candidate positions, then climbs along the steepest ascent direction
//     of its star's worst tets (the nearest point to the origin of their gradients' convex hull,
//     as Freitag & Ollivier-Gooch's non-smooth optimisation), each step kept if every tet of its
//     star stays positively oriented (exact orientation predicate) and the worst angle grows;
//   - edge collapse: such a vertex goes, its star re-filled as the cone from one of its
//     neighbours (any vertex, M's included, which stays put), if every new tet is positively
//     oriented and the worst angle grows;
//   - 2-3 flips and edge removal: two tets sharing a face, or the 3 to 7 tets around an edge
//     (Shewchuk's edge removal; 3 is the 3-2 flip), all of one region, are replaced when every
//     new tet is positively oriented and the worst dihedral angle grows;
//   - vertex insertion: a new vertex next to a tet still bad after all that (a sliver between
//     triangles of M, or on a thin triangle of M), its cavity re-filled as a cone, when the worst
//     angle grows; candidates above each face and next to each edge, at a distance set by that
//     edge's length (a short edge of M needs a vertex near it), and the new vertex is smoothed.
// Nothing changes a vertex of M, a triangle of M (its two sides are different regions, or it
// bounds the mesh) or a region tag, so the inside region's boundary stays M exactly and its
// volume stays the volume M encloses. Each pass visits the tets below the target angle in a
// fixed order (by angle, then by vertex indices).
//
// In parallel, by blocks (tet_improvement_blocks.cpp): each tet goes to the cube of side
// block_size holding its centroid, and the blocks with bad tets are improved concurrently, each
// by the sequential improver on its own tets alone. That is safe without locks: every move
// above keeps the boundary of the tets it is given, and a vertex moves or goes only when its
// whole star is among them (a closed star: a tet mesh's link of an interior vertex is one
// sphere), so no two blocks change the same tet or vertex, or read what another changes.
// Vertices on a block's boundary stay; a second sweep over blocks shifted by half a side gives
// most of them an interior, and a last block around the bad tets still near a boundary (split
// into its pieces that share no vertex) the rest. The blocks are a fixed function of the
// geometry and their results are merged in block order, so the mesh does not depend on the
// thread count.
#include <isodel/surface_mesh.h>

#include <cstddef>

namespace isodel::mesher {

struct TetImprovementParams {
    double target_deg = 15.0;   ///< work on tets with a dihedral angle below this or above 180 minus it
    int max_passes = 10;        ///< bound on the sweeps over the bad tets (per block)
    double block_size = 0;      ///< world units; 0: the whole mesh as one block, serially
    /// The last, serial, block (tet_improvement_blocks.cpp) improved as its vertex-disjoint
    /// pieces, concurrently: the same tets as one block (false, which tests compare against).
    bool split_last_block = true;
};

struct TetImprovementStats {
    double min_dihedral_before_deg = 0;
    std::size_t vertices_moved = 0, vertices_removed = 0, flips_23 = 0;
    std::size_t edges_removed = 0; ///< edge removals (3-2 flips and rings of up to 7 tets)
    std::size_t vertices_inserted = 0; ///< new vertices next to slivers of M (insert_vertex)
    std::size_t last_block_pieces = 0; ///< blocks the last block was improved as (split_last_block)
    int passes = 0;
};

/// Improves \p mesh in place (vertices with index < \p surface_vertices are M's and stay put).
/// Tets keep positive orientation; the result lists tets in no particular order, and the
/// vertices after M's are renumbered (collapses remove some).
TetImprovementStats improve_tets(TetMesh& mesh, std::size_t surface_vertices, const TetImprovementParams& params);

/// Smallest dihedral angle of the tetrahedron (a, b, c, d), in degrees (0 when degenerate).
double min_dihedral_deg(const std::array<double, 3>& a, const std::array<double, 3>& b,
                        const std::array<double, 3>& c, const std::array<double, 3>& d);

} // namespace isodel::mesher
