#pragma once
// The checks every volume reader's result must pass (include/isodel/volume.h's promises), and
// libFuzzer's initialisation hook for the volume targets (one translation unit each).
#include "fuzz_input.h"

#include <isodel/volume.h>

#include <cmath>

namespace isodel::fuzz {

/// Reads \p file as a volume and checks what read_volume promises of a returned volume.
inline void read_and_check_volume(const InputFile& file, const ReadOptions& options = {})
{
    expect_clean_refusal(file.path(), [&] {
        const Volume v = read_volume(file.path(), options);
        require(v.grid != nullptr, "null grid");
        require(!v.lattice.empty(), "empty lattice");
        require(std::isfinite(v.value_min) && std::isfinite(v.value_max) && v.value_min <= v.value_max,
                "value range not finite or inverted");
        require(v.grid->voxelSize()[0] > 0 && std::isfinite(v.grid->voxelSize()[0]), "voxel size");
        // The reported range is the samples' range: a caller checks isovalues against it.
        for (auto it = v.grid->cbeginValueOn(); it; ++it)
            require(*it >= v.value_min && *it <= v.value_max, "sample outside the reported range");
    });
}

/// A whole volume target: the bytes as a file named with \p suffix, read and checked.
inline int fuzz_volume_bytes(const std::uint8_t* data, std::size_t size, const char* suffix)
{
    const InputFile file(data, size, suffix);
    read_and_check_volume(file);
    return 0;
}

} // namespace isodel::fuzz

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    openvdb::initialize();
    return 0;
}
