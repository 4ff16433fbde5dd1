// Fuzz target: the raw reader (src/io/read_raw.cpp). The layout a user gives on the command
// line comes from the input's first four bytes (dims 0..31 each, a sample type among the four
// known and one unknown, a spacing among 0.5, 1, 2 and the invalid 0); the rest is the file.
#include "fuzz_volume_check.h"

#include <array>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 4) return 0;
    static const std::array<const char*, 5> types{"float32", "uint8", "uint16", "int16", "float64"};
    static const std::array<double, 4> spacings{0.5, 1.0, 2.0, 0.0};
    isodel::RawLayout layout;
    layout.dims = {data[0] % 32, data[1] % 32, data[2] % 32};
    layout.type = types[data[3] % types.size()];
    layout.spacing = spacings[(data[3] / types.size()) % spacings.size()];
    isodel::ReadOptions options;
    options.raw = layout;
    const isodel::fuzz::InputFile file(data + 4, size - 4, ".raw");
    isodel::fuzz::read_and_check_volume(file, options);
    return 0;
}
