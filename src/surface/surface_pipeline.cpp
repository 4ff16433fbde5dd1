// DELSURFMESH steps 1-3 (paper Fig. 3), then the refiner set up over them:
//   samples --edge_crossings--> E,  crossed cells --protective_layer--> G   (seeding/)
//   Del(E u G)                                                              (delaunay/)
#include "surface/surface_pipeline.h"
#include "surface/stage_clock.h"

#include "delaunay/initial_delaunay.h"

namespace isodel::mesher {

SurfacePipeline::SurfacePipeline(const FieldRun& run, const MeshOptions& options, CandidateFilter keep,
                                 CandidateFilter near, MeshStats& st, Interrupter* interrupter)
    : field_(*run.field)
{
    const octree::AdaptiveGrid* adaptive = run.adaptive;
    if (adaptive) leaves_ = std::make_unique<octree::AdaptiveGrid::Reader>(*adaptive);
    const double eps_user = options.eps > 0 ? options.eps : options.eps_voxels * run.field->min_voxel_edge();
    st.eps_world = eps_user;
    // The surface meshed is Sigma' (octree/face_slabs.h): slabs around the grid planes blunt
    // the knife-edge creases, and M within eps - slab_shift of Sigma' keeps Sigma within eps of M.
    field_.set_face_slabs(field_.face_slabs_for_eps_world(eps_user));
    const double slab_shift = field_.face_slab_shift();
    const double eps = eps_user - slab_shift;
    const double snap_radius = options.snap ? 0.5 * eps : 0.0; // snap_edge_points.h: eps / 2

    // Steps 1-2: E and G (initial_points.h).
    auto t0 = StageClock::now();
    if (run.point_box) {
        octree::SampleField clipped(field_, *run.point_box);
        clipped.set_face_slabs(field_.face_slabs());
        ip_ = initial_points(clipped, adaptive, leaves_.get(), options.snap, snap_radius, run.seeds, st, interrupter,
                             run.point_box);
    } else {
        ip_ = initial_points(field_, adaptive, leaves_.get(), options.snap, snap_radius, run.seeds, st, interrupter);
    }
    st.seconds["points"] = seconds_since(t0);
    if (st.e_points == 0) return;

    // Step 3: Del(E u G), spatially sorted insertion.
    t0 = StageClock::now();
    {
        InterruptScope scope(interrupter, "delaunay");
        build_initial_delaunay(dt_, ip_.points, &scope);
        scope.check(100);
    }
    first_inserted_ = std::uint32_t(ip_.points.size());
    ip_.points.clear();
    ip_.points.shrink_to_fit();
    st.seconds["delaunay"] = seconds_since(t0);

    // Steps 4-5 are the refiner's (refiner.h).
    RefinerInput in;
    in.field = &field_;
    in.adaptive = adaptive;
    in.leaves = leaves_.get();
    in.g_mask = &ip_.g_mask;
    in.layer_radius = {{ip_.layer.radius[0], ip_.layer.radius[1], ip_.layer.radius[2]}};
    in.eps = eps;
    // A snapped grid point is within snap_radius of Sigma, and Sigma' within slab_shift of it.
    in.snap_radius = snap_radius + slab_shift;
    in.slab_h_world = field_.face_slabs().h * field_.min_voxel_edge();
    in.keep = std::move(keep);
    in.near = std::move(near);
    refiner_ = std::make_unique<Refiner>(dt_, in, std::move(ip_.crossed_cells), options, st, first_inserted_,
                                         interrupter);
}

} // namespace isodel::mesher
