#pragma once
/// \file verify.h
/// Certificates for the guarantees of include/isodel/mesh.h, computed WITHOUT the mesher's code:
///  - the topology of Sigma = {F = v} from an exact refinement of the trilinear interpolant
///    (marching tetrahedra on a Freudenthal subdivision of an R x refined sub-lattice of every
///    cell Sigma crosses), at R and 2R ("undetermined" when they disagree);
///  - the combinatorics of M (closed, 2-manifold, consistently and outward oriented, no
///    self-intersections, components and genus), and the homeomorphism verdict;
///  - the two-sided Hausdorff distance between M and Sigma against eps;
///  - Delaunay conformity of every triangle of M, decided exactly (empty ball test);
///  - triangle quality.
/// The function F and its conventions (ties, domain) are those of octree/sample_field.h.
/// Plain structs only (no CGAL types) so callers need not see CGAL.
#include <isodel/stats.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <openvdb/openvdb.h>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace isodel {

struct VerifyOptions {
    double isovalue = 0.0;
    std::optional<Inside> inside;  ///< default: Below for level-set grids, Above otherwise
    double eps = 0.0;              ///< Hausdorff bound, world units; 0 = use eps_voxels
    double eps_voxels = 0.0;       ///< ... in smallest voxel edges; both 0 = skip Hausdorff
    /// R: reference topology at R and 2R. R is a minimum: it is raised (up to 16) while the 2R
    /// lattice stays within refine_budget samples (crossed cells x (2R)^3), because low R can
    /// agree on a wrong answer for near-critical data.
    int refine = 4;
    double refine_budget = 6.4e7;
    /// When R and 2R disagree, keep doubling (2R vs 4R, ...) up to this refinement, or further
    /// while the next lattice stays within 1.5 x refine_budget samples (small volumes: random
    /// cells with a saddle value near v settle only at R = 64); the reference is "determined"
    /// when two consecutive refinements agree. 0 = only R and 2R.
    int max_refine = 32;
    /// Sub-lattice refinement used to sample Sigma for Sigma -> M (spacing 1/R_h voxel);
    /// 0 = automatic: clamp(ceil(1 / eps_voxels), 4, 12).
    int hausdorff_refine = 0;
    bool check_delaunay = true;
    bool check_self_intersections = true;
    /// Reference "undetermined" counts as a failure (default: reported, not failing).
    bool require_determined_topology = false;
};

/// Check 1's homeomorphism verdict (VerifyReport::topology_verdict).
enum class TopologyVerdict {
    Fail,        ///< M is not a 2-manifold, or its genera differ from the reference's
    Pass,        ///< M is a 2-manifold with the reference's multiset of genera
    Undetermined ///< the reference topology was not determined (refinements disagree)
};

/// "fail", "pass", "undetermined": the words of the JSON report.
inline const char* to_string(TopologyVerdict verdict)
{
    switch (verdict) {
    case TopologyVerdict::Pass: return "pass";
    case TopologyVerdict::Undetermined: return "undetermined";
    case TopologyVerdict::Fail: break;
    }
    return "fail";
}

struct ReferenceTopologyReport {
    bool determined = false;
    std::size_t crossed_cells = 0;          ///< cells of the grid with mixed phi signs
    /// Lattice planes added through near-critical points of F (saddles within a small fraction of
    /// their cell's value range of v), on top of the uniform R x refinement.
    std::size_t critical_planes = 0;
    /// Each refinement tried, with the sorted genera it produced.
    std::vector<int> refinements;
    std::vector<std::vector<int>> genera;
    std::vector<ComponentTopology> components; ///< of the finest agreeing refinement
    double seconds = 0.0;
};

struct MeshTopologyReport {
    std::size_t vertices = 0, triangles = 0;
    std::size_t unreferenced_vertices = 0;
    std::size_t degenerate_triangles = 0;   ///< repeated index or exactly collinear corners
    std::size_t duplicate_triangles = 0;    ///< same vertex set as an earlier triangle
    std::size_t boundary_edges = 0;         ///< edges with one triangle
    std::size_t nonmanifold_edges = 0;      ///< edges with more than two triangles
    std::size_t nonmanifold_vertices = 0;   ///< vertex link not a single cycle
    std::size_t misoriented_edges = 0;      ///< two triangles traverse the edge the same way
    std::size_t inward_components = 0;      ///< normals point into the inside region
    bool closed = false, manifold = false, oriented = false, outward = false;
    bool self_intersection_checked = false;
    std::size_t self_intersecting_pairs = 0;
    std::vector<ComponentTopology> components; ///< sorted by genus, then size
};

struct DistanceStats {
    std::size_t samples = 0;
    double max = 0.0, rms = 0.0;             ///< world units
    double max_voxels = 0.0, rms_voxels = 0.0; ///< in smallest voxel edges
    std::array<double, 3> argmax{0, 0, 0};   ///< world position of the worst sample
    double sample_spacing = 0.0;             ///< world; sup <= max + sample_spacing
};

