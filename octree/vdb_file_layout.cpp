#include "octree/vdb_file_layout.h"

#include <isodel/errors.h>

#include <openvdb/Metadata.h>
#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/openvdb.h>
#include <openvdb/version.h>

#include <algorithm>
#include <cstring>
#include <fstream>

namespace isodel::octree {
namespace {

/// Reads the little-endian fields of the file as OpenVDB's reader does, each checked against
/// the file's size before it is read or skipped.
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

    void need(std::uint64_t bytes, const char* what) const
    {
        if (bytes > left())
            refuse(std::string(what) + " needs " + std::to_string(bytes) + " bytes at offset " + std::to_string(pos_) +
                   ", the file has " + std::to_string(left()) + " more (truncated or corrupt)");
    }
    template <class T>
    T read(const char* what)
    {
        need(sizeof(T), what);
        T v;
        in_.read(reinterpret_cast<char*>(&v), sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    void skip(std::uint64_t bytes, const char* what)
    {
        need(bytes, what);
        pos_ += bytes;
        in_.seekg(std::streamoff(pos_));
    }
    /// openvdb::readString: a uint32 length, then the characters.
    std::string string(const char* what)
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

/// One array of openvdb::io::DelayedLoadMetadata::readValue: a uint32 byte count, then a Blosc
/// buffer of that many bytes, or (count 0) \p count raw elements of \p element bytes. OpenVDB
/// sizes its vector by the Blosc header's uncompressed size, so that must be the array's (or the
/// 128 bytes OpenVDB's compressor pads a shorter array to).
/// \return the bytes the array takes.
std::uint64_t skip_delayed_load_array(LayoutReader& r, std::uint32_t count, std::uint64_t element, const char* what)
{
    const auto bytes = r.read<std::uint32_t>(what);
    if (bytes == 0) {
        r.skip(count * element, what);
        return 4 + count * element;
    }
    constexpr std::uint32_t kBloscHeader = 16;
    if (bytes < kBloscHeader) r.refuse(std::string(what) + ": a compressed array shorter than its header");
    r.need(bytes, what);
    const std::uint64_t start = r.pos();
    r.skip(4, what); // Blosc's version, flags and type size
    const auto uncompressed = r.read<std::uint32_t>(what);
    constexpr std::uint64_t kBloscPadBytes = 128; // openvdb::io BLOSC_PAD_BYTES
    if (uncompressed < count * element || uncompressed > std::max<std::uint64_t>(count * element, kBloscPadBytes))
        r.refuse(std::string(what) + ": a compressed array of " + std::to_string(uncompressed) + " bytes for " +
                 std::to_string(count) + " elements of " + std::to_string(element));
    r.skip(bytes - (r.pos() - start), what);
    return 4 + std::uint64_t(bytes);
}

/// openvdb::io::DelayedLoadMetadata::readValue (a registered type that OpenVDB's writer puts in
/// every grid): a leaf count, then a mask byte per leaf, then optionally a size per leaf. A leaf
/// takes more than one byte of the file, so the count is bounded by the file's size.
void skip_delayed_load(LayoutReader& r, std::uint32_t bytes, const char* what)
{
    if (bytes == 0) return;
    const std::uint64_t start = r.pos();
    const auto count = r.read<std::uint32_t>(what);
    if (count > r.size()) r.refuse(std::string(what) + ": " + std::to_string(count) + " leaves cannot fit in the file");
    skip_delayed_load_array(r, count, sizeof(std::int8_t), what);
    const std::uint64_t mark = r.pos();
    if (r.read<std::uint32_t>(what) != 0xFFFFFFFFu) { // else no sizes stored
        r.seek(mark);
        skip_delayed_load_array(r, count, sizeof(std::int64_t), what);
    }
    const std::uint64_t used = r.pos() - start;
    if (used > bytes) r.refuse(std::string(what) + ": delayed-load metadata longer than its stated size");
    r.skip(bytes - used, what); // OpenVDB skips what it does not know
}

/// openvdb::MetaMap::readMeta: a count, then name, type name, byte count and value per entry.
/// A registered type of fixed size is read with its own size whatever the byte count says, so
/// the byte count must equal it, or OpenVDB's reading would part from this walk.
void skip_metadata(LayoutReader& r, const char* what)
{
    const auto count = r.read<std::uint32_t>(what);
    if (count > r.left() / 12) // each entry holds at least three uint32 sizes
        r.refuse(std::string(what) + ": " + std::to_string(count) + " metadata entries cannot fit in the file");
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::string name = r.string(what);
        const std::string type = r.string(what);
        const auto bytes = r.read<std::uint32_t>(what);
        if (type == openvdb::io::DelayedLoadMetadata::staticTypeName()) {
            skip_delayed_load(r, bytes, what);
            continue;
        }
        if (type != openvdb::StringMetadata::staticTypeName() && openvdb::Metadata::isRegisteredType(type)) {
            const auto expected = openvdb::Metadata::createMetadata(type)->size();
            if (bytes != expected)
                r.refuse(std::string(what) + ": metadata '" + name + "' of type " + type + " states " +
                         std::to_string(bytes) + " bytes, the type has " + std::to_string(expected));
        }
        r.skip(bytes, what); // a string's characters, or a type OpenVDB does not know
    }
}

} // namespace

void check_vdb_file_layout(const std::string& path)
{
    LayoutReader r(path);
    openvdb::initialize(); // the metadata types must be registered
    // Archive::readHeader.
    if (r.size() < 8 || r.read<std::int64_t>("the magic number") != openvdb::OPENVDB_MAGIC)
        r.refuse("wrong magic number");
    const auto version = r.read<std::uint32_t>("the header");
    if (version < openvdb::OPENVDB_FILE_VERSION_FLOAT_FRUSTUM_BBOX || version > openvdb::OPENVDB_FILE_VERSION)
        r.refuse("file format version " + std::to_string(version) + " (this OpenVDB reads " +
                 std::to_string(openvdb::OPENVDB_FILE_VERSION_FLOAT_FRUSTUM_BBOX) + " to " +
                 std::to_string(openvdb::OPENVDB_FILE_VERSION) + ")");
    r.skip(8, "the header"); // library major and minor version
    const bool has_grid_offsets = r.read<char>("the header") != 0;
    if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION) r.skip(1, "the header"); // compression flag
    r.skip(36, "the header"); // the UUID as text
    skip_metadata(r, "the file metadata");
    const auto grids = r.read<std::int32_t>("the grid count");
    // Without offsets (a file written as a stream) the grids follow one another, and OpenVDB
    // reads them whole when it opens the file: there are no descriptors to check.
    if (!has_grid_offsets) return;
    if (grids < 0 || std::uint64_t(grids) > r.left() / 36) // three strings and three offsets each
        r.refuse(std::to_string(grids) + " grids cannot fit in the file");
    for (std::int32_t g = 0; g < grids; ++g) {
        // GridDescriptor::read, then File::readGridDescriptors' seek to the grid's end.
        const std::string name = r.string("a grid descriptor");
        r.string("a grid descriptor"); // type
        if (version >= openvdb::OPENVDB_FILE_VERSION_GRID_INSTANCING) r.string("a grid descriptor");
        const std::uint64_t header_end = r.pos() + 24;
        const auto grid_pos = r.read<std::int64_t>("a grid descriptor");
        const auto block_pos = r.read<std::int64_t>("a grid descriptor");
        const auto end_pos = r.read<std::int64_t>("a grid descriptor");
        if (grid_pos < std::int64_t(header_end) || block_pos < grid_pos || end_pos < block_pos ||
            std::uint64_t(end_pos) > r.size())
            r.refuse("grid '" + name + "' states offsets " + std::to_string(grid_pos) + ", " +
                     std::to_string(block_pos) + ", " + std::to_string(end_pos) + " outside its descriptor's end " +
                     std::to_string(header_end) + " and the file's " + std::to_string(r.size()) +
                     " bytes (truncated or corrupt)");
        // Archive::readGrid: the compression flags, then the grid's metadata, before its blocks.
        r.seek(std::uint64_t(grid_pos));
        if (version >= openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION) r.skip(4, "a grid's compression flags");
        skip_metadata(r, "a grid's metadata");
        if (r.pos() > std::uint64_t(block_pos))
            r.refuse("grid '" + name + "': its metadata runs past the start of its data");
        r.seek(std::uint64_t(end_pos));
    }
}

} // namespace isodel::octree
