// VerifyReport::to_json() and summary(): the machine-readable and the human-readable report.
#include <isodel/verify.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace isodel {
namespace {

std::string num(double x)
{
    if (!std::isfinite(x)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}

std::string str(const std::string& s)
{
    std::string o = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        o += c;
    }
    return o + "\"";
}

std::string comps(const std::vector<VerifyComponent>& cs)
{
    std::string o = "[";
    for (std::size_t i = 0; i < cs.size(); ++i)
        o += (i ? ", " : "") + std::string("{\"euler\": ") + std::to_string(cs[i].euler) +
             ", \"genus\": " + std::to_string(cs[i].genus) + ", \"triangles\": " + std::to_string(cs[i].triangles) + "}";
    return o + "]";
}

std::string ints(const std::vector<int>& v)
{
    std::string o = "[";
    for (std::size_t i = 0; i < v.size(); ++i) o += (i ? ", " : "") + std::to_string(v[i]);
    return o + "]";
}

std::string dist(const DistanceStats& d)
{
    return "{\"samples\": " + std::to_string(d.samples) + ", \"max\": " + num(d.max) + ", \"rms\": " + num(d.rms) +
           ", \"max_voxels\": " + num(d.max_voxels) + ", \"rms_voxels\": " + num(d.rms_voxels) +
           ", \"argmax\": [" + num(d.argmax[0]) + ", " + num(d.argmax[1]) + ", " + num(d.argmax[2]) +
           "], \"sample_spacing\": " + num(d.sample_spacing) + "}";
}

const char* yn(bool b) { return b ? "true" : "false"; }

std::string genus_list(const std::vector<VerifyComponent>& cs)
{
    std::vector<int> g;
    for (const auto& c : cs) g.push_back(c.genus);
    return ints(g);
}

} // namespace

