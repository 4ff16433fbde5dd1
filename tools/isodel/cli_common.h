#pragma once
// Shared pieces of the isodel CLI subcommands. Each subcommand lives in its own cmd_<name>.cpp
// and registers itself through add_<name>_command(); main.cpp calls them all and maps
// exceptions to exit codes: 0 ok, 1 a guarantee/verification failed, 2 bad usage or input,
// 130 interrupted (Ctrl-C): isodel::Cancelled.
#include <isodel/interrupt.h>
#include <isodel/volume.h>

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace isodel::cli {

/// Exit codes.
enum Exit : int { kOk = 0, kFailed = 1, kBadInput = 2, kInterrupted = 130 };

/// Progress on stderr (stage, percent, elapsed) only when stderr is a terminal and not --quiet;
/// also the Ctrl-C hook: wasInterrupted() returns true once SIGINT was received. With \p trace
/// the library's trace lines (Interrupter::log) go to stderr, one a line.
class ProgressReporter final : public Interrupter {
public:
    explicit ProgressReporter(bool quiet, bool trace = false);
    ~ProgressReporter() override;
    void start(const char* name) override;
    void end() override;
    bool wasInterrupted(int percent = -1) override;
    bool progress(std::uint64_t done, std::uint64_t total, const char* unit) override;
    void log(const char* message) override;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Options shared by every subcommand that reads a volume.
struct InputOptions {
    std::string path;
    std::string grid;
    std::string raw_dims;    // "X,Y,Z"
    std::string raw_type;    // float32|uint8|uint16|int16
    double raw_spacing = 1.0;
};

/// Adds INPUT, --grid, --raw-dims, --raw-type, --raw-spacing to \p cmd.
void add_input_options(CLI::App& cmd, InputOptions& in);

/// Reads the volume \p in describes (throws InvalidInput/IoError with the path in the message).
Volume read_input(const InputOptions& in);
// How read_input reads (grid name, raw layout, ISODEL_MAX_VOXELS).
ReadOptions read_options(const InputOptions& in);

// Subcommand registration (one per cmd_*.cpp). Each returns after adding its subcommand; the
// callback it installs returns its exit code through the given int.
void add_info_command(CLI::App& app, int& exit_code);
void add_convert_command(CLI::App& app, int& exit_code);
void add_mesh_command(CLI::App& app, int& exit_code);
void add_decimate_command(CLI::App& app, int& exit_code);
void add_resample_command(CLI::App& app, int& exit_code);
void add_verify_command(CLI::App& app, int& exit_code);

} // namespace isodel::cli
