#include "octree/vdb_tree_layout.h"

#include <openvdb/io/Compression.h>
#include <openvdb/math/Maps.h>
#include <openvdb/openvdb.h>

#include <blosc.h>
#include <zlib.h>

#include <array>
#include <bitset>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

namespace isodel::octree {
namespace {

using Key = std::array<std::int32_t, 3>;

std::string text(const Key& k)
{
    return "(" + std::to_string(k[0]) + ", " + std::to_string(k[1]) + ", " + std::to_string(k[2]) + ")";
}

/// Bytes of util::NodeMask<log2dim> as NodeMask::load reads it.
constexpr std::uint64_t mask_bytes(int log2dim) { return (std::uint64_t(1) << (3 * log2dim)) / 8; }

/// A leaf as the topology pass leaves it: the active count of its value mask (which the buffer
/// pass uses, since a file is seekable: LeafNode::readBuffers seeks over the mask it stores
/// again) and the origin its parents give it.
struct LeafRecord {
    std::uint32_t active = 0;
    Key origin{};
};

class TreeWalk {
public:
    TreeWalk(LayoutReader& r, const VdbTreeKind& kind, const VdbGridStream& stream, const std::string& grid)
        : r_(r), kind_(kind), stream_(stream), grid_(grid)
    {
    }

    /// RootNode::readTopology, then RootNode::readBuffers.
    void tree()
    {
        r_.skip(4, at("the tree's buffer count")); // TreeBase::readTopology
        value(at("the background value"));
        const auto tiles = r_.read<std::uint32_t>(at("the root's tile count"));
        const auto children = r_.read<std::uint32_t>(at("the root's child count"));
        const std::uint64_t tile_bytes = 12 + kind_.value_bytes + 1; // origin, value, active flag
        if (tiles > r_.left() / tile_bytes)
            r_.refuse(at(std::to_string(tiles) + " root tiles cannot fit in the file"));
        // The root's table is a std::map keyed by the stated origin (Coord's order: x, then y,
        // then z); a later tile or child replaces an earlier one of the same key, and only the
        // children left in the table are read in the buffer pass.
        std::map<Key, std::optional<std::vector<LeafRecord>>> table; // a tile: no leaves
        for (std::uint32_t t = 0; t < tiles; ++t) {
            const Key k = key(at("a root tile"));
            value(at("a root tile"));
            flag(at("a root tile's active flag"));
            table[k] = std::nullopt;
        }
        const std::uint64_t child_bytes = 12 + 2 * mask_bytes(5); // origin and two masks at least
        if (children > r_.left() / child_bytes)
            r_.refuse(at(std::to_string(children) + " root children cannot fit in the file"));
        for (std::uint32_t c = 0; c < children; ++c) {
            const Key k = key(at("a root child"));
            std::vector<LeafRecord> leaves;
            // InternalNode's constructor aligns the stated origin to its 4096-voxel span.
            const Key origin{k[0] & ~4095, k[1] & ~4095, k[2] & ~4095};
            internal_topology(5, origin, leaves);
            table[k] = std::move(leaves);
        }
        for (const auto& entry : table)
            if (entry.second)
                for (const LeafRecord& leaf : *entry.second) leaf_buffers(leaf);
    }

private:
    std::string at(const std::string& part) const { return "grid '" + grid_ + "': " + part; }

    Key key(const std::string& what)
    {
        Key k;
        r_.read_bytes(k.data(), sizeof(k), what);
        return k;
    }

    /// OpenVDB reads a bool as the file's byte, and any byte but 0 or 1 is an invalid bool
    /// (undefined behaviour wherever it is then used).
    void flag(const std::string& what)
    {
        const auto b = r_.read<std::uint8_t>(what);
        if (b > 1) r_.refuse(what + ": a bool stored as " + std::to_string(b));
    }
    /// One value of the tree's type; a bool tree's (bool and mask grids) must be 0 or 1.
    void value(const std::string& what)
    {
        if (bool_tree())
            flag(what);
        else
            r_.skip(kind_.value_bytes, what);
    }
    bool bool_tree() const { return kind_.leaf != VdbTreeKind::Leaf::Values; }
    void check_bools(const std::vector<unsigned char>& bytes, const std::string& what) const
    {
        for (unsigned char b : bytes)
            if (b > 1) r_.refuse(what + ": a bool stored as " + std::to_string(b));
    }

    /// A NodeMask<log2dim> as NodeMask::load reads it.
    std::vector<std::uint64_t> mask(int log2dim, const std::string& what)
    {
        std::vector<std::uint64_t> words(mask_bytes(log2dim) / 8);
        r_.read_bytes(words.data(), mask_bytes(log2dim), what);
        return words;
    }
    static std::uint32_t count_on(const std::vector<std::uint64_t>& words)
    {
        std::uint32_t n = 0;
        for (std::uint64_t w : words) n += std::uint32_t(std::bitset<64>(w).count());
        return n;
    }

