#pragma once
// Internal: the walk of one grid's transform and tree data, the part of an OpenVDB file after the
// grid's metadata (vdb_file_layout.h walks what comes before). OpenVDB's node readers trust what
// the file states: io::bloscFromStream and io::unzipFromStream read an uncompressed chunk of the
// length the file gives into a buffer of the node's size and compare the two only afterwards (a
// heap overflow), Blosc decompresses by the sizes in its own header, and a root node's tile count
// drives a loop of up to 2^32 reads. This walk reads the tree as Tree::readTopology and
// Tree::readBuffers do (openvdb/tree/RootNode.h, InternalNode.h, LeafNode*.h, io/Compression.h of
// OpenVDB 10) and refuses the file when a chunk's stated length is not the one its node needs, or
// a count or a chunk does not fit in the file.
#include "octree/vdb_layout_reader.h"

#include <cstdint>
#include <optional>
#include <string>

namespace isodel::octree {

/// How a grid type's tree stores its leaves and values.
struct VdbTreeKind {
    enum class Leaf {
        Values, ///< a value mask, then the values (LeafNode<T>)
        Bool,   ///< a value mask, the origin and a bit mask of values (LeafNode<bool>)
        Mask,   ///< a bit mask and the origin (LeafNode<ValueMask>)
    };
    Leaf leaf = Leaf::Values;
    std::uint32_t value_bytes = 0; ///< sizeof the tree's ValueType
    std::uint32_t half_bytes = 0;  ///< bytes of a value saved as half floats; 0: never saved so
};

/// The tree kind of \p grid_type (a type name as OpenVDB writes it, without the "_HalfFloat"
/// suffix), for the standard 5-4-3 trees of OpenVDB's float, double, int32, int64, vec3s, vec3d,
/// vec3i, bool and mask grids; std::nullopt for any other type, whose data the walk cannot check.
std::optional<VdbTreeKind> vdb_tree_kind(const std::string& grid_type);

/// The stream state OpenVDB's node readers consult for one grid.
struct VdbGridStream {
    std::uint32_t compression = 0; ///< the grid's io::COMPRESS_* flags
    bool half = false;             ///< the grid's "is_saved_as_half_float" metadata
};

/// Walks a math::Transform as Transform::read does (file format 222 and later): the map's type
/// name, then its fixed-size fields (a frustum's second map once).
void skip_vdb_transform(LayoutReader& r, const std::string& grid);

/// Walks a grid's tree as Tree::readTopology, then Tree::readBuffers do for a file read whole (no
/// delayed loading) and refuses, naming \p grid, any stated size that does not fit.
void skip_vdb_tree(LayoutReader& r, const VdbTreeKind& kind, const VdbGridStream& stream, const std::string& grid);

} // namespace isodel::octree