std::string VerifyReport::to_json() const
{
    std::ostringstream o;
    o << "{\n  \"passed\": " << yn(passed()) << ",\n  \"effective_isovalue\": " << num(effective_isovalue)
      << ",\n  \"inside\": " << str(inside) << ",\n  \"voxel\": " << num(voxel);
    o << ",\n  \"reference\": {\"determined\": " << yn(reference.determined)
      << ", \"crossed_cells\": " << reference.crossed_cells << ", \"critical_planes\": " << reference.critical_planes << ", \"refinements\": " << ints(reference.refinements)
      << ", \"genera\": [";
    for (std::size_t i = 0; i < reference.genera.size(); ++i) o << (i ? ", " : "") << ints(reference.genera[i]);
    o << "], \"components\": " << comps(reference.components) << ", \"seconds\": " << num(reference.seconds) << "}";
    const auto& m = mesh;
    o << ",\n  \"mesh\": {\"ok\": " << yn(mesh_ok()) << ", \"vertices\": " << m.vertices << ", \"triangles\": " << m.triangles
      << ", \"unreferenced_vertices\": " << m.unreferenced_vertices << ", \"degenerate_triangles\": " << m.degenerate_triangles
      << ", \"duplicate_triangles\": " << m.duplicate_triangles << ", \"boundary_edges\": " << m.boundary_edges
      << ", \"nonmanifold_edges\": " << m.nonmanifold_edges << ", \"nonmanifold_vertices\": " << m.nonmanifold_vertices
      << ", \"misoriented_edges\": " << m.misoriented_edges << ", \"inward_components\": " << m.inward_components
      << ", \"closed\": " << yn(m.closed) << ", \"manifold\": " << yn(m.manifold) << ", \"oriented\": " << yn(m.oriented)
      << ", \"outward\": " << yn(m.outward) << ", \"self_intersection_checked\": " << yn(m.self_intersection_checked)
      << ", \"self_intersecting_pairs\": " << m.self_intersecting_pairs << ", \"components\": " << comps(m.components) << "}";
    o << ",\n  \"topology\": {\"verdict\": " << str(topology_verdict) << ", \"ok\": " << yn(topology_ok())
      << ", \"mesh_genera\": " << genus_list(mesh.components) << ", \"reference_genera\": " << genus_list(reference.components) << "}";
    const auto& h = hausdorff;
    o << ",\n  \"hausdorff\": {\"checked\": " << yn(h.checked) << ", \"passed\": " << yn(h.passed) << ", \"eps\": " << num(h.eps)
      << ", \"eps_voxels\": " << num(h.eps_voxels) << ", \"mesh_to_surface\": " << dist(h.mesh_to_surface)
      << ", \"surface_to_mesh\": " << dist(h.surface_to_mesh) << ", \"sigma_refine\": " << h.sigma_refine
      << ", \"fallback_queries\": " << h.fallback_queries << ", \"unresolved\": " << h.unresolved
      << ", \"seconds\": " << num(h.seconds) << "}";
    const auto& d = delaunay;
    o << ",\n  \"delaunay\": {\"checked\": " << yn(d.checked) << ", \"passed\": " << yn(d.passed) << ", \"triangles\": " << d.triangles
      << ", \"dt_facets\": " << d.dt_facets << ", \"empty_ball_exact\": " << d.empty_ball_exact
      << ", \"non_delaunay\": " << d.non_delaunay << ", \"degenerate\": " << d.degenerate << ", \"examples\": [";
    for (std::size_t i = 0; i < d.examples.size(); ++i)
        o << (i ? ", " : "") << "[" << d.examples[i][0] << ", " << d.examples[i][1] << ", " << d.examples[i][2] << "]";
    o << "], \"seconds\": " << num(d.seconds) << "}";
    const auto& q = quality;
    o << ",\n  \"quality\": {\"min_angle_histogram_10deg\": [";
    for (std::size_t i = 0; i < q.min_angle_histogram.size(); ++i) o << (i ? ", " : "") << q.min_angle_histogram[i];
    o << "], \"min_angle_deg\": " << num(q.min_angle_deg) << ", \"mean_min_angle_deg\": " << num(q.mean_min_angle_deg)
      << ", \"max_radius_edge\": " << num(q.max_radius_edge) << ", \"mean_radius_edge\": " << num(q.mean_radius_edge) << "}";
    const auto& t = tets;
    o << ",\n  \"tets\": {\"checked\": " << yn(t.checked);
    if (t.checked) {
        o << ", \"passed\": " << yn(t.passed) << ", \"vertices\": " << t.vertices << ", \"tets\": " << t.tets
          << ", \"inverted\": " << t.inverted << ", \"degenerate\": " << t.degenerate
          << ", \"unknown_region\": " << t.unknown_region << ", \"inside_tets\": " << t.inside_tets
          << ", \"outside_tets\": " << t.outside_tets << ", \"inside_volume\": " << num(t.inside_volume)
          << ", \"outside_volume\": " << num(t.outside_volume) << ", \"enclosed_volume\": " << num(t.enclosed_volume)
          << ", \"volume_rel_error\": " << num(t.volume_rel_error) << ", \"boundary_faces\": " << t.boundary_faces
          << ", \"boundary_not_in_mesh\": " << t.boundary_not_in_mesh
          << ", \"mesh_not_in_boundary\": " << t.mesh_not_in_boundary
          << ", \"unmatched_mesh_vertices\": " << t.unmatched_mesh_vertices
          << ", \"min_dihedral_deg\": " << num(t.min_dihedral_deg) << ", \"max_dihedral_deg\": " << num(t.max_dihedral_deg)
          << ", \"dihedral_histogram_10deg\": [";
        for (std::size_t i = 0; i < t.dihedral_histogram.size(); ++i) o << (i ? ", " : "") << t.dihedral_histogram[i];
        o << "]";
    }
    o << "}";
    o << ",\n  \"notes\": [";
    for (std::size_t i = 0; i < notes.size(); ++i) o << (i ? ", " : "") << str(notes[i]);
    o << "],\n  \"seconds\": " << num(seconds) << "\n}\n";
    return o.str();
}

