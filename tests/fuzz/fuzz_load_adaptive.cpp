// Fuzz target: isodel's adaptive .vdb files (`isodel decimate`'s output; the levels and their
// metadata, octree/adaptive_vdb_format.cpp). An accepted file is resampled, as `isodel mesh`
// does before meshing: metadata the loader lets through must not break the adaptive grid.
#include "fuzz_input.h"

#include <isodel/adaptive.h>

#include <openvdb/openvdb.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    openvdb::initialize();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const isodel::fuzz::InputFile file(data, size, ".vdb");
    isodel::fuzz::expect_clean_refusal(file.path(), [&] {
        const isodel::AdaptiveVolume v = isodel::load_adaptive(file.path());
        isodel::fuzz::require(v.samples != nullptr, "adaptive volume without samples");
        isodel::fuzz::require(v.k >= 1, "level difference bound below 1");
        // Resampling is linear in the domain: small domains only, so one execution stays short.
        if (v.domain.volume() <= (1u << 18)) isodel::fuzz::require(isodel::resample(v) != nullptr, "resample");
    });
    return 0;
}
