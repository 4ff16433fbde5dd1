#include <isodel/mesh.h>

#include <sstream>

namespace isodel {

std::string to_json(const MeshStats& s)
{
    std::ostringstream o;
    o.precision(17);
    o << "{\n  \"counts\": {\"E\": " << s.e_points << ", \"G\": " << s.g_points
      << ", \"N_topology\": " << s.n_topology << ", \"N_geometry\": " << s.n_geometry
      << ", \"snapped\": " << s.snapped << ", \"N_facet_angle\": " << s.n_facet_angle
      << ", \"facet_angle_stop\": \"" << s.facet_angle_stop << "\", \"vertices\": " << s.vertices
      << ", \"triangles\": " << s.triangles << ", \"rounds\": " << s.rounds << "},\n";
    o << "  \"effective_isovalue\": " << s.effective_isovalue << ",\n  \"eps_world\": " << s.eps_world
      << ",\n  \"seconds\": {";
    bool first = true;
    for (const auto& [k, v] : s.seconds) {
        o << (first ? "" : ", ") << '"' << k << "\": " << v;
        first = false;
    }
    o << "},\n  \"refinement_seconds\": {";
    first = true;
    for (const auto& [k, v] : s.refinement_seconds) {
        o << (first ? "" : ", ") << '"' << k << "\": " << v;
        first = false;
    }
    o << "},\n  \"peak_memory_bytes\": " << s.peak_memory_bytes << ",\n";
    o << "  \"voxel_bound\": {\"max_cells_E\": " << s.max_cells_e << ", \"bound_E\": " << s.bound_e
      << ", \"max_cells_N\": " << s.max_cells_n << ", \"bound_N\": " << s.bound_n
      << ", \"repairs\": " << s.bound_repairs << "},\n";
    o << "  \"topology\": {\"components\": " << s.components.size() << ", \"per_component\": [";
    for (std::size_t i = 0; i < s.components.size(); ++i) {
        const auto& c = s.components[i];
        o << (i ? ", " : "") << "{\"euler\": " << c.euler << ", \"genus\": " << c.genus
          << ", \"triangles\": " << c.triangles << "}";
    }
    o << "]}";
    if (s.partition.blocks > 0) {
        const PartitionStats& p = s.partition;
        o << ",\n  \"partition\": {\"blocks\": " << p.blocks << ", \"collar_voxels\": " << p.collar_voxels
          << ", \"blocks_failed\": " << p.blocks_failed << ", \"block_points\": " << p.block_points
          << ", \"seam_points\": " << p.seam_points << "}";
    }
    if (s.certify_attempts > 0) o << ",\n  \"certify_attempts\": " << s.certify_attempts;
    const TetStats& t = s.tets;
    if (t.vertices > 0) {
        o << ",\n  \"tets\": {\"vertices\": " << t.vertices << ", \"tets_inside\": " << t.tets_inside
          << ", \"tets_outside\": " << t.tets_outside << ", \"G_prime\": " << t.g_prime << ", \"grid_points_removed\": " << t.grid_points_removed
          << ",\n    \"volume_inside\": " << t.volume_inside << ", \"volume_outside\": " << t.volume_outside
          << ", \"volume_enclosed_by_surface\": " << t.volume_enclosed_by_surface
          << ",\n    \"min_dihedral_deg\": " << t.min_dihedral_deg << ", \"max_dihedral_deg\": " << t.max_dihedral_deg
          << ", \"max_radius_edge\": " << t.max_radius_edge << ", \"tets_below_10deg\": " << t.tets_below_10deg
          << ",\n    \"tets_touching_surface\": " << t.tets_touching_surface
          << ", \"min_dihedral_deg_off_surface\": " << t.min_dihedral_deg_off_surface
          << ", \"max_radius_edge_off_surface\": " << t.max_radius_edge_off_surface
          << ",\n    \"min_dihedral_deg_delaunay\": " << t.min_dihedral_deg_delaunay
          << ", \"vertices_moved\": " << t.vertices_moved << ", \"vertices_removed\": " << t.vertices_removed << ", \"vertices_inserted\": " << t.vertices_inserted << ", \"flips\": " << t.flips
          << ", \"improvement_seconds\": " << t.improvement_seconds << ",\n    \"seconds\": {";
        for (auto it = t.seconds.begin(); it != t.seconds.end(); ++it)
            o << (it == t.seconds.begin() ? "" : ", ") << "\"" << it->first << "\": " << it->second;
        o << "},\n    \"dihedral_histogram_10deg\": [";
        for (std::size_t i = 0; i < t.dihedral_histogram.size(); ++i) o << (i ? ", " : "") << t.dihedral_histogram[i];
        o << "]}";
    }
    o << "\n}\n";
    return o.str();
}

} // namespace isodel
