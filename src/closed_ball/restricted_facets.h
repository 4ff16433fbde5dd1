#pragma once
// Internal: the restricted Delaunay facets Del P|Sigma (paper Section 3): a facet is restricted
// when its dual Voronoi edge meets Sigma. For each facet with a surface vertex we compute the
// crossings of its Voronoi edge with Sigma by walking the few cells the edge passes through
// (octree/segment_walk.h): the edge lies in the Voronoi cell of its E/N vertex, which the
// protective layer traps in O(1) cells (Theorem 2). Facets among grid points only are skipped:
// their Voronoi edges miss Sigma (Theorem 3).
#include "delaunay/delaunay.h"
#include "closed_ball/facet_table.h"
#include "octree/sample_field.h"
#include "octree/segment_walk.h"

#include <cmath>
#include <stdexcept>
#include <functional>
#include <vector>

namespace isodel::mesher {

struct FacetRecord {
    std::uint16_t crossings = 0;  ///< transversal crossings of the Voronoi edge with Sigma
    bool overflow = false;        ///< the Voronoi edge is unbounded or left its cell bound
    Point surface_point;          ///< crossing farthest from the triangle's circumcentre
    double distance = 0;          ///< |surface_point - circumcentre of the triangle|
    Vector outward;               ///< along the Voronoi edge, from its inside end to its outside end
};

/// Crossings of the Voronoi edge dual to \p f with Sigma.
FacetRecord compute_facet_record(const Delaunay& dt, const Facet& f,
                                 const octree::SampleField::Reader& reader, int max_cells);

/// Cache of facet records keyed by vertex ids, maintained incrementally. A facet's Voronoi edge
/// changes exactly when one of its two cells is replaced, and every cell an insertion destroys
/// is in the new point's conflict region: so insert() drops the records of the facets of those
/// cells, and update() computes records only for the facets of the cells around the points
/// inserted since the last update. All points after the initial triangulation must go through
/// insert().
class FacetCache {
public:
    FacetCache() = default;

    /// First call: scans every finite facet with a surface vertex. Later calls: only the facets
    /// around the points inserted since. Records are computed in parallel; each depends only on
    /// the triangulation, and the active list is sorted by key, so the result is deterministic.
    void update(const Delaunay& dt, const octree::SampleField& field, int max_cells);

    /// Whether update() has scanned the triangulation yet (before that the table is empty).
    bool scanned() const { return scanned_; }

    /// Inserts \p p (located from \p hint) and returns its vertex, or a null handle when p is
    /// already a vertex.
    Vertex_handle insert(Delaunay& dt, const Point& p, VertexInfo info, Cell_handle hint = Cell_handle());

    /// A cell of vertex \p id, where locating a point near that vertex may start; a null handle
    /// when \p id is no vertex. The first call indexes every vertex of \p dt by id; insert() and
    /// remove() keep the index after that. (The points of a round are spread over the whole
    /// surface, so a walk from the last inserted point crosses many cells; a walk from the
    /// vertex whose check asked for the point starts next to it.)
    Cell_handle cell_near(const Delaunay& dt, std::uint32_t id);

    /// Removes \p vertices from \p dt, in order, keeping the cache current: the records of the
    /// facets of each vertex's cells go (the facets through it vanish, the others of those
    /// cells border the re-triangulated hole, so their Voronoi edges change), and the next
    /// update() computes the facets around the hole's vertices, where every new cell is. A
    /// removal leaves the other cells, and so their stored handles, as they were.
    void remove(Delaunay& dt, const std::vector<Vertex_handle>& vertices);

    struct Entry {
        Facet facet;
        FacetKey key;
        const FacetRecord* record;
        // Copies of the record's flags, so that scans of every active facet (the Hausdorff and
        // extraction steps, the flagged classes' self-check) read this array sequentially
        // instead of chasing `record` into the hash map.
        std::uint16_t crossings;
        bool overflow;
        bool all_on_surface; ///< every vertex is an E/N point (kinds never change)
    };
    /// Facets whose Voronoi edge meets Sigma or overflowed, sorted by key.
    const std::vector<Entry>& active() const
    {
        merge_pending();
        return active_;
    }
    /// The active facets the closed-ball checks look for (closed_ball.h), by class: keys in
    /// sorted order, kept up to date by update() from the changed and recomputed facets, as the
    /// restricted stars are. A round then finds its violations in O(changes) instead of
    /// scanning every active facet in each of the many rounds. Valid
    /// right after update(): an insert() or remove() since may have erased keys they name.
    struct Flagged {
        std::vector<FacetKey> overflow; ///< Voronoi edge unbounded or out of its cell bound
        std::vector<FacetKey> multiple; ///< Voronoi edge crossing Sigma more than once (CBP_VE)
        std::vector<FacetKey> grid_vertex; ///< restricted, with a grid vertex
        std::vector<FacetKey> far; ///< restricted, surface point farther than far_distance() from the circumcentre
    };
    const Flagged& flagged() const { return flagged_; }
    /// The distance of Flagged::far (the eps criterion): infinite (no facet is far) until set,
    /// which must happen before the first update().
    void set_far_distance(double d)
    {
        if (scanned_) throw std::logic_error("FacetCache::set_far_distance after the first update()");
        far_distance_ = d;
    }
    double far_distance() const { return far_distance_; }
    /// Records only facets with a vertex in \p region (all when empty): a block of partitioned
    /// meshing checks the Voronoi elements near its own region, not those of its collar.
    void set_region(std::function<bool(const Point&)> region) { region_ = std::move(region); }
    /// The active facet \p key (as in active()); throws std::logic_error if it is none.
    Entry entry(const FacetKey& key) const;
    /// The number of active facets.
    std::size_t active_count() const { return map_.size(); }

