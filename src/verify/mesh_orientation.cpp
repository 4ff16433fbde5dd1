// Check 2, orientation against Sigma: M's normals must point to the outside region, i.e. against
// the gradient of phi (phi > 0 inside). Decided per component from the area-weighted sum of
// n . grad_world(phi) at triangle centroids: a component is "inward" when the sum is positive.
// A sum (not a per-triangle vote) because near a saddle of F single triangles may legitimately
// disagree with the local gradient while the component as a whole is unambiguous.
#include "verify/checks.h"

namespace isodel::verify {

void check_outward(const TrilinearField& field, const SurfaceMesh& mesh,
                   const std::vector<int>& tri_component, MeshTopologyReport& rep)
{
    std::vector<double> flux(rep.components.size(), 0.0);
    TrilinearField::Evaluator ev(field);
    const openvdb::Mat3d AinvT = field.A().inverse().transpose();
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        const auto& t = mesh.triangles[f];
        Vec3d p[3];
        for (int q = 0; q < 3; ++q) {
            const auto& v = mesh.vertices[std::size_t(t[std::size_t(q)])];
            p[q] = Vec3d(v[0], v[1], v[2]);
        }
        const Vec3d n = (p[1] - p[0]).cross(p[2] - p[0]); // 2 * area * unit normal
        Vec3d g;
        ev.phi(field.to_index((p[0] + p[1] + p[2]) / 3.0), &g);
        flux[std::size_t(tri_component[f])] += n.dot(AinvT * g);
    }
    rep.inward_components = 0;
    for (double s : flux) rep.inward_components += s > 0;
    rep.outward = rep.oriented && rep.inward_components == 0 && !rep.components.empty();
}

} // namespace isodel::verify
