#pragma once
// Internal: one value written as its little-endian bytes (binary PLY/STL, VTU's appended data).
// Every supported host is little-endian (dense_volume.cpp checks it on the reader path), so the
// bytes are written as they are in memory.
#include <cstring>
#include <ostream>

namespace isodel::io {

template <typename T>
void put_little_endian(std::ostream& out, T v)
{
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.write(b, sizeof(T));
}

} // namespace isodel::io
