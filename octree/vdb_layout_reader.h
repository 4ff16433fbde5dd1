#pragma once
// Internal: the byte reader of the OpenVDB file checks (vdb_file_layout.cpp, vdb_tree_layout.cpp).
// Every field is read as OpenVDB's reader reads it (little-endian, the in-memory layout of the
// type), and only after its size has been checked against the bytes the file has left, so the
// walk itself never reads past the end or allocates what a corrupt size states.
#include <isodel/errors.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace isodel::octree {

class LayoutReader {
public:
    explicit LayoutReader(const std::string& path) : path_(path), in_(path, std::ios::binary)
    {
        if (!in_) throw IoError(path + ": cannot open for reading");
        in_.seekg(0, std::ios::end);
        size_ = std::uint64_t(std::streamoff(in_.tellg()));
        in_.seekg(0);
    }

    [[noreturn]] void refuse(const std::string& why) const
    {
        throw InvalidInput(path_ + ": not a readable OpenVDB file: " + why);
    }
    std::uint64_t size() const { return size_; }
    std::uint64_t pos() const { return pos_; }
    std::uint64_t left() const { return size_ - pos_; }

    void need(std::uint64_t bytes, const std::string& what) const
    {
        if (bytes > left())
            refuse(what + " needs " + std::to_string(bytes) + " bytes at offset " + std::to_string(pos_) +
                   ", the file has " + std::to_string(left()) + " more (truncated or corrupt)");
    }
    template <class T>
    T read(const std::string& what)
    {
        need(sizeof(T), what);
        T v;
        in_.read(reinterpret_cast<char*>(&v), sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    /// Reads \p bytes into \p out (which holds at least that many).
    void read_bytes(void* out, std::uint64_t bytes, const std::string& what)
    {
        need(bytes, what);
        in_.read(static_cast<char*>(out), std::streamsize(bytes));
        pos_ += bytes;
    }
    void skip(std::uint64_t bytes, const std::string& what)
    {
        need(bytes, what);
        pos_ += bytes;
        in_.seekg(std::streamoff(pos_));
    }
    /// openvdb::readString: a uint32 length, then the characters.
    std::string string(const std::string& what)
    {
        const auto n = read<std::uint32_t>(what);
        need(n, what);
        std::string s(n, '\0');
        in_.read(s.data(), n);
        pos_ += n;
        return s;
    }
    void seek(std::uint64_t offset)
    {
        pos_ = offset;
        in_.seekg(std::streamoff(offset));
    }

private:
    std::string path_;
    std::ifstream in_;
    std::uint64_t size_ = 0;
    std::uint64_t pos_ = 0;
};

/// The sizes of a Blosc buffer's 16-byte header, which Blosc trusts when it decompresses.
struct BloscHeader {
    std::uint8_t flags = 0;
    std::uint32_t uncompressed = 0; ///< bytes it decompresses to
    std::uint32_t compressed = 0;   ///< bytes of the whole buffer, header included
};
inline BloscHeader blosc_header(const unsigned char* header)
{
    BloscHeader h;
    h.flags = header[2];
    std::memcpy(&h.uncompressed, header + 4, 4);
    std::memcpy(&h.compressed, header + 12, 4);
    return h;
}
/// Whether decompressing a buffer of \p chunk bytes with header \p h reads within the buffer:
/// the stated whole from its header up to the chunk, and a stored (memcpy) buffer holds all its
/// bytes.
inline bool blosc_fits(const BloscHeader& h, std::uint64_t chunk)
{
    constexpr std::uint8_t kMemcpyed = 0x2; // BLOSC_MEMCPYED
    return h.compressed >= 16 && h.compressed <= chunk &&
           (!(h.flags & kMemcpyed) || h.compressed >= 16 + std::uint64_t(h.uncompressed));
}

} // namespace isodel::octree
