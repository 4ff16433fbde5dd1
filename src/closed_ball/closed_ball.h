#pragma once
// Internal: the closed ball property checks of DELSURFMESH step 4 (paper Section 4.1, in the
// paper's order) and the eps criterion of step 5. Each returns the points to insert; the driver
// inserts one class at a time, highest priority first, and checks again.
#include "closed_ball/restricted_facets.h"

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace isodel::mesher {

struct Candidate {
    Point p;
    PointKind kind;
    double spacing; ///< distance to the nearest vertex of the element that asked for it
    FacetKey origin; ///< deterministic order
    /// The id of a vertex near p, where the insertion's walk to p starts (kNoVertex: from the
    /// last inserted point). Only a start: the triangulation is the same from any.
    std::uint32_t near = kNoVertex;
    static constexpr std::uint32_t kNoVertex = 0xffffffffu;
};

enum class Violation {
    None,
    GridCell,     ///< Theorem 3 fails: Sigma enters the Voronoi cell of a grid point
    VoronoiEdge,  ///< CBP_VE: a Voronoi edge meets Sigma more than once
    GridVertex,   ///< a restricted facet has a grid vertex: its surface point is inserted so
                  ///< that M's vertices lie on Sigma
    VoronoiFacet, ///< CBP_VF: a Delaunay edge has other than 0 or 2 restricted facets
    FacetLoop,    ///< CBP_VF: Sigma meets a Voronoi facet in a closed loop (facet_loops.h)
    VoronoiCell,  ///< CBP_VC: a surface vertex's restricted link is not one cycle (Theorem 5)
    VoronoiCellDisk, ///< CBP_VC: Vor(p) n Sigma not certified a disk (voronoi_cell_disks.h)
    Epsilon,      ///< |surface point - circumcentre| > eps (Section 4.1, mesh refinement)
    Hausdorff,    ///< a one-sided distance between a facet and Sigma exceeds eps (measured)
    FacetAngle,   ///< optional: a restricted facet's smallest angle is below the bound
    Unbounded,    ///< a Voronoi edge of a surface facet left its cell bound
};

const char* to_string(Violation v);

struct ViolationReport {
    Violation kind = Violation::None;
    std::vector<Candidate> candidates;
};

/// Which candidate points a run may insert: all when empty. A block of partitioned meshing
/// (partitioned_meshing.h) refines only near its core; violations elsewhere are not its own.
using CandidateFilter = std::function<bool(const Point&)>;

/// Removes the candidates \p keep rejects.
void filter_candidates(std::vector<Candidate>& candidates, const CandidateFilter& keep);

/// Looks for violations in priority order and returns those of the first class present
/// (a class whose candidates \p keep all rejects counts as absent).
///
/// CBP_VF and CBP_VC are properties of a vertex's restricted star alone, so the finder keeps
/// each vertex's verdict between calls and re-examines only the vertices whose star changed
/// since (FacetCache::take_touched_vertices): a round costs O(changes) there instead of
/// O(|restricted facets|). The answer is the one a scan of every vertex would give.
class ViolationFinder {
public:
    /// With the self-checks on (self_checks.h) when it is made, every find() also examines
    /// every vertex from scratch, and classifies every active facet, and throws
    /// std::logic_error if a kept verdict or the cache's flagged facets differ (tests).
    ViolationFinder();

    /// The eps criterion reads FacetCache::flagged().far: the cache's far_distance is eps.
    ViolationReport find(FacetCache& cache, const CandidateFilter& keep = {});

private:
    void check_flagged(const FacetCache& cache) const;
    void examine(const FacetCache& cache, std::uint32_t p);
    void check_kept_verdicts(const FacetCache& cache);
    bool self_check_ = false;
    // Per vertex id p: the candidate of every Delaunay edge (p, w > p) with other than 0 or 2
    // restricted facets (CBP_VF), and of a restricted link that is not one cycle (CBP_VC).
    std::vector<std::vector<Candidate>> edge_bad_;
    std::vector<std::vector<Candidate>> link_bad_;
    std::set<std::uint32_t> edge_bad_ids_, link_bad_ids_;
    std::vector<std::pair<std::uint32_t, int>> spokes_;
    std::vector<int> parent_;
};

/// Triangle quality (MeshOptions::facet_angle_deg): the surface point of every restricted facet
/// whose smallest angle is under \p min_angle_deg (Delaunay refinement of the restricted
/// surface, as Boissonnat and Oudot's facet angle criterion).
std::vector<Candidate> facet_angle_violations(const std::vector<const FacetCache::Entry*>& restricted,
                                              double min_angle_deg, const CandidateFilter& keep = {});

/// CBP_VE among \p entries only (e.g. FacetCache::recent()): the farthest crossing of every
/// Voronoi edge crossing Sigma more than once. Empty when an entry overflowed (a hole in G is
/// the driver's to repair first).
std::vector<Candidate> voronoi_edge_violations(const std::vector<FacetCache::Entry>& entries,
                                               const CandidateFilter& keep = {});

} // namespace isodel::mesher
