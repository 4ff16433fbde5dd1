// STUB until issue 5 lands: registers `isodel verify` with its interface (issue 2) so that
// scripts and --help see it, and exits 2 saying it is not available yet.
#include "cli_common.h"

#include <iostream>

namespace isodel::cli {
namespace {
struct VerifyOptions {
    InputOptions in;
    std::string out, inside, tets, region, stats, importance, mesh, json;
    double iso = 0, eps = 0, eps_voxels = 0.5, tolerance = 0, band = 0;
    int threads = 0, k = 1;
    bool quiet = false;
};
} // namespace

void add_verify_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("verify", "Check the guarantees of a mesh against its volume");
    auto o = std::make_shared<VerifyOptions>();
    add_input_options(*cmd, o->in);
    cmd->add_option("--iso", o->iso, "Isovalue")->required();
    cmd->add_option("--mesh", o->mesh, "Surface mesh to verify")->required();
    cmd->add_option("--tets", o->tets, "Tetrahedral mesh to verify");
    cmd->add_option("--eps", o->eps, "Hausdorff bound in world units");
    cmd->add_option("--json", o->json, "Write the report as JSON");
    cmd->callback([o, &exit_code] {
        std::cerr << "isodel verify: not available yet (issue 5 has not landed)\n";
        exit_code = kBadInput;
    });
}

} // namespace isodel::cli
