// `isodel decimate`: coarsen a volume into an adaptive grid (paper Property IV; octree/decimate.h).
#include "cli_common.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <iostream>

namespace isodel::cli {
namespace {
struct DecimateCli {
    InputOptions in;
    std::string out, importance;
    double iso = 0, tolerance = 0, band = 1;
    int k = 1, max_level = 8;
    bool quiet = false;
};

std::string mib(std::size_t b) { return std::to_string(double(b) / (1024.0 * 1024.0)).substr(0, 6) + " MiB"; }
} // namespace

void add_decimate_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("decimate", "Decimate a volume to an adaptive grid (level difference <= k)");
    auto o = std::make_shared<DecimateCli>();
    add_input_options(*cmd, o->in);
    cmd->add_option("-o,--output", o->out, "Output adaptive .vdb")->required();
    cmd->add_option("--k", o->k, "Maximum level difference between touching cells (>= 1)")->required();
    cmd->add_option("--tolerance", o->tolerance, "Maximum interpolation error T (value units)")->required();
    auto* iso = cmd->add_option("--iso", o->iso, "Isovalue whose neighbourhood stays fine");
    cmd->add_option("--band", o->band, "Half-width in voxels of the fine band around --iso (default 1)")->needs(iso);
    cmd->add_option("--importance", o->importance, "Mask .vdb: cells stay fine where it is active");
    cmd->add_option("--max-level", o->max_level, "Coarsest level (default 8)");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress");
    cmd->callback([o, iso, &exit_code] {
        ProgressReporter progress(o->quiet);
        const Volume vol = read_input(o->in);
        DecimateOptions opt;
        opt.k = o->k;
        opt.tolerance = o->tolerance;
        if (iso->count()) {
            opt.iso = o->iso;
            opt.band = o->band;
        }
        opt.max_level = o->max_level;
        opt.source = vol.path;
        if (!o->importance.empty()) {
            opt.importance = read_importance_grid(o->importance);
        }
        const DecimateResult r = decimate(*vol.grid, opt, &progress);
        save_adaptive(o->out, r.volume);
        std::cout << "cells:        " << r.cells_before << " -> " << r.cells_after << "  (factor "
                  << double(r.cells_before) / double(std::max<std::uint64_t>(1, r.cells_after)) << ")\n"
                  << "memory:       " << mib(r.memory_before) << " -> " << mib(r.memory_after) << "\n"
                  << "levels:";
        for (std::size_t l = 0; l < r.histogram.size(); ++l) std::cout << "  L" << l << ": " << r.histogram[l];
        std::cout << "\nmax error:    " << r.max_error << "  (tolerance " << opt.tolerance << ", measured on every fine sample)\n"
                  << "k:            " << opt.k << "  (max level difference found " << r.max_level_difference << ")\n"
                  << "time:         " << r.seconds << " s\n";
        exit_code = kOk;
    });
}

} // namespace isodel::cli
