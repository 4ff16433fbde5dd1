// isodel convert: any supported volume -> .vdb, keeping samples and transform bit-identical, so
// a map can be inspected with OpenVDB tools or fed to decimate.
#include "cli_common.h"

#include <isodel/errors.h>

namespace isodel::cli {

void add_convert_command(CLI::App& app, int& exit_code)
{
    auto* cmd = app.add_subcommand("convert", "Convert a volume to an OpenVDB file");
    auto in = std::make_shared<InputOptions>();
    auto out = std::make_shared<std::string>();
    add_input_options(*cmd, *in);
    cmd->add_option("-o,--output", *out, "Output .vdb file")->required();
    cmd->callback([in, out, &exit_code] {
        // Refuse a wrong output name before spending time on the input.
        if (out->size() < 4 || out->compare(out->size() - 4, 4, ".vdb") != 0)
            throw InvalidInput(*out + ": output must be a .vdb file");
        ProgressReporter progress(false);
        Volume vol = [&] {
            InterruptScope scope(&progress, "read");
            return read_input(*in);
        }();
        InterruptScope scope(&progress, "write");
        scope.check();
        vol.grid->insertMeta("isodel_source", openvdb::StringMetadata(vol.path));
        write_vdb(*out, {vol.grid});
        exit_code = kOk;
    });
}

} // namespace isodel::cli
