// Headerless raw volumes: the layout comes from the command line (--raw-dims/--raw-type/
// --raw-spacing), so the only consistency check possible is the file size.
#include "dense_volume.h"
#include "readers.h"
#include "atomic_file.h"

#include <fstream>

namespace isodel::io {

Volume read_raw(const std::string& path, const ReadOptions& opt)
{
    const std::uint64_t fsize = file_size_or_throw(path);
    if (!opt.raw)
        invalid(path, "unknown extension '" + extension_of(path) +
                          "' (expected .vdb, .mrc, .map, .ccp4, .inr, .inr.gz; for raw volumes give --raw-dims)");
    const RawLayout& L = *opt.raw;
    SampleType st;
    if (L.type == "float32") st = SampleType::Float32;
    else if (L.type == "uint8") st = SampleType::UInt8;
    else if (L.type == "uint16") st = SampleType::UInt16;
    else if (L.type == "int16") st = SampleType::Int16;
    else invalid(path, "unknown raw sample type '" + L.type + "' (float32, uint8, uint16 or int16)");
    const std::array<long long, 3> dims{L.dims[0], L.dims[1], L.dims[2]};
    const std::uint64_t count = checked_sample_count(path, dims, opt.max_voxels);
    check_voxel_size(path, {L.spacing, L.spacing, L.spacing}, "--raw-spacing");
    const std::uint64_t expected = count * sample_bytes(st);
    if (fsize < expected)
        io_failure(path, "truncated: " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                             std::to_string(dims[2]) + " " + L.type + " samples need " + std::to_string(expected) +
                             " bytes, the file has " + std::to_string(fsize));
    if (fsize > expected)
        invalid(path, "dims " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                          std::to_string(dims[2]) + " " + L.type + " disagree with the file size: expected " +
                          std::to_string(expected) + " bytes, the file has " + std::to_string(fsize));

    auto xform = openvdb::math::Transform::createLinearTransform(L.spacing);
    if (opt.regions) {
        DenseLayout layout;
        layout.file_dims = {L.dims[0], L.dims[1], L.dims[2]};
        layout.type = st;
        layout.swap = !host_is_little_endian(); // raw volumes are little-endian (RawLayout)
        return read_dense_regions(path, "raw", layout, *opt.regions, xform);
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> raw(expected);
    if (!in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(expected)))
        io_failure(path, "truncated: read failed");
    DenseBlock block;
    block.file_dims = {L.dims[0], L.dims[1], L.dims[2]};
    block.values.resize(count);
    // Raw volumes are little-endian by definition (see RawLayout).
    convert_samples(raw.data(), count, st, !host_is_little_endian(), block.values.data());
    raw = {};
    return make_dense_volume(path, "raw", block, xform);
}

} // namespace isodel::io
