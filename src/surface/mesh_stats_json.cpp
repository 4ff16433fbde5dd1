// to_json(MeshStats): the CLI's --stats file. Keys keep the order below (ordered_json); integers
// stay integers, doubles are written so they read back to the same value.
#include <isodel/mesh.h>

#include <nlohmann/json.hpp>

namespace isodel {

std::string to_json(const MeshStats& s)
{
    using Json = nlohmann::ordered_json;
    Json o;
    o["counts"] = {{"E", s.e_points},
                   {"G", s.g_points},
                   {"N_topology", s.n_topology},
                   {"N_geometry", s.n_geometry},
                   {"snapped", s.snapped},
                   {"N_facet_angle", s.n_facet_angle},
                   {"facet_angle_stop", to_string(s.facet_angle_stop)},
                   {"N_tet_sliver", s.n_tet_sliver},
                   {"tet_sliver_runs", s.tet_sliver_runs},
                   {"tet_sliver_stop", to_string(s.tet_sliver_stop)},
                   {"vertices", s.vertices},
                   {"triangles", s.triangles},
                   {"rounds", s.rounds}};
    o["effective_isovalue"] = s.effective_isovalue;
    o["eps_world"] = s.eps_world;
    o["seconds"] = Json::object();
    for (const auto& [k, v] : s.seconds) o["seconds"][k] = v;
    o["refinement_seconds"] = Json::object();
    for (const auto& [k, v] : s.refinement_seconds) o["refinement_seconds"][k] = v;
    o["peak_memory_bytes"] = s.peak_memory_bytes;
    o["voxel_bound"] = {{"max_cells_E", s.max_cells_e},
                        {"bound_E", s.bound_e},
                        {"max_cells_N", s.max_cells_n},
                        {"bound_N", s.bound_n},
                        {"repairs", s.bound_repairs}};
    Json comps = Json::array();
    for (const ComponentTopology& c : s.components)
        comps.push_back({{"euler", c.euler}, {"genus", c.genus}, {"triangles", c.triangles}});
    o["topology"] = {{"components", s.components.size()}, {"per_component", std::move(comps)}};
    if (s.partition.blocks > 0) {
        const PartitionStats& p = s.partition;
        o["partition"] = {{"blocks", p.blocks},
                          {"collar_voxels", p.collar_voxels},
                          {"collar_growths", p.collar_growths},
                          {"exchange_rounds", p.exchange_rounds},
                          {"exchanged_points", p.exchanged_points},
                          {"block_rebuilds", p.block_rebuilds},
                          {"processes", p.processes},
                          {"max_process_peak_memory_bytes", p.max_process_peak_memory_bytes},
                          {"max_process_samples_read", p.max_process_samples_read},
                          {"file_samples", p.file_samples},
                          {"block_points", p.block_points},
                          {"seam_points", p.seam_points}};
    }
    if (s.adaptive.used) {
        const AdaptiveStats& a = s.adaptive;
        o["adaptive"] = {{"eps_coarsening_world", a.eps_coarsening_world},
                         {"distance_world", a.distance_world},
                         {"eps_meshing_world", a.eps_meshing_world},
                         {"leaves_per_level", a.leaves_per_level},
                         {"cells_certified", a.cells_certified},
                         {"repair_rounds", a.repair_rounds},
                         {"repair_splits", a.repair_splits},
                         {"E_uniform", a.e_uniform},
                         {"E_octree", a.e_octree},
                         {"E_removable_bound", a.e_removable},
                         {"meshed_on", a.meshed_on_octree ? "octree" : "input grid"}};
    }
    if (s.certify_attempts > 0) o["certify_attempts"] = s.certify_attempts;
    const TetStats& t = s.tets;
    if (t.vertices > 0) {
        Json seconds = Json::object();
        for (const auto& [k, v] : t.seconds) seconds[k] = v;
        o["tets"] = {{"vertices", t.vertices},
                     {"tets_inside", t.tets_inside},
                     {"tets_outside", t.tets_outside},
                     {"G_prime", t.g_prime},
                     {"grid_points_removed", t.grid_points_removed},
                     {"volume_inside", t.volume_inside},
                     {"volume_outside", t.volume_outside},
                     {"volume_enclosed_by_surface", t.volume_enclosed_by_surface},
                     {"min_dihedral_deg", t.min_dihedral_deg},
                     {"max_dihedral_deg", t.max_dihedral_deg},
                     {"max_radius_edge", t.max_radius_edge},
                     {"tets_below_10deg", t.tets_below_10deg},
                     {"tets_touching_surface", t.tets_touching_surface},
                     {"min_dihedral_deg_off_surface", t.min_dihedral_deg_off_surface},
                     {"max_radius_edge_off_surface", t.max_radius_edge_off_surface},
                     {"min_dihedral_deg_delaunay", t.min_dihedral_deg_delaunay},
                     {"vertices_moved", t.vertices_moved},
                     {"vertices_removed", t.vertices_removed},
                     {"vertices_inserted", t.vertices_inserted},
                     {"flips", t.flips},
                     {"improvement_seconds", t.improvement_seconds},
                     {"seconds", std::move(seconds)},
                     {"dihedral_histogram_10deg", t.dihedral_histogram}};
    }
    return o.dump(2) + "\n";
}

} // namespace isodel
