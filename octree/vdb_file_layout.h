#pragma once
// Internal: a check of an OpenVDB file before OpenVDB reads it. OpenVDB's reader trusts the
// sizes a file states: a string length, a metadata size, a grid's offsets, a node's chunk
// length. In a cut or corrupted file they are arbitrary, and OpenVDB allocates what they claim
// (up to 2^63 bytes) before it notices the file ends, or reads a chunk of the stated length into
// a buffer of the node's size (a heap overflow). This walk reads the header, the file metadata,
// every grid descriptor, and each grid's metadata, transform and tree as OpenVDB does
// (openvdb/io/Archive.cc, File.cc, GridDescriptor.cc, MetaMap.cc; the tree in vdb_tree_layout.h),
// and refuses the file when a stated size or offset does not fit.
#include <cstdint>
#include <string>

namespace isodel::octree {

/// Throws isodel::InvalidInput ("<path>: not a readable OpenVDB file: <why>") when the file's
/// header, metadata, grid descriptors or the data of a grid whose type vdb_grid_type_checked
/// accepts state a size or an offset that does not fit, and isodel::IoError when it cannot be
/// opened. In a file without grid offsets (written as a stream, read whole by OpenVDB) every
/// grid must be of such a type.
void check_vdb_file_layout(const std::string& path);

/// Whether check_vdb_file_layout walks the data of grids of \p grid_type (as GridBase::type()
/// names it): OpenVDB's standard float, double, int32, int64, vec3s, vec3d, vec3i, bool and mask
/// grids. Readers ask OpenVDB for no grid of another type.
bool vdb_grid_type_checked(const std::string& grid_type);

} // namespace isodel::octree
