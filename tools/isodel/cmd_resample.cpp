// `isodel resample`: adaptive .vdb -> dense .vdb of the continuous interpolant (octree/resample.h).
#include "cli_common.h"

#include <isodel/adaptive.h>
#include <isodel/errors.h>

#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace isodel::cli {
namespace {
struct ResampleCli {
    std::string in, out;
    bool quiet = false;
};
} // namespace

void add_resample_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("resample", "Resample an adaptive grid to a dense grid");
    auto o = std::make_shared<ResampleCli>();
    cmd->add_option("INPUT", o->in, "Adaptive .vdb")->required();
    cmd->add_option("-o,--output", o->out, "Output dense .vdb")->required();
    cmd->add_flag("-q,--quiet", o->quiet, "No progress");
    cmd->callback([o, &exit_code] {
        ProgressReporter progress(o->quiet);
        const AdaptiveVolume v = load_adaptive(o->in);
        auto dense = resample(v, &progress);
        dense->setSaveFloatAsHalf(false);
        const std::string tmp = o->out + ".tmp" + std::to_string(::getpid());
        try {
            openvdb::io::File(tmp).write({dense});
        } catch (const std::exception& e) {
            std::remove(tmp.c_str());
            throw IoError(o->out + ": cannot write: " + e.what());
        }
        if (std::rename(tmp.c_str(), o->out.c_str()) != 0) throw IoError(o->out + ": cannot rename into place");
        std::cout << "resampled " << o->in << " -> " << o->out << " (" << dense->activeVoxelCount()
                  << " active samples)\n";
        exit_code = kOk;
    });
}

} // namespace isodel::cli
