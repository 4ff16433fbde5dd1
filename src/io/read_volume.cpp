// read_volume(): picks the reader by extension. The file's existence is checked first so that a
// missing file is reported as such whatever its name.
#include "atomic_file.h"
#include "dense_volume.h"
#include "readers.h"

namespace isodel {
namespace {

Volume read_by_extension(const std::string& path, const ReadOptions& opt)
{
    const std::string ext = io::extension_of(path);
    if (ext == ".vdb") return io::read_vdb(path, opt);
    if (ext == ".mrc" || ext == ".map" || ext == ".ccp4" || ext == ".mrcs") return io::read_mrc(path, opt);
    if (ext == ".inr" || ext == ".inr.gz") return io::read_inr(path, opt);
    return io::read_raw(path, opt); // refuses unknown extensions when no raw layout is given
}

} // namespace

Volume read_volume(const std::string& path, const ReadOptions& opt)
{
    io::file_size_or_throw(path);
    try {
        return read_by_extension(path, opt);
    } catch (const openvdb::ArithmeticError& e) {
        // The dense readers check that voxel sizes are finite and > 0, but OpenVDB's maps also
        // refuse a voxel volume under 3e-15 (their determinant tolerance): say so with the file.
        io::invalid(path, std::string("OpenVDB cannot make a transform of this voxel size and cell (") + e.what() +
                              "); express the map in larger units");
    }
}

} // namespace isodel
