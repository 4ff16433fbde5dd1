// verify_surface(): runs the checks of checks.h and combines them into the verdicts.
#include "verify/checks.h"

#include <isodel/errors.h>

#include <algorithm>
#include <chrono>

namespace isodel {

bool VerifyReport::mesh_ok() const
{
    return mesh.closed && mesh.manifold && mesh.oriented && mesh.outward &&
           (!mesh.self_intersection_checked || mesh.self_intersecting_pairs == 0);
}

bool VerifyReport::topology_ok() const
{
    if (topology_verdict == TopologyVerdict::Pass) return true;
    return topology_verdict == TopologyVerdict::Undetermined && !require_determined_topology;
}

VerifyReport verify_surface(const openvdb::FloatGrid& grid, const SurfaceMesh& mesh, const VerifyOptions& options)
{
    const auto t0 = std::chrono::steady_clock::now();
    if (options.refine < 1 || options.refine > 64) throw InvalidInput("verify: --refine must be in [1, 64]");
    if (options.eps < 0 || options.eps_voxels < 0) throw InvalidInput("verify: eps must be >= 0");
    const Inside inside = options.inside ? *options.inside
                                         : default_inside(grid);
    verify::TrilinearField field(grid, options.isovalue, inside);

    VerifyReport rep;
    rep.effective_isovalue = field.samples().effective_isovalue();
    rep.inside = inside;
    rep.voxel = field.voxel();
    rep.require_determined_topology = options.require_determined_topology;
    if (rep.effective_isovalue != options.isovalue)
        rep.notes.push_back("some samples equal the isovalue: meshing v* = v - d (sample_field.h tie rule)");

    // 1. Reference topology.
    rep.reference = verify::reference_topology(field, options.refine, options.max_refine, options.refine_budget);

    // 2. M itself.
    std::vector<int> tri_component;
    rep.mesh = verify::mesh_topology(mesh, tri_component);
    verify::check_outward(field, mesh, tri_component, rep.mesh);
    if (options.check_self_intersections) verify::check_self_intersections(mesh, rep.mesh);
    else rep.notes.push_back("self-intersection test skipped");

    // Homeomorphism: same multiset of genera per component (closed orientable surfaces are
    // classified by genus), only meaningful when M is a closed 2-manifold.
    std::vector<int> gm, gr;
    for (const auto& c : rep.mesh.components) gm.push_back(c.genus);
    for (const auto& c : rep.reference.components) gr.push_back(c.genus);
    std::sort(gm.begin(), gm.end());
    std::sort(gr.begin(), gr.end());
    if (!rep.mesh.manifold) rep.topology_verdict = TopologyVerdict::Fail;
    else if (!rep.reference.determined) rep.topology_verdict = TopologyVerdict::Undetermined;
    else rep.topology_verdict = gm == gr ? TopologyVerdict::Pass : TopologyVerdict::Fail;

    // 3. Hausdorff.
    const double eps = options.eps > 0 ? options.eps : options.eps_voxels * field.voxel();
    if (eps > 0) rep.hausdorff = verify::hausdorff(field, mesh, eps, options.hausdorff_refine);
    else rep.notes.push_back("Hausdorff distance not checked (no eps given)");

    // 4. Delaunay conformity.
    if (options.check_delaunay) rep.delaunay = verify::delaunay_conformity(mesh);
    else rep.notes.push_back("Delaunay conformity not checked");

    // 5. Quality.
    rep.quality = verify::triangle_quality(mesh);
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return rep;
}

} // namespace isodel
