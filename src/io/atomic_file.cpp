#include "atomic_file.h"

#include <isodel/errors.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace isodel::io {

AtomicFile::AtomicFile(const std::string& path) : path_(path)
{
    const auto slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash == 0 ? 1 : slash);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.empty()) throw IoError(path + ": cannot write: not a file name");
    // Same folder as the target: rename() is then atomic (same file system).
    tmp_ = dir + "/." + name + ".tmp." + std::to_string(::getpid());
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
    if (!out_) throw IoError(path + ": cannot write: " + std::strerror(errno));
}

AtomicFile::~AtomicFile()
{
    if (!committed_) {
        out_.close();
        std::remove(tmp_.c_str());
    }
}

void AtomicFile::commit()
{
    out_.flush();
    if (!out_) throw IoError(path_ + ": write failed: " + std::strerror(errno));
    out_.close();
    if (out_.fail()) throw IoError(path_ + ": write failed on close");
    // Data on disk before the rename makes it visible under the final name.
    const int fd = ::open(tmp_.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
        throw IoError(path_ + ": cannot rename the temporary file into place: " + std::strerror(errno));
    committed_ = true;
}

std::string extension_of(const std::string& path)
{
    const auto slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const auto dot = name.find_last_of('.');
    if (dot == std::string::npos || dot == 0) return "";
    std::string ext = name.substr(dot);
    if (ext == ".gz") { // compound: ".inr.gz"
        const auto dot2 = name.find_last_of('.', dot - 1);
        if (dot2 != std::string::npos && dot2 != 0) ext = name.substr(dot2);
    }
    return ext;
}

} // namespace isodel::io
