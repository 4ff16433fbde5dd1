// isodel: the command line. Parses, dispatches to one subcommand (cmd_*.cpp), and maps exceptions
// to exit codes: bad usage or input -> 2 with one line "isodel: <message>" on stderr,
// a guarantee that could not be certified -> 1, Ctrl-C -> 130.
#include "cli_common.h"
#include "mpi_transport.h"

#include <isodel/errors.h>

#include <openvdb/openvdb.h>

#include <iostream>

int main(int argc, char** argv)
{
    using namespace isodel::cli;
    MpiSession mpi(argc, argv); // inactive unless mpirun started this process
    // Under mpirun every process fails together (partitioned meshing agrees on failures), and the
    // first one alone says why: one message, not one per process.
    if (mpi.rank() != 0) std::cerr.setstate(std::ios::failbit);
    openvdb::initialize();
    CLI::App app{"isodel: Delaunay meshes of level sets of sampled volumes, with guarantees\n"
                 "(Goswami, Gillette, Bajaj, IMR 2007)"};
    app.name("isodel");
    app.require_subcommand(1);
    int exit_code = kOk;
    add_info_command(app, exit_code);
    add_convert_command(app, exit_code);
    add_mesh_command(app, exit_code);
    add_decimate_command(app, exit_code);
    add_resample_command(app, exit_code);
    add_verify_command(app, exit_code);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help, --version
        std::cerr << "isodel: " << e.what() << " (see isodel --help)\n";
        return kBadInput;
    } catch (const isodel::Cancelled& e) {
        std::cerr << "isodel: " << e.what() << "; nothing was written\n";
        return kInterrupted;
    } catch (const isodel::GuaranteeViolated& e) {
        std::cerr << "isodel: " << e.what() << "\n";
        return kFailed;
    } catch (const isodel::Error& e) { // InvalidInput, IoError
        std::cerr << "isodel: " << e.what() << "\n";
        return kBadInput;
    } catch (const openvdb::Exception& e) {
        std::cerr << "isodel: " << e.what() << "\n";
        return kBadInput;
    } catch (const std::bad_alloc&) {
        std::cerr << "isodel: out of memory\n";
        return kBadInput;
    } catch (const std::exception& e) {
        // Anything else is a bug, but the user still gets one line and a non-zero status.
        std::cerr << "isodel: internal error: " << e.what() << "\n";
        return kFailed;
    }
    return exit_code;
}