    /// InternalNode<_, log2dim>::readTopology: child mask, value mask, the tile values, then each
    /// child in the child mask's order. The children of the lowest internal level are leaves,
    /// whose topology is one 512-bit mask.
    void internal_topology(int log2dim, const Key& origin, std::vector<LeafRecord>& leaves)
    {
        const auto child_mask = mask(log2dim, at("an internal node's child mask"));
        const auto value_mask = mask(log2dim, at("an internal node's value mask"));
        values(std::uint64_t(1) << (3 * log2dim), count_on(value_mask), log2dim, "an internal node's values");
        const int dim = 1 << log2dim;
        const int child_total = log2dim == 5 ? 7 : 3; // log2 of a child's span in voxels
        for (std::uint32_t n = 0; n < (std::uint32_t(1) << (3 * log2dim)); ++n) {
            if (!((child_mask[n / 64] >> (n % 64)) & 1)) continue;
            // InternalNode::offsetToGlobalCoord.
            const Key local{std::int32_t(n >> (2 * log2dim)), std::int32_t((n >> log2dim) & (dim - 1)),
                            std::int32_t(n & (dim - 1))};
            const Key child{origin[0] + (local[0] << child_total), origin[1] + (local[1] << child_total),
                            origin[2] + (local[2] << child_total)};
            if (log2dim == 5) {
                internal_topology(4, child, leaves);
            } else {
                // LeafNode*::readTopology: the value mask (a mask leaf's data mask).
                leaves.push_back({count_on(mask(3, at("a leaf's mask"))), child});
            }
        }
    }

    /// LeafNode*::readBuffers of a seekable stream.
    void leaf_buffers(const LeafRecord& leaf)
    {
        r_.skip(mask_bytes(3), at("a leaf's mask"));
        if (kind_.leaf == VdbTreeKind::Leaf::Values) {
            values(512, leaf.active, 3, "a leaf's values");
            return;
        }
        // Bool and mask leaves store their origin again, and OpenVDB takes it as read: a leaf
        // placed elsewhere than its parents say would break the tree's invariants.
        const Key stored = key(at("a leaf's origin"));
        if (stored != leaf.origin)
            r_.refuse(at("a leaf stores origin " + text(stored) + ", its parents place it at " + text(leaf.origin)));
        if (kind_.leaf == VdbTreeKind::Leaf::Bool) r_.skip(mask_bytes(3), at("a leaf's values"));
    }

    /// io::readCompressedValues for a node of \p count values, \p active of them on in its value
    /// mask: a flag byte, the inactive values and selection mask it announces, then one chunk.
    void values(std::uint64_t count, std::uint32_t active, int log2dim, const char* part)
    {
        using namespace openvdb::io;
        const std::string what = at(part);
        const auto meta = r_.read<std::int8_t>(what);
        if (meta == NO_MASK_AND_ONE_INACTIVE_VAL || meta == MASK_AND_ONE_INACTIVE_VAL ||
            meta == MASK_AND_TWO_INACTIVE_VALS)
            value(what); // always at full precision
        if (meta == MASK_AND_TWO_INACTIVE_VALS) value(what);
        if (meta == MASK_AND_NO_INACTIVE_VALS || meta == MASK_AND_ONE_INACTIVE_VAL || meta == MASK_AND_TWO_INACTIVE_VALS)
            r_.skip(mask_bytes(log2dim), what);
        const bool only_active = (stream_.compression & COMPRESS_ACTIVE_MASK) && meta != NO_MASK_AND_ALL_VALS;
        const std::uint64_t n = only_active ? active : count;
        const bool half = stream_.half && kind_.half_bytes > 0;
        if (half && n == 0) return; // HalfReader reads nothing for no values
        chunk(n * (half ? kind_.half_bytes : kind_.value_bytes), what);
    }

    /// io::readData's chunk of \p bytes: bloscFromStream, unzipFromStream, or the bytes as such.
    /// A bool tree's values are read (and decompressed: at most a node's 32768 bytes) and checked.
    void chunk(std::uint64_t bytes, const std::string& what)
    {
        using namespace openvdb::io;
        if (!(stream_.compression & (COMPRESS_BLOSC | COMPRESS_ZIP))) {
            raw(bytes, what);
            return;
        }
        // A length of at most zero announces -length uncompressed bytes, which OpenVDB reads
        // into the node's buffer before it compares the two.
        const auto stated = r_.read<std::int64_t>(what);
        if (stated <= 0) {
            if (stated == std::numeric_limits<std::int64_t>::min() || std::uint64_t(-stated) != bytes)
                r_.refuse(what + ": an uncompressed chunk states " + std::to_string(stated) + " bytes, the node holds " +
                          std::to_string(bytes));
            raw(bytes, what);
            return;
        }
        r_.need(std::uint64_t(stated), what);
        if (stream_.compression & COMPRESS_BLOSC)
            blosc_chunk(std::uint64_t(stated), bytes, what);
        else if (bool_tree())
            check_bools(unzip(std::uint64_t(stated), bytes, what), what);
        else
            r_.skip(std::uint64_t(stated), what); // zlib's uncompress is told both sizes
    }

