#pragma once
// Internal: DELSURFMESH step 5 made good on its promise. The paper refines until the surface
// point p of every restricted facet lies within eps of the circumcentre c of its triangle. On
// smooth level sets that keeps the Hausdorff distance below eps, but the trilinear Sigma is only
// C0 across cell faces and has features thinner than a voxel; there |p - c| <= eps let M stray up
// to 1.8 eps (measured on the skull and random volumes). So after the paper's criterion holds,
// both one-sided distances are measured locally and any facet that exceeds them is refined by
// inserting its surface point p (a point of Sigma: ordinary Delaunay refinement, after which the
// closed ball checks run again):
//  - M -> Sigma: |s - projection| bounds d(s, Sigma) from above for a sample s Newton-projected
//    onto Sigma. The triangle is split in four until each piece's corner bounds plus its
//    covering radius stay under 0.7 eps + (eps/4)/sqrt(3), or its edges are eps/4 long and each
//    corner must be within 0.7 eps (the bound of a barycentric sample grid of spacing eps/4,
//    with a dozen projections per triangle instead of ~200).
//  - Sigma -> M: p itself, the point of Sigma on the Voronoi edge, must lie within eps of its
//    triangle or of a triangle sharing one of its edges.
//  - Sigma -> M along the creases: where Sigma crosses a cell face it is only C0, and a ridge
//    there can stand out of M between its vertices. Once every facet passes the two checks above,
//    the crease curves (Sigma on the faces of the crossed cells, where F is bilinear) are sampled
//    every eps/2 along lines of the face (F is linear on them: exact roots) and each sample
//    farther than the threshold from M is inserted (hausdorff_creases.cpp: the triangles near
//    the sample's cell settle most samples, an AABB tree measures the far ones). The mesher
//    meshes Sigma' (octree/face_slabs.h), whose creases are these curves mapped to the slab
//    boundaries h inside each cell; the wall between two copies is 2h long.
// The threshold is 0.7 eps, leaving the sampling spacing's share of the margin. A facet's
// verdict depends only on its vertices, so each facet is checked once; a cell's crease samples
// are checked again only when a triangle that passed one of them (its witness) has left M.
#include "closed_ball/closed_ball.h"
#include "refinement/crease_cells.h"
#include "octree/sample_field.h"

#include <vector>

namespace isodel::mesher {

class HausdorffRefinement {
public:
    /// \p crossed_cells: lower corners of the cells Sigma passes through.
    /// \p snap_radius: how far snapped vertices may be from Sigma (0 without --snap).
    HausdorffRefinement(const octree::SampleField& field, double eps, std::vector<openvdb::Coord> crossed_cells,
                        double snap_radius = 0.0);

    /// Candidates (surface points of the offending facets) among the restricted facets not
    /// checked before. \p restricted: the facets with one crossing, sorted by key without
    /// repeats (FacetCache::active()'s order).
    std::vector<Candidate> violations(const std::vector<const FacetCache::Entry*>& restricted);

    /// Crease samples farther than the threshold from the triangles of \p restricted. With the
    /// self-checks on (self_checks.h), each call also computes afresh what it kept from the
    /// last call (M's triangles) and what its block filter skipped (the triangles near the
    /// cells to check), and throws std::logic_error if they differ.
    std::vector<Candidate> crease_violations(const std::vector<const FacetCache::Entry*>& restricted);

    /// How many calls (all instances, for tests) had their block filter checked that way.
    static std::size_t crease_block_filter_checks();

    /// Only candidates \p keep accepts are returned; a facet or crease cell whose candidate it
    /// rejects is not this run's to refine and is not checked again (partitioned meshing).
    void set_filter(CandidateFilter keep) { keep_ = std::move(keep); }

private:
    /// The crease check's stages (hausdorff_creases.cpp).
    std::vector<FacetKey> update_crease_triangles(const std::vector<const FacetCache::Entry*>& restricted,
                                                  bool self_check);
    std::vector<std::size_t> crease_cells_to_check(const std::vector<FacetKey>& left);
    CreaseTriangle crease_triangle(const FacetCache::Entry& e) const;
    /// A world distance r spans at most r * index_units_per_world() index units along any axis.
    double index_units_per_world() const;
    /// violations()'s stages (hausdorff_refinement.cpp): the facets not checked before, the
    /// restricted triangles around their edges, each facet's verdict, and the points to insert.
    struct EdgeTriangle;
    struct Verdicts;
    std::vector<const FacetCache::Entry*> facets_to_check(const std::vector<const FacetCache::Entry*>& restricted) const;
    static std::vector<EdgeTriangle> triangles_around_edges(const std::vector<const FacetCache::Entry*>& restricted,
                                                           const std::vector<const FacetCache::Entry*>& todo);
    Verdicts check_facets(const std::vector<const FacetCache::Entry*>& todo, const std::vector<EdgeTriangle>& around) const;
    std::vector<Candidate> refinement_points(const std::vector<const FacetCache::Entry*>& todo, Verdicts& verdicts,
                                             std::vector<FacetKey>& passing) const;

    const octree::SampleField& field_;
    double eps_;
    double snap_radius_;
    openvdb::math::Mat3d index_to_world_, world_to_index_;
    // Keys of the facets that passed, sorted. `restricted` comes sorted by key too, so finding the
    // facets still to check is one merge walk instead of a hash lookup per restricted facet in
    // every round (most rounds check a handful of a few hundred thousand).
    std::vector<FacetKey> passed_;
    std::vector<openvdb::Coord> crossed_cells_;
    // Per crossed cell, what the last crease check found: no crease sample at all (F does not
    // change, so never again), or passed, with a triangle within the threshold of each of its
    // samples (its witnesses).
    enum class CreaseState : char { Unknown, NoCrease, Passed };
    std::vector<CreaseState> crease_state_;
    std::vector<std::vector<FacetKey>> crease_witness_;
    std::vector<FacetKey> crease_m_; // M's facets at the last crease check, sorted
    // Their triangles, in that order (crease_cells.h: a pure function of the key).
    std::vector<CreaseTriangle> crease_tris_;
    CandidateFilter keep_;
};

} // namespace isodel::mesher
