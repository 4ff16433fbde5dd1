// Shared CLI pieces: input options -> ReadOptions, and the terminal progress line / Ctrl-C hook.
#include "cli_common.h"

#include <isodel/errors.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <mutex>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <unistd.h>

namespace isodel::cli {
namespace {

std::atomic<bool> g_sigint{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT handler needs a lock-free flag");

extern "C" void on_sigint(int) { g_sigint.store(true); }

} // namespace

struct ProgressReporter::Impl {
    bool show = false;
    bool trace = false;
    std::mutex log_mutex; // trace lines come from worker threads too
    std::string stage;
    std::chrono::steady_clock::time_point stage_start, last_print;
    bool printed = false;
    struct sigaction old_action {};

    /// "stage 40% 1.2s", or with a count "points 1200/3000 leaves 1.2s".
    void print(int percent, const std::string& count = {})
    {
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start).count();
        if (!count.empty()) std::fprintf(stderr, "\r%s %s %.1fs\033[K", stage.c_str(), count.c_str(), secs);
        else if (percent >= 0) std::fprintf(stderr, "\r%s %d%% %.1fs\033[K", stage.c_str(), percent, secs);
        else std::fprintf(stderr, "\r%s %.1fs\033[K", stage.c_str(), secs);
        std::fflush(stderr);
        printed = true;
        last_print = std::chrono::steady_clock::now();
    }
};

ProgressReporter::ProgressReporter(bool quiet, bool trace) : impl_(std::make_unique<Impl>())
{
    impl_->trace = trace;
    // Progress only for a person watching: never into a log file or a pipe.
    impl_->show = !quiet && ::isatty(2);
    g_sigint.store(false);
    struct sigaction sa {};
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    // A second Ctrl-C kills at once, for when a stage does not poll for a while.
    sa.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &sa, &impl_->old_action);
}

ProgressReporter::~ProgressReporter()
{
    if (impl_->printed) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    sigaction(SIGINT, &impl_->old_action, nullptr);
}

void ProgressReporter::start(const char* name)
{
    impl_->stage = name ? name : "";
    impl_->stage_start = std::chrono::steady_clock::now();
    if (impl_->show) impl_->print(-1);
}

void ProgressReporter::end()
{
    if (impl_->show) impl_->print(100);
}

bool ProgressReporter::wasInterrupted(int percent)
{
    // At most ten updates a second: printing must not slow the work it reports on.
    if (impl_->show &&
        std::chrono::steady_clock::now() - impl_->last_print > std::chrono::milliseconds(100))
        impl_->print(percent);
    return g_sigint.load();
}

bool ProgressReporter::progress(std::uint64_t done, std::uint64_t total, const char* unit)
{
    if (impl_->show &&
        std::chrono::steady_clock::now() - impl_->last_print > std::chrono::milliseconds(100))
        impl_->print(-1, std::to_string(done) + "/" + std::to_string(total) + " " + (unit ? unit : ""));
    return g_sigint.load();
}

void ProgressReporter::log(const char* message)
{
    if (!impl_->trace) return;
    std::lock_guard<std::mutex> lock(impl_->log_mutex);
    if (impl_->printed) std::fprintf(stderr, "\r\033[K"); // not on top of the progress line
    std::fprintf(stderr, "%s\n", message);
    std::fflush(stderr);
}

void add_input_options(CLI::App& cmd, InputOptions& in)
{
    cmd.add_option("INPUT", in.path, "Input volume (.vdb, .mrc/.map/.ccp4, .inr/.inr.gz, or raw)")->required();
    cmd.add_option("--grid", in.grid, ".vdb: name of the grid to read (default: the first scalar grid)");
    cmd.add_option("--raw-dims", in.raw_dims, "Raw volume: dimensions X,Y,Z (x fastest)");
    cmd.add_option("--raw-type", in.raw_type, "Raw volume: sample type float32|uint8|uint16|int16 (default float32)");
    cmd.add_option("--raw-spacing", in.raw_spacing, "Raw volume: voxel size (default 1)");
}

Volume read_input(const InputOptions& in) { return read_volume(in.path, read_options(in)); }

ReadOptions read_options(const InputOptions& in)
{
    ReadOptions opt;
    opt.grid_name = in.grid;
    if (const char* cap = std::getenv("ISODEL_MAX_VOXELS")) {
        try {
            opt.max_voxels = std::stoull(cap);
        } catch (const std::exception&) {
            throw InvalidInput("ISODEL_MAX_VOXELS: '" + std::string(cap) + "' is not a number");
        }
    }
    if (!in.raw_dims.empty()) {
        RawLayout raw;
        std::istringstream s(in.raw_dims);
        char c1 = 0, c2 = 0;
        if (!(s >> raw.dims[0] >> c1 >> raw.dims[1] >> c2 >> raw.dims[2]) || c1 != ',' || c2 != ',' || !s.eof())
            throw InvalidInput("--raw-dims: '" + in.raw_dims + "' is not X,Y,Z");
        raw.type = in.raw_type.empty() ? "float32" : in.raw_type;
        raw.spacing = in.raw_spacing;
        opt.raw = raw;
    } else if (!in.raw_type.empty()) {
        throw InvalidInput("--raw-type needs --raw-dims");
    }
    return opt;
}

} // namespace isodel::cli