struct HausdorffReport {
    bool checked = false;
    double eps = 0.0, eps_voxels = 0.0;
    DistanceStats mesh_to_surface, surface_to_mesh;
    int sigma_refine = 0;                    ///< R_h used to sample Sigma
    std::size_t fallback_queries = 0;        ///< M samples that needed the local search
    std::size_t unresolved = 0;              ///< M samples with no point of Sigma found nearby
    double seconds = 0.0;
    bool passed = false;
};

struct DelaunayReport {
    bool checked = false;
    std::size_t triangles = 0;
    std::size_t dt_facets = 0;               ///< facets of CGAL's Del(V(M))
    std::size_t empty_ball_exact = 0;        ///< not a facet there, but an empty ball exists
    std::size_t non_delaunay = 0;            ///< no empty ball: a violation
    std::size_t degenerate = 0;              ///< collinear / repeated corners (violation)
    std::vector<std::array<int, 3>> examples; ///< up to 10 violating triangles
    double seconds = 0.0;
    bool passed = false;
};

/// isodel verify --tets: the tetrahedral mesh against M (what DELVOLMESH, paper Section 4.1, and
/// MeshOptions::tets promise of it, checked from the files alone).
struct TetReport {
    bool checked = false;
    std::size_t vertices = 0, tets = 0;
    std::size_t inverted = 0;          ///< not positively oriented (exact orientation test)
    std::size_t degenerate = 0;        ///< zero volume (coplanar corners)
    std::size_t unknown_region = 0;    ///< region tag other than 1 (inside) or 2 (outside)
    std::size_t inside_tets = 0, outside_tets = 0;
    double inside_volume = 0, outside_volume = 0; ///< world units^3
    double enclosed_volume = 0;        ///< volume enclosed by M (divergence theorem)
    double volume_rel_error = 0;       ///< |inside - enclosed| / enclosed
    /// Boundary of the inside region (faces of exactly one inside tet, outward) against M's
    /// triangles (matched by exact vertex position): faces of one but not the other.
    std::size_t boundary_faces = 0, boundary_not_in_mesh = 0, mesh_not_in_boundary = 0;
    std::size_t unmatched_mesh_vertices = 0; ///< M vertices with no tet vertex at that position
    double min_dihedral_deg = 0, max_dihedral_deg = 0;
    std::array<std::size_t, 18> dihedral_histogram{}; ///< 10-degree bins of all dihedral angles
    bool passed = false;
};

struct QualityReport {
    /// Histogram of the smallest angle of each triangle, 6 bins of 10 degrees [0,10),...,[50,60].
    std::array<std::size_t, 6> min_angle_histogram{};
    double min_angle_deg = 0.0, mean_min_angle_deg = 0.0;
    double max_radius_edge = 0.0, mean_radius_edge = 0.0; ///< circumradius / shortest edge
};

struct VerifyReport {
    double effective_isovalue = 0.0;
    Inside inside = Inside::Above;           ///< the side verified as inside (VerifyOptions::inside)
    double voxel = 0.0;                      ///< smallest voxel edge (world)
    ReferenceTopologyReport reference;
    MeshTopologyReport mesh;
    /// Undetermined when the reference is not determined; it fails verification only with
    /// require_determined_topology.
    TopologyVerdict topology_verdict = TopologyVerdict::Fail;
    bool require_determined_topology = false;
    HausdorffReport hausdorff;
    DelaunayReport delaunay;
    QualityReport quality;
    TetReport tets;                          ///< filled by verify_tets (--tets)
    std::vector<std::string> notes;
    double seconds = 0.0;

    bool mesh_ok() const;
    bool topology_ok() const;
    bool hausdorff_ok() const { return !hausdorff.checked || hausdorff.passed; }
    bool delaunay_ok() const { return !delaunay.checked || delaunay.passed; }
    bool tets_ok() const { return !tets.checked || tets.passed; }
    bool passed() const { return mesh_ok() && topology_ok() && hausdorff_ok() && delaunay_ok() && tets_ok(); }
    std::string to_json() const; ///< enums written as their to_string words
    std::string summary() const; ///< readable multi-line text
};

/// Verifies \p mesh against {F = options.isovalue} of \p grid (see octree/sample_field.h).
/// \throw InvalidInput bad options, empty grid, isovalue outside the range, non-affine transform
VerifyReport verify_surface(const openvdb::FloatGrid& grid, const SurfaceMesh& mesh,
                            const VerifyOptions& options);

/// Checks a tetrahedral mesh against the surface mesh \p mesh: every tet positively oriented
/// (exact predicate), region tags 1/2, the inside region's boundary equal to M's triangles with
/// the same orientation, inside volume equal to the volume M encloses (1e-9 relative), and the
/// dihedral angles. Independent of the mesher: only the two meshes are used.
TetReport verify_tets(const TetMesh& tets, const SurfaceMesh& mesh);

/// The reference topology alone (check 1), e.g. to compare with a data set's expected topology.
ReferenceTopologyReport reference_topology(const openvdb::FloatGrid& grid, double isovalue,
                                           Inside inside, int refine = 4, int max_refine = 32,
                                           double refine_budget = 6.4e7);

} // namespace isodel
