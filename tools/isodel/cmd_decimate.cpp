// STUB until issue 3 lands: registers `isodel decimate` with its interface (issue 2) so that
// scripts and --help see it, and exits 2 saying it is not available yet.
#include "cli_common.h"

#include <iostream>

namespace isodel::cli {
namespace {
struct DecimateOptions {
    InputOptions in;
    std::string out, inside, tets, region, stats, importance, mesh, json;
    double iso = 0, eps = 0, eps_voxels = 0.5, tolerance = 0, band = 0;
    int threads = 0, k = 1;
    bool quiet = false;
};
} // namespace

void add_decimate_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("decimate", "Decimate a volume to an adaptive grid (level difference <= k)");
    auto o = std::make_shared<DecimateOptions>();
    add_input_options(*cmd, o->in);
    cmd->add_option("-o,--output", o->out, "Output adaptive .vdb")->required();
    cmd->add_option("--k", o->k, "Maximum level difference between neighbouring cells")->required();
    cmd->add_option("--tolerance", o->tolerance, "Maximum interpolation error")->required();
    auto* iso = cmd->add_option("--iso", o->iso, "Isovalue to protect");
    cmd->add_option("--band", o->band, "Half-width of the protected band around --iso")->needs(iso);
    cmd->add_option("--importance", o->importance, "Importance mask (.vdb)");
    cmd->callback([o, &exit_code] {
        std::cerr << "isodel decimate: not available yet (issue 3 has not landed)\n";
        exit_code = kBadInput;
    });
}

} // namespace isodel::cli
