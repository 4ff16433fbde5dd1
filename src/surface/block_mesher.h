#pragma once
// Internal: one block of partitioned meshing (partitioned_meshing.h), kept alive across the
// rounds of point exchange. It takes E, G and the seeds from the cells of its box (core and
// collar), checks the Voronoi elements near its own region and fixes exactly the violations
// whose candidate point lies in that region, hands out the points it inserted and takes in its
// neighbours', and finally reports the restricted facets it owns: those whose smallest vertex
// lies in its own region and whose two Delaunay balls lie in its trusted box, where its points
// are the global ones (docs/partitioned.md proves why those facets are the global ones).
#include "surface/surface_pipeline.h"

#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace isodel::mesher {

struct BlockSpec {
    std::array<int, 3> index{};  ///< position in the block lattice
    openvdb::CoordBBox core;     ///< the cells the block owns (lower corners, inclusive)
    openvdb::CoordBBox box;      ///< the samples it reads: core's samples grown by the collar
    /// Its own region, in index space: own_lo <= q < own_hi per axis. The core's cells,
    /// unbounded on the domain's outer faces (points on the ring belong to the outermost blocks).
    openvdb::Vec3d own_lo, own_hi;
};

/// A triangle of M in world coordinates, oriented with its normal towards the outside.
using WorldTriangle = std::array<std::array<double, 3>, 3>;

struct BlockSurface {
    std::vector<WorldTriangle> triangles; ///< the owned restricted facets, in facet-key order
    std::size_t balls_outside = 0;        ///< owned facets refused: a Delaunay ball leaves the trusted box
};

class BlockMesher {
public:
    /// Steps 1-3 with E and G from the cells of block.box (the options' eps in world units of
    /// \p field, which must outlive the block), then the voxel bound of its own points.
    /// \p trusted_margin: how far inside the box's inner faces the block's points may differ
    /// from the global ones (the protective layer and seeds of cells beyond the box), in voxels.
    BlockMesher(const octree::SampleField& field, const BlockSpec& block, const MeshOptions& options, int trusted_margin,
                Interrupter* interrupter);
    BlockMesher(const BlockMesher&) = delete;
    BlockMesher& operator=(const BlockMesher&) = delete;

    const BlockSpec& spec() const { return spec_; }
    /// Sigma crosses no grid edge of the box: no triangulation, nothing to own.
    bool empty() const { return !parked_ && (!pipeline_ || pipeline_->empty()); }
    /// Is the world point \p w among the samples this block reads (its box)?
    bool reads(const std::array<double, 3>& w) const;
    /// Is the world point \p w in the block's own region?
    bool owns(const std::array<double, 3>& w) const;
    /// Is \p w within kNearVoxels of the own region? The refiner checks only the Voronoi
    /// elements with a vertex there: a violation's candidate lies in the Voronoi cell of one of
    /// its element's vertices, within two voxels of it per axis (Theorem 2, the voxel bound
    /// measured and enforced for every E and N point), or within one of a grid point.
    bool near_own(const std::array<double, 3>& w) const;
    static constexpr int kNearVoxels = 3;

    /// The refinement loop until no violation of the own region is left (refiner.h), or until
    /// its candidates are all vertices already (then stalled() is true until the next call).
    void refine();
    bool stalled() const { return stalled_; }
    /// The points this block inserted since the last call (not those it received), in id order.
    std::vector<SeedPoint> take_new_points();
    /// Inserts the neighbours' points (those it reads; the rest are skipped); returns how many
    /// were new vertices.
    std::size_t receive(const std::vector<SeedPoint>& points);
    /// The restricted facets it owns (see the file comment).
    BlockSurface owned_surface() const;
    /// MeshOptions::release_blocks: frees the triangulation and its records, keeping what the
    /// run still needs of it (the owned facets, the own E and G counts, the points it inserted or
    /// received). A later receive() of new points builds it again from E, G and those points
    /// (the same point set, so the same triangulation, whose refiner then checks every element
    /// again) and goes on from there. The points not handed out yet are kept for
    /// take_new_points().
    void park();
    bool parked() const { return parked_; }
    /// How many times park()'s block was built again.
    std::size_t rebuilds() const { return rebuilds_; }
    /// Its counts: inserted points (all in its own region), E and G in its own region.
    const MeshStats& stats() const { return st_; }
    std::size_t own_edge_points() const;
    std::size_t own_grid_points() const;

private:
    /// Steps 1-3 on the box with seeds_ as seeds, then the voxel bound (the constructor's work).
    void build(Interrupter* interrupter);
    BlockSurface compute_owned_surface() const;
    bool ball_trusted(const Cell_handle& c) const;
    /// Vertices in the own region whose info \p counted accepts.
    template <class Counted>
    std::size_t count_own(Counted counted) const;
    openvdb::Vec3d index_of(const Point& p) const;

    BlockSpec spec_;
    MeshOptions options_;
    MeshStats st_;
    const octree::SampleField* field_ = nullptr; ///< the whole field (null when the box misses it)
    openvdb::CoordBBox box_;                      ///< the samples whose cells give E and G
    std::unique_ptr<SurfacePipeline> pipeline_;
    openvdb::Vec3d trusted_lo_, trusted_hi_;   ///< index space, infinite on the domain's faces
    openvdb::Vec3d ball_axis_scale_;           ///< index-axis extent of a world ball of radius 1
    std::uint32_t next_unsent_ = 0;            ///< ids from here on not handed out yet
    bool stalled_ = false;
    Interrupter* interrupter_ = nullptr;
    /// park(): the points beyond E and G (inserted, received, repairs of G) in the order they
    /// came, the seeds of the next build; the owned facets and own counts while parked.
    std::vector<SeedPoint> seeds_;
    std::vector<SeedPoint> unsent_; ///< while parked: take_new_points()'s answer
    bool parked_ = false;
    bool built_ = false; ///< a later build() is a rebuild: its counts of E, G and seeds are not new
    std::size_t rebuilds_ = 0;
    BlockSurface parked_surface_;
    bool counted_ = false; ///< own_e_ and own_g_ hold the first triangulation's counts
    std::size_t own_e_ = 0, own_g_ = 0;
};

} // namespace isodel::mesher
