#pragma once
// Internal: one reader per volume format; read_volume() dispatches on the extension.
#include <isodel/volume.h>

#include <string>

namespace isodel::io {

Volume read_vdb(const std::string& path, const ReadOptions& opt);
Volume read_mrc(const std::string& path, const ReadOptions& opt);
Volume read_inr(const std::string& path, const ReadOptions& opt);
Volume read_raw(const std::string& path, const ReadOptions& opt);

} // namespace isodel::io
