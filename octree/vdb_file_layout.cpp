#include "octree/vdb_file_layout.h"

#include "octree/vdb_layout_reader.h"
#include "octree/vdb_tree_layout.h"

#include <isodel/errors.h>

#include <openvdb/Metadata.h>
#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/openvdb.h>
#include <openvdb/version.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <vector>

namespace isodel::octree {
namespace {

/// One array of openvdb::io::DelayedLoadMetadata::readValue: a uint32 byte count, then a Blosc
/// buffer of that many bytes, or (count 0) \p count raw elements of \p element bytes. OpenVDB
/// sizes its vector by the Blosc header's uncompressed size, so that must be the array's (or the
/// 128 bytes OpenVDB's compressor pads a shorter array to), and Blosc decompresses by the
/// header's compressed size, which must lie within the buffer (blosc_fits).
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
    unsigned char header[kBloscHeader];
    r.read_bytes(header, kBloscHeader, what);
    const BloscHeader h = blosc_header(header);
    constexpr std::uint64_t kBloscPadBytes = 128; // openvdb::io BLOSC_PAD_BYTES
    if (h.uncompressed < count * element || h.uncompressed > std::max<std::uint64_t>(count * element, kBloscPadBytes))
        r.refuse(std::string(what) + ": a compressed array of " + std::to_string(h.uncompressed) + " bytes for " +
                 std::to_string(count) + " elements of " + std::to_string(element));
    if (!blosc_fits(h, bytes))
        r.refuse(std::string(what) + ": a compressed array of " + std::to_string(bytes) + " bytes whose header states " +
                 std::to_string(h.compressed));
    r.skip(bytes - kBloscHeader, what);
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
/// \return the value of a grid's "is_saved_as_half_float" entry (false without one): after
/// GridBase::readMeta, Grid::readTopology and readBuffers read the tree at half precision by
/// it, whatever the descriptor's type name said.
bool skip_metadata(LayoutReader& r, const char* what, bool grid_metadata = false)
{
    bool saved_as_half = false;
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
        const bool half_entry = grid_metadata && name == openvdb::GridBase::META_SAVE_HALF_FLOAT;
        if (half_entry && (type != openvdb::BoolMetadata::staticTypeName() || bytes != 1))
            r.refuse(std::string(what) + ": metadata '" + name + "' is not a bool");
        if (type == openvdb::BoolMetadata::staticTypeName() && bytes == 1) {
            // BoolMetadata reads the byte as a bool: only 0 and 1 are bools.
            const auto b = r.read<std::uint8_t>(what);
            if (b > 1) r.refuse(std::string(what) + ": metadata '" + name + "' is a bool stored as " + std::to_string(b));
            if (half_entry) saved_as_half = b == 1;
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
    return saved_as_half;
}

/// A grid descriptor as GridDescriptor::read reads it.
struct Descriptor {
    std::string unique_name;
    std::string type; ///< without the "_HalfFloat" suffix (the grid's metadata says how its tree is stored)
    std::string parent; ///< the instance parent's unique name; empty for a grid with its own tree
    std::int64_t grid_pos = 0, block_pos = 0, end_pos = 0;
};

Descriptor read_descriptor(LayoutReader& r)
{
    Descriptor d;
    d.unique_name = r.string("a grid descriptor");
    d.type = r.string("a grid descriptor");
    const std::string half_suffix = "_HalfFloat"; // GridDescriptor.cc, not exported
    if (d.type.size() > half_suffix.size() &&
        d.type.compare(d.type.size() - half_suffix.size(), half_suffix.size(), half_suffix) == 0) {
        d.type.resize(d.type.size() - half_suffix.size());
    }
    d.parent = r.string("a grid descriptor"); // format 216 and later: the instance parent
    d.grid_pos = r.read<std::int64_t>("a grid descriptor");
    d.block_pos = r.read<std::int64_t>("a grid descriptor");
    d.end_pos = r.read<std::int64_t>("a grid descriptor");
    return d;
}

/// Archive::readGrid from the grid's start: its compression flags, metadata, transform, and
/// (unless it shares an instance parent's tree) its tree. \p data_start bounds the metadata when
/// the descriptor states where the grid's data begins.
void walk_grid(LayoutReader& r, const Descriptor& d, const VdbTreeKind& kind, std::uint64_t data_start)
{
    VdbGridStream stream;
    stream.compression = r.read<std::uint32_t>("a grid's compression flags");
    stream.half = skip_metadata(r, "a grid's metadata", /*grid_metadata=*/true);
    if (r.pos() > data_start) r.refuse("grid '" + d.unique_name + "': its metadata runs past the start of its data");
    skip_vdb_transform(r, d.unique_name);
    if (d.parent.empty()) skip_vdb_tree(r, kind, stream, d.unique_name);
}

/// A file written as a stream has no grid offsets: File::open reads every grid, one after the
/// other, so every one must be of a type whose data the walk checks.
void walk_stream_grids(LayoutReader& r, std::int32_t grids)
{
    for (std::int32_t g = 0; g < grids; ++g) {
        const Descriptor d = read_descriptor(r);
        const auto kind = vdb_tree_kind(d.type);
        if (!kind)
            r.refuse("grid '" + d.unique_name + "' has type " + d.type +
                     ", whose data isodel cannot check, in a file without grid offsets (which OpenVDB reads whole)");
        walk_grid(r, d, *kind, r.size());
    }
}

/// A file with grid offsets: OpenVDB reads a grid when asked, from its descriptor's offset. The
/// grids of a type the walk knows are walked; an instance's parent (which OpenVDB reads in its
/// place, found by name) must be such a grid of the same type.
void walk_indexed_grids(LayoutReader& r, std::int32_t grids)
{
    std::vector<Descriptor> all;
    for (std::int32_t g = 0; g < grids; ++g) {
        // GridDescriptor::read, then File::readGridDescriptors' seek to the grid's end.
        Descriptor d = read_descriptor(r);
        const std::uint64_t header_end = r.pos();
        // An instance has no data blocks of its own: Archive::writeGridInstance leaves its block
        // offset 0, and it is never read.
        const bool instance = !d.parent.empty();
        if (d.grid_pos < std::int64_t(header_end) || d.end_pos < d.grid_pos || std::uint64_t(d.end_pos) > r.size() ||
            (!instance && (d.block_pos < d.grid_pos || d.end_pos < d.block_pos)))
            r.refuse("grid '" + d.unique_name + "' states offsets " + std::to_string(d.grid_pos) + ", " +
                     std::to_string(d.block_pos) + ", " + std::to_string(d.end_pos) + " outside its descriptor's end " +
                     std::to_string(header_end) + " and the file's " + std::to_string(r.size()) +
                     " bytes (truncated or corrupt)");
        r.seek(std::uint64_t(d.end_pos));
        all.push_back(std::move(d));
    }
    for (const Descriptor& d : all) {
        const auto kind = vdb_tree_kind(d.type);
        if (!kind) continue; // isodel's readers never ask OpenVDB for it (vdb_grid_type_checked)
        r.seek(std::uint64_t(d.grid_pos));
        walk_grid(r, d, *kind, std::uint64_t(d.parent.empty() ? d.block_pos : d.end_pos));
        if (r.pos() > std::uint64_t(d.end_pos))
            r.refuse("grid '" + d.unique_name + "': its data runs past the end its descriptor states");
        if (d.parent.empty()) continue;
        // File::findDescriptor looks the parent up by name, then by name without its "[N]"
        // suffix: every grid either lookup could return must have the instance's type.
        using openvdb::io::GridDescriptor;
        const std::string name = GridDescriptor::nameAsString(d.parent);
        const std::string stripped = GridDescriptor::stripSuffix(GridDescriptor::stringAsUniqueName(name));
        for (const Descriptor& p : all)
            if (const std::string key = GridDescriptor::stripSuffix(p.unique_name);
                (key == name || key == stripped) && p.type != d.type)
                r.refuse("grid '" + d.unique_name + "' of type " + d.type + " is an instance of '" + p.unique_name +
                         "', of type " + p.type);
    }
}

} // namespace

bool vdb_grid_type_checked(const std::string& grid_type) { return vdb_tree_kind(grid_type).has_value(); }

void check_vdb_file_layout(const std::string& path)
{
    LayoutReader r(path);
    openvdb::initialize(); // the metadata types must be registered
    // Archive::readHeader.
    if (r.size() < 8 || r.read<std::int64_t>("the magic number") != openvdb::OPENVDB_MAGIC)
        r.refuse("wrong magic number");
    const auto version = r.read<std::uint32_t>("the header");
    // The node formats walked here are those of format 222 (OpenVDB 2.0) and later.
    if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION || version > openvdb::OPENVDB_FILE_VERSION)
        r.refuse("file format version " + std::to_string(version) + " (isodel reads " +
                 std::to_string(openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION) + " to " +
                 std::to_string(openvdb::OPENVDB_FILE_VERSION) + ")");
    r.skip(8, "the header"); // library major and minor version
    const bool has_grid_offsets = r.read<char>("the header") != 0;
    r.skip(36, "the header"); // the UUID as text
    skip_metadata(r, "the file metadata");
    const auto grids = r.read<std::int32_t>("the grid count");
    if (grids < 0 || std::uint64_t(grids) > r.left() / 36) // three strings and three offsets each
        r.refuse(std::to_string(grids) + " grids cannot fit in the file");
    if (has_grid_offsets)
        walk_indexed_grids(r, grids);
    else
        walk_stream_grids(r, grids);
}

} // namespace isodel::octree
