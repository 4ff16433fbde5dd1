// Fuzz target: the .vdb reader (src/io/read_vdb.cpp, through OpenVDB's file reader), which also
// recognises isodel's adaptive files by their metadata.
#include "fuzz_volume_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return isodel::fuzz::fuzz_volume_bytes(data, size, ".vdb");
}
