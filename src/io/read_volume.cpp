// read_volume(): picks the reader by extension. The file's existence is checked first so that a
// missing file is reported as such whatever its name.
#include "atomic_file.h"
#include "dense_volume.h"
#include "readers.h"

namespace isodel {

Volume read_volume(const std::string& path, const ReadOptions& opt)
{
    io::file_size_or_throw(path);
    const std::string ext = io::extension_of(path);
    if (ext == ".vdb") return io::read_vdb(path, opt);
    if (ext == ".mrc" || ext == ".map" || ext == ".ccp4" || ext == ".mrcs") return io::read_mrc(path, opt);
    if (ext == ".inr" || ext == ".inr.gz") return io::read_inr(path, opt);
    return io::read_raw(path, opt); // refuses unknown extensions when no raw layout is given
}

} // namespace isodel
