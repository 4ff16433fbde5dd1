// VerifyReport::to_json() and summary(): the machine-readable and the human-readable report.
#include <isodel/verify.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace isodel {
namespace {

using Json = nlohmann::ordered_json;

// Text of the summary: 9 significant digits.
std::string num(double x)
{
    if (!std::isfinite(x)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}

std::string ints(const std::vector<int>& v)
{
    std::string o = "[";
    for (std::size_t i = 0; i < v.size(); ++i) o += (i ? ", " : "") + std::to_string(v[i]);
    return o + "]";
}

const char* yn(bool b) { return b ? "true" : "false"; }

std::vector<int> genera(const std::vector<ComponentTopology>& cs)
{
    std::vector<int> g;
    for (const auto& c : cs) g.push_back(c.genus);
    return g;
}

std::string genus_list(const std::vector<ComponentTopology>& cs) { return ints(genera(cs)); }

// JSON: non-finite doubles are written as null (nlohmann's dump does that).
Json comps(const std::vector<ComponentTopology>& cs)
{
    Json o = Json::array();
    for (const auto& c : cs) o.push_back({{"euler", c.euler}, {"genus", c.genus}, {"triangles", c.triangles}});
    return o;
}

Json dist(const DistanceStats& d)
{
    return {{"samples", d.samples},       {"max", d.max},
            {"rms", d.rms},               {"max_voxels", d.max_voxels},
            {"rms_voxels", d.rms_voxels}, {"argmax", d.argmax},
            {"sample_spacing", d.sample_spacing}};
}

} // namespace

std::string VerifyReport::to_json() const
{
    Json o;
    o["passed"] = passed();
    o["effective_isovalue"] = effective_isovalue;
    o["inside"] = to_string(inside);
    o["voxel"] = voxel;
    o["reference"] = {{"determined", reference.determined},
                      {"crossed_cells", reference.crossed_cells},
                      {"critical_planes", reference.critical_planes},
                      {"refinements", reference.refinements},
                      {"genera", reference.genera},
                      {"components", comps(reference.components)},
                      {"seconds", reference.seconds}};
    const auto& m = mesh;
    o["mesh"] = {{"ok", mesh_ok()},
                 {"vertices", m.vertices},
                 {"triangles", m.triangles},
                 {"unreferenced_vertices", m.unreferenced_vertices},
                 {"degenerate_triangles", m.degenerate_triangles},
                 {"duplicate_triangles", m.duplicate_triangles},
                 {"boundary_edges", m.boundary_edges},
                 {"nonmanifold_edges", m.nonmanifold_edges},
                 {"nonmanifold_vertices", m.nonmanifold_vertices},
                 {"misoriented_edges", m.misoriented_edges},
                 {"inward_components", m.inward_components},
                 {"closed", m.closed},
                 {"manifold", m.manifold},
                 {"oriented", m.oriented},
                 {"outward", m.outward},
                 {"self_intersection_checked", m.self_intersection_checked},
                 {"self_intersecting_pairs", m.self_intersecting_pairs},
                 {"components", comps(m.components)}};
    o["topology"] = {{"verdict", to_string(topology_verdict)},
                     {"ok", topology_ok()},
                     {"mesh_genera", genera(mesh.components)},
                     {"reference_genera", genera(reference.components)}};
    const auto& h = hausdorff;
    o["hausdorff"] = {{"checked", h.checked},
                      {"passed", h.passed},
                      {"eps", h.eps},
                      {"eps_voxels", h.eps_voxels},
                      {"mesh_to_surface", dist(h.mesh_to_surface)},
                      {"surface_to_mesh", dist(h.surface_to_mesh)},
                      {"sigma_refine", h.sigma_refine},
                      {"fallback_queries", h.fallback_queries},
                      {"unresolved", h.unresolved},
                      {"seconds", h.seconds}};
    const auto& d = delaunay;
    o["delaunay"] = {{"checked", d.checked},
                     {"passed", d.passed},
                     {"triangles", d.triangles},
                     {"dt_facets", d.dt_facets},
                     {"empty_ball_exact", d.empty_ball_exact},
                     {"non_delaunay", d.non_delaunay},
                     {"degenerate", d.degenerate},
                     {"examples", d.examples},
                     {"seconds", d.seconds}};
    const auto& q = quality;
    o["quality"] = {{"min_angle_histogram_10deg", q.min_angle_histogram},
                    {"min_angle_deg", q.min_angle_deg},
                    {"mean_min_angle_deg", q.mean_min_angle_deg},
                    {"max_radius_edge", q.max_radius_edge},
                    {"mean_radius_edge", q.mean_radius_edge}};
    const auto& t = tets;
    Json& jt = o["tets"];
    jt["checked"] = t.checked;
    if (t.checked) {
        jt["passed"] = t.passed;
        jt["vertices"] = t.vertices;
        jt["tets"] = t.tets;
        jt["inverted"] = t.inverted;
        jt["degenerate"] = t.degenerate;
        jt["unknown_region"] = t.unknown_region;
        jt["inside_tets"] = t.inside_tets;
        jt["outside_tets"] = t.outside_tets;
        jt["inside_volume"] = t.inside_volume;
        jt["outside_volume"] = t.outside_volume;
        jt["enclosed_volume"] = t.enclosed_volume;
        jt["volume_rel_error"] = t.volume_rel_error;
        jt["boundary_faces"] = t.boundary_faces;
        jt["boundary_not_in_mesh"] = t.boundary_not_in_mesh;
        jt["mesh_not_in_boundary"] = t.mesh_not_in_boundary;
        jt["unmatched_mesh_vertices"] = t.unmatched_mesh_vertices;
        jt["min_dihedral_deg"] = t.min_dihedral_deg;
        jt["max_dihedral_deg"] = t.max_dihedral_deg;
        jt["dihedral_histogram_10deg"] = t.dihedral_histogram;
    }
    o["notes"] = notes;
    o["seconds"] = seconds;
    return o.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
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
    o << "[" << (topology_verdict == TopologyVerdict::Undetermined ? "UNDETERMINED" : verdict(topology_ok())) << "] homeomorphic to Sigma\n";
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
