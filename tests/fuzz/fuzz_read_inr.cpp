// Fuzz target: the INRIMAGE-4 reader (src/io/read_inr.cpp). Inputs that start with gzip's
// magic are named *.inr.gz and go through the decompressing path, the others *.inr.
#include "fuzz_volume_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
    return isodel::fuzz::fuzz_volume_bytes(data, size, gz ? ".inr.gz" : ".inr");
}