    /// The active facets the last update() computed (new or changed since the update before),
    /// sorted by key: where the last insertions changed the restricted Voronoi diagram.
    const std::vector<Entry>& recent() const { return recent_; }
    std::size_t computed_last_update() const { return computed_; }

    /// A restricted facet (one crossing) as seen from one of its vertices.
    struct StarFacet {
        FacetKey key;
        Point surface_point;
    };
    /// The restricted facets around the vertex with id \p id, sorted by key: the restricted
    /// link the CBP_VF / CBP_VC checks read (closed_ball.h), kept up to date by update().
    const std::vector<StarFacet>& restricted_star(std::uint32_t id) const
    {
        static const std::vector<StarFacet> none;
        return id < stars_.size() ? stars_[id] : none;
    }
    /// Every vertex id with a restricted star is below this.
    std::size_t vertex_id_bound() const { return stars_.size(); }
    /// Position of the vertex with id \p id (known for every vertex of a restricted facet).
    const Point& vertex_point(std::uint32_t id) const { return points_[id]; }
    /// Ids of the vertices whose restricted star changed since the last call, sorted, unique;
    /// clears the list. The checks of closed_ball.h re-examine only these vertices.
    std::vector<std::uint32_t> take_touched_vertices();

private:
    struct Stored {
        Facet facet;
        FacetRecord record;
    };
    FacetTable<Stored> map_;
    std::vector<Vertex_handle> inserted_;
    struct InsertScratch {
        std::vector<Cell_handle> conflicts;
        std::vector<Facet> boundary, internal;
    } scratch_; ///< insert()'s conflict region
    std::vector<FacetKey> changed_; ///< keys erased by insert() since the last update
    bool scanned_ = false;
    // active() merges the changes of the updates since it was last read (not thread-safe
    // against concurrent updates, like everything here).
    mutable std::vector<Entry> active_;
    mutable std::vector<FacetKey> pending_changed_;
    mutable std::vector<Entry> pending_added_;
    void merge_pending() const;
    std::vector<Entry> recent_;
    std::size_t computed_ = 0;
    Flagged flagged_;
    double far_distance_ = INFINITY;
    std::function<bool(const Point&)> region_;
    void update_flagged(const std::vector<Entry>& added);
    // update()'s stages (restricted_facets.cpp), in order: the facets to compute (every facet
    // on the first call, by runs of cells; later the facets around the inserted points), their
    // records computed and the active ones entered, and the changes handed on to the active
    // list, the restricted stars and the flagged classes. UpdateRun is the state they share.
    struct UpdateRun;
    struct CellRun;
    void scan_every_facet(UpdateRun& run);
    void record_cell_run(UpdateRun& run, CellRun& batch);
    void scan_around_inserted(UpdateRun& run);
    bool in_region(const Facet& f) const;
    void record_todo(UpdateRun& run);
    void apply_changes(std::vector<Entry>& added);
    /// The entry of a stored record (its flags copied, and whether every vertex is on Sigma).
    static Entry entry_of(const Stored& st, const FacetKey& key);
    /// Stores the record of an active facet, marks the facet on both its cells (cell_base.h)
    /// and returns its entry.
    Entry enter(const Facet& f, const FacetKey& key, const FacetRecord& record);
    // Restricted star of every vertex id (sorted by key), the vertices' positions, and the ids
    // whose star changed since take_touched_vertices() was last called.
    std::vector<std::vector<StarFacet>> stars_;
    std::vector<Point> points_;
    std::vector<Vertex_handle> by_id_; ///< cell_near()'s index, once by_id_ready_
    bool by_id_ready_ = false;
    std::vector<std::uint32_t> touched_;
    void unstar(const FacetKey& key);
    void star(const Entry& e);
};

} // namespace isodel::mesher
