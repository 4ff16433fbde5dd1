#pragma once
// Internal: a check of an OpenVDB file's layout before OpenVDB reads it. OpenVDB's reader trusts
// the sizes a file states: a string length, a metadata size, a grid's offsets. In a cut or
// corrupted file they are arbitrary, and OpenVDB allocates what they claim (up to 2^63 bytes)
// before it notices the file ends. This walk reads the header, the file metadata, every grid
// descriptor and every grid's own metadata as OpenVDB does (openvdb/io/Archive.cc, File.cc,
// GridDescriptor.cc, MetaMap.cc), and refuses the file when a stated size or offset does not fit
// in it. The tree data after that (node masks, compressed buffers) is not walked: a size stated
// there that the machine cannot allocate is OpenVDB's std::bad_alloc, which the readers report.
#include <cstdint>
#include <string>

namespace isodel::octree {

/// Throws isodel::InvalidInput ("<path>: not a readable OpenVDB file: <why>") when the file's
/// header, metadata or grid descriptors state a size or an offset beyond the file's end, and
/// isodel::IoError when it cannot be opened.
void check_vdb_file_layout(const std::string& path);

} // namespace isodel::octree
