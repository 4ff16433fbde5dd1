#pragma once
// Internal: write a file under a temporary name in the target folder, rename on commit().
// If commit() is never reached (exception, Ctrl-C through Cancelled), the destructor removes the
// temporary, so no partial or corrupted output is ever left under the final name.
#include <fstream>
#include <string>

namespace isodel::io {

class AtomicFile {
public:
    /// Opens "<dir>/.<name>.tmp.<pid>" for binary writing. \throw IoError naming \p path.
    explicit AtomicFile(const std::string& path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ofstream& stream() { return out_; }
    /// Flushes, checks the stream, renames to the final path. \throw IoError
    void commit();

private:
    std::string path_, tmp_;
    std::ofstream out_;
    bool committed_ = false;
};

/// Lower-case extension of \p path including compound ones (".inr.gz"); "" if none.
std::string extension_of(const std::string& path);

} // namespace isodel::io
