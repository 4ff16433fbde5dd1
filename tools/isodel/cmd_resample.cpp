// STUB until issue 3 lands: registers `isodel resample` with its interface (issue 2) so that
// scripts and --help see it, and exits 2 saying it is not available yet.
#include "cli_common.h"

#include <iostream>

namespace isodel::cli {
namespace {
struct ResampleOptions {
    InputOptions in;
    std::string out, inside, tets, region, stats, importance, mesh, json;
    double iso = 0, eps = 0, eps_voxels = 0.5, tolerance = 0, band = 0;
    int threads = 0, k = 1;
    bool quiet = false;
};
} // namespace

void add_resample_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("resample", "Resample an adaptive grid to a dense grid");
    auto o = std::make_shared<ResampleOptions>();
    cmd->add_option("INPUT", o->in.path, "Adaptive .vdb")->required();
    cmd->add_option("-o,--output", o->out, "Output dense .vdb")->required();
    cmd->callback([o, &exit_code] {
        std::cerr << "isodel resample: not available yet (issue 3 has not landed)\n";
        exit_code = kBadInput;
    });
}

} // namespace isodel::cli
