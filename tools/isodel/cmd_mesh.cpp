// STUB until issue 4 lands: registers `isodel mesh` with its interface (issue 2) so that
// scripts and --help see it, and exits 2 saying it is not available yet.
#include "cli_common.h"

#include <iostream>

namespace isodel::cli {
namespace {
struct MeshOptions {
    InputOptions in;
    std::string out, inside, tets, region, stats, importance, mesh, json;
    double iso = 0, eps = 0, eps_voxels = 0.5, tolerance = 0, band = 0;
    int threads = 0, k = 1;
    bool quiet = false;
};
} // namespace

void add_mesh_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("mesh", "Mesh the level set {F = iso} of a volume (DELSURFMESH)");
    auto o = std::make_shared<MeshOptions>();
    add_input_options(*cmd, o->in);
    cmd->add_option("-o,--output", o->out, "Output surface (.ply, .obj, .off, .stl)")->required();
    cmd->add_option("--iso", o->iso, "Isovalue")->required();
    cmd->add_option("--inside", o->inside, "Which side is inside: above|below (default from the grid class)")
        ->check(CLI::IsMember({"above", "below"}));
    auto* eps = cmd->add_option("--eps", o->eps, "Hausdorff bound in world units");
    cmd->add_option("--eps-voxels", o->eps_voxels, "Hausdorff bound in voxels (default 0.5)")->excludes(eps);
    cmd->add_option("--tets", o->tets, "Also write a tetrahedral mesh (.mesh, .vtu, .msh)");
    cmd->add_option("--region", o->region, "Tetrahedra to keep: inside|outside|both")
        ->check(CLI::IsMember({"inside", "outside", "both"}));
    cmd->add_option("--threads", o->threads, "Threads (0 = all)");
    cmd->add_option("--stats", o->stats, "Write statistics as JSON");
    cmd->add_flag("--quiet", o->quiet, "No progress output");
    cmd->callback([o, &exit_code] {
        // Bad input is refused even before the mesher lands: the isovalue must lie in the range.
        check_isovalue(read_input(o->in), o->iso);
        std::cerr << "isodel mesh: not available yet (issue 4 has not landed)\n";
        exit_code = kBadInput;
    });
}

} // namespace isodel::cli
