// write_vdb(): OpenVDB's stream writer into an AtomicFile, so a failed or interrupted write never
// leaves a partial .vdb under the final name.
#include "atomic_file.h"

#include <isodel/errors.h>
#include <isodel/volume.h>

#include <openvdb/io/Stream.h>

namespace isodel {

void write_vdb(const std::string& path, const openvdb::GridPtrVec& grids)
{
    if (io::extension_of(path) != ".vdb")
        throw InvalidInput(path + ": output must have the extension .vdb");
    openvdb::initialize();
    io::AtomicFile file(path);
    try {
        openvdb::io::Stream stream(file.stream());
        stream.write(grids);
    } catch (const openvdb::Exception& e) {
        throw IoError(path + ": cannot write: " + e.what());
    }
    file.commit();
}

} // namespace isodel
