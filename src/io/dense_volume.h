#pragma once
// Internal: pieces shared by the dense-format readers (MRC, INR, raw) so that every format
// refuses bad input with the same checks and the same "<path>: <problem>" messages.
#include <isodel/volume.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace isodel::io {

/// Throws InvalidInput("<path>: <what>").
[[noreturn]] void invalid(const std::string& path, const std::string& what);
/// Throws IoError("<path>: <what>").
[[noreturn]] void io_failure(const std::string& path, const std::string& what);

/// Size of \p path in bytes; IoError naming the path (and errno text) if it cannot be opened.
std::uint64_t file_size_or_throw(const std::string& path);

/// Refuses non-positive dims and lattices over \p max_voxels, before anything is allocated.
/// \return the number of samples.
std::uint64_t checked_sample_count(const std::string& path, const std::array<long long, 3>& dims,
                                   std::uint64_t max_voxels);

/// Refuses zero, negative or non-finite voxel sizes (\p what names the header field).
void check_voxel_size(const std::string& path, const std::array<double, 3>& size, const char* what);

/// Sample type of a dense file, and whether its bytes need swapping to host order.
enum class SampleType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };
int sample_bytes(SampleType t);

/// Converts \p count samples of type \p t from \p bytes (file order) to float.
void convert_samples(const unsigned char* bytes, std::size_t count, SampleType t, bool swap,
                     float* out);

/// True when the host is little-endian (every supported build machine is, but say why it matters:
/// the file's byte order is compared with it to decide whether to swap).
bool host_is_little_endian();

/// A dense block of samples in file order: the fastest axis first.
/// \p axis_of[f] tells which lattice axis (0=x, 1=y, 2=z) file axis f (0 = fastest) runs along.
struct DenseBlock {
    std::array<int, 3> file_dims{0, 0, 0};
    std::array<int, 3> axis_of{0, 1, 2};
    std::vector<float> values;
};

/// Builds the Volume: every sample an active voxel at index (i,j,k), i along x from 0;
/// refuses NaN/Inf naming the first offending index; computes the value range.
Volume make_dense_volume(const std::string& path, const std::string& format, const DenseBlock& block,
                         openvdb::math::Transform::Ptr transform);

/// Where a dense file's samples are: \p file_dims samples in file order (the fastest axis first,
/// file axis f along lattice axis axis_of[f]) of \p type from byte \p data_offset on.
struct DenseLayout {
    std::array<int, 3> file_dims{0, 0, 0};
    std::array<int, 3> axis_of{0, 1, 2};
    SampleType type = SampleType::Float32;
    bool swap = false;
    std::uint64_t data_offset = 0;
};

/// ReadOptions::regions for a dense file: reads the samples of each box (clipped to the lattice)
/// run by run along the file's fastest axis, each run at its offset; refuses NaN/Inf like
/// make_dense_volume. The Volume's lattice is the whole file's.
Volume read_dense_regions(const std::string& path, const std::string& format, const DenseLayout& layout,
                          const std::vector<openvdb::CoordBBox>& regions, openvdb::math::Transform::Ptr transform);

/// Refuses a transform without a finite, positive voxel size and a finite origin, and a
/// non-finite background (every reader's grid).
void check_transform_and_background(const Volume& vol);

/// Fills lattice, value range (and checks finiteness) of a Volume whose grid is set.
void finish_volume(Volume& vol);

} // namespace isodel::io