std::string VerifyReport::summary() const
{
    std::ostringstream o;
    auto verdict = [](bool ok) { return ok ? "PASS" : "FAIL"; };
    o << "reference topology: " << (reference.determined ? "" : "UNDETERMINED ") << reference.components.size()
      << " component(s), genus " << genus_list(reference.components) << " (" << reference.crossed_cells
      << " crossed cells, " << reference.critical_planes << " critical planes, refinements " << ints(reference.refinements) << ", "
      << num(reference.seconds) << " s)\n";
    o << "mesh: " << mesh.vertices << " vertices, " << mesh.triangles << " triangles, " << mesh.components.size()
      << " component(s), genus " << genus_list(mesh.components) << "\n";
    o << "  closed " << yn(mesh.closed) << ", manifold " << yn(mesh.manifold) << ", oriented " << yn(mesh.oriented)
      << ", outward " << yn(mesh.outward) << ", self-intersecting pairs "
      << (mesh.self_intersection_checked ? std::to_string(mesh.self_intersecting_pairs) : std::string("not checked")) << "\n";
    if (mesh.boundary_edges + mesh.nonmanifold_edges + mesh.nonmanifold_vertices + mesh.misoriented_edges +
        mesh.degenerate_triangles + mesh.duplicate_triangles)
        o << "  boundary edges " << mesh.boundary_edges << ", non-manifold edges " << mesh.nonmanifold_edges
          << ", non-manifold vertices " << mesh.nonmanifold_vertices << ", misoriented edges " << mesh.misoriented_edges
          << ", degenerate " << mesh.degenerate_triangles << ", duplicates " << mesh.duplicate_triangles << "\n";
    o << "[" << verdict(mesh_ok()) << "] mesh is a closed oriented 2-manifold without self-intersections\n";
    o << "[" << (topology_verdict == "undetermined" ? "UNDETERMINED" : verdict(topology_ok())) << "] homeomorphic to Sigma\n";
    if (hausdorff.checked) {
        const auto& h = hausdorff;
        o << "[" << verdict(h.passed) << "] Hausdorff <= eps = " << num(h.eps) << " (" << num(h.eps_voxels) << " voxel): M->Sigma max "
          << num(h.mesh_to_surface.max) << " (" << num(h.mesh_to_surface.max_voxels) << " vx) rms " << num(h.mesh_to_surface.rms)
          << "; Sigma->M max " << num(h.surface_to_mesh.max) << " (" << num(h.surface_to_mesh.max_voxels) << " vx) rms "
          << num(h.surface_to_mesh.rms) << "\n";
    } else {
        o << "[SKIP] Hausdorff (no eps)\n";
    }
    if (delaunay.checked)
        o << "[" << verdict(delaunay.passed) << "] Delaunay conforming: " << delaunay.dt_facets << " DT facets, "
          << delaunay.empty_ball_exact << " cospherical (empty ball, exact), " << delaunay.non_delaunay << " non-Delaunay, "
          << delaunay.degenerate << " degenerate\n";
    o << "quality: min angle " << num(quality.min_angle_deg) << " deg (mean " << num(quality.mean_min_angle_deg)
      << "), radius-edge max " << num(quality.max_radius_edge) << " (mean " << num(quality.mean_radius_edge) << ")\n";
    for (const auto& n : notes) o << "note: " << n << "\n";
    if (tets.checked) {
        const auto& t = tets;
        o << "[" << verdict(t.passed) << "] tetrahedra: " << t.tets << " (" << t.inside_tets << " inside, "
          << t.outside_tets << " outside), " << t.inverted << " inverted, " << t.degenerate << " flat, "
          << t.unknown_region << " untagged; inside boundary " << t.boundary_faces << " faces, "
          << t.boundary_not_in_mesh << " not in M, " << t.mesh_not_in_boundary << " of M missing; inside volume "
          << num(t.inside_volume) << " vs enclosed by M " << num(t.enclosed_volume) << " (rel. "
          << num(t.volume_rel_error) << "); dihedral " << num(t.min_dihedral_deg) << " - " << num(t.max_dihedral_deg)
          << " deg\n";
    }
    o << (passed() ? "VERIFIED" : "NOT VERIFIED") << " (" << num(seconds) << " s)\n";
    return o.str();
}

} // namespace isodel
