#pragma once
// Internal: DELVOLMESH (paper Section 4.1). Once M = Del(E u G u N)|Sigma is final, the grid
// points G' strictly inside and/or outside that are not in G are added (interior_points.h); the
// protective layer keeps their Voronoi cells off Sigma (Theorem 3), so M stays a subcomplex of
// the finer triangulation, whose tetrahedra then fill the region(s) with grid-sized elements.
//
// Nothing here takes the theorem on trust: after the insertion the restricted facets are
// recomputed and M is extracted again; it must equal \p surface exactly (same vertices, same
// triangles, same orientation), and every G' point's Voronoi cell is checked to keep to its side
// of Sigma (grid_cell_check.h). Either failure throws GuaranteeViolated.
#include "delaunay/delaunay.h"
#include "closed_ball/restricted_facets.h"
#include "octree/adaptive_grid.h"
#include "volume/interior_points.h"
#include "octree/sample_field.h"

#include <isodel/interrupt.h>
#include <isodel/mesh.h>

#include <openvdb/openvdb.h>

namespace isodel::mesher {

struct VolumeMeshParams {
    TetRegion region = TetRegion::Inside;
    int max_cells_walk = 0;           ///< as for FacetCache::update
    std::uint32_t* next_id = nullptr; ///< the mesher's vertex id counter (advanced)
    Interrupter* interrupter = nullptr;
    /// On an adaptive grid: G' is the leaf corners only (adaptive_points.h).
    const octree::AdaptiveGrid::Reader* adaptive = nullptr;
    /// Improve the worst tets by smoothing and flips away from M (tet_improvement.h); false
    /// keeps the Delaunay tetrahedra.
    bool improve = true;
    /// Graded G' on a uniform grid (interior_points.h); null = every sample.
    const GradedSpacing* spacing = nullptr;
};

/// Inserts G' into \p dt (through \p cache), checks that M is unchanged, classifies the cells
/// and returns the tetrahedra of params.region (numbering as documented for MeshResult::tets).
/// Fills \p st (counts, volumes, quality).
/// \pre \p surface == extract_surface(dt, cache); params.region != None
/// \throw GuaranteeViolated the insertion changed M, or M does not bound a region
TetMesh build_volume_mesh(Delaunay& dt, FacetCache& cache, const octree::SampleField& field,
                          const openvdb::MaskGrid& g_mask, const SurfaceMesh& surface,
                          const VolumeMeshParams& params, TetStats& st);

} // namespace isodel::mesher