    void raw(std::uint64_t bytes, const std::string& what)
    {
        if (!bool_tree()) {
            r_.skip(bytes, what);
            return;
        }
        std::vector<unsigned char> values(bytes);
        r_.read_bytes(values.data(), bytes, what);
        check_bools(values, what);
    }

    /// Blosc trusts its header: the uncompressed size must be the node's, and the buffer must
    /// lie within the chunk (blosc_fits).
    void blosc_chunk(std::uint64_t stated, std::uint64_t bytes, const std::string& what)
    {
        constexpr std::uint64_t kHeader = 16;
        if (stated < kHeader) r_.refuse(what + ": a Blosc chunk shorter than its header");
        std::vector<unsigned char> chunk(bool_tree() ? stated : kHeader);
        r_.read_bytes(chunk.data(), kHeader, what);
        const BloscHeader h = blosc_header(chunk.data());
        if (h.uncompressed != bytes || !blosc_fits(h, stated))
            r_.refuse(what + ": a Blosc chunk of " + std::to_string(stated) + " bytes states " +
                      std::to_string(h.compressed) + " compressed and " + std::to_string(h.uncompressed) +
                      " uncompressed bytes, the node holds " + std::to_string(bytes));
        if (!bool_tree()) {
            r_.skip(stated - kHeader, what);
            return;
        }
        r_.read_bytes(chunk.data() + kHeader, stated - kHeader, what);
        std::vector<unsigned char> values(bytes);
        if (blosc_decompress_ctx(chunk.data(), values.data(), bytes, 1) != int(bytes))
            r_.refuse(what + ": a Blosc chunk that does not decompress to the node's " + std::to_string(bytes) + " bytes");
        check_bools(values, what);
    }

    std::vector<unsigned char> unzip(std::uint64_t stated, std::uint64_t bytes, const std::string& what)
    {
        std::vector<unsigned char> chunk(stated), values(bytes);
        r_.read_bytes(chunk.data(), stated, what);
        uLongf out = uLongf(bytes);
        if (uncompress(values.data(), &out, chunk.data(), uLong(stated)) != Z_OK || out != bytes)
            r_.refuse(what + ": a Zip chunk that does not decompress to the node's " + std::to_string(bytes) + " bytes");
        return values;
    }

    LayoutReader& r_;
    const VdbTreeKind& kind_;
    const VdbGridStream& stream_;
    const std::string& grid_;
};

} // namespace

std::optional<VdbTreeKind> vdb_tree_kind(const std::string& grid_type)
{
    using Leaf = VdbTreeKind::Leaf;
    static const std::map<std::string, VdbTreeKind> kinds{
        {openvdb::FloatGrid::gridType(), {Leaf::Values, sizeof(float), 2}},
        {openvdb::DoubleGrid::gridType(), {Leaf::Values, sizeof(double), 2}},
        {openvdb::Int32Grid::gridType(), {Leaf::Values, sizeof(std::int32_t), 0}},
        {openvdb::Int64Grid::gridType(), {Leaf::Values, sizeof(std::int64_t), 0}},
        {openvdb::Vec3SGrid::gridType(), {Leaf::Values, sizeof(openvdb::Vec3s), 6}},
        {openvdb::Vec3DGrid::gridType(), {Leaf::Values, sizeof(openvdb::Vec3d), 6}},
        {openvdb::Vec3IGrid::gridType(), {Leaf::Values, sizeof(openvdb::Vec3i), 0}},
        {openvdb::BoolGrid::gridType(), {Leaf::Bool, sizeof(bool), 0}},
        {openvdb::MaskGrid::gridType(), {Leaf::Mask, sizeof(bool), 0}},
    };
    const auto it = kinds.find(grid_type);
    if (it == kinds.end()) return std::nullopt;
    return it->second;
}

void skip_vdb_transform(LayoutReader& r, const std::string& grid)
{
    namespace m = openvdb::math;
    const std::string what = "grid '" + grid + "': its transform";
    // Fixed-size maps: Mat4d (128 bytes) or Vec3d fields (24 bytes each), as each Map::read reads.
    static const std::map<std::string, std::uint64_t> fixed{
        {m::AffineMap::mapType(), 128},          {m::UnitaryMap::mapType(), 128},
        {m::ScaleMap::mapType(), 5 * 24},        {m::UniformScaleMap::mapType(), 5 * 24},
        {m::TranslationMap::mapType(), 24},      {m::ScaleTranslateMap::mapType(), 6 * 24},
        {m::UniformScaleTranslateMap::mapType(), 6 * 24},
    };
    std::string type = r.string(what);
    if (type == m::NonlinearFrustumMap::mapType()) {
        r.skip(48 + 8 + 8, what); // bounding box, taper, depth
        type = r.string(what);    // then its second, linear map
    }
    const auto it = fixed.find(type);
    if (it == fixed.end()) r.refuse(what + " has map type '" + type + "', which OpenVDB does not read");
    r.skip(it->second, what);
}

void skip_vdb_tree(LayoutReader& r, const VdbTreeKind& kind, const VdbGridStream& stream, const std::string& grid)
{
    TreeWalk(r, kind, stream, grid).tree();
}

} // namespace isodel::octree
