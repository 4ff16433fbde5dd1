#pragma once
// Internal: the byte reader of the OpenVDB file checks (vdb_file_layout.cpp, vdb_tree_layout.cpp).
// Every field is read as OpenVDB's reader reads it (little-endian, the in-memory layout of the
// type), and only after its size has been checked against the bytes the file has left, so the
// walk itself never reads past the end or allocates what a corrupt size states.
#include <isodel/errors.h>

#include <cstdint>
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

} // namespace isodel::octree
