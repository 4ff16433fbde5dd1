// Fuzz target: the MRC/CCP4 reader (src/io/read_mrc.cpp) on any bytes named *.mrc.
#include "fuzz_volume_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    return isodel::fuzz::fuzz_volume_bytes(data, size, ".mrc");
}
