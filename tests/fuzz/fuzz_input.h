#pragma once
// What every fuzz target shares: the input as a file, and the readers' contract.
//
// The readers take paths (they compare header sizes with the file's size, stream, and dispatch
// on the extension), so each input is written to a temporary file of this process first.
// The contract checked on every input: a reader either returns, or throws isodel::Error whose
// message names the file. Any other exception escapes to libFuzzer, which reports it as a
// crash; a message without the file's name aborts here.
#include <isodel/errors.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace isodel::fuzz {

class InputFile {
public:
    InputFile(const std::uint8_t* data, std::size_t size, const std::string& suffix)
        : path_(directory() + "/isodel_fuzz_" + std::to_string(::getpid()) + suffix)
    {
        std::ofstream out(path_, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    ~InputFile() { std::remove(path_.c_str()); }
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;
    const std::string& path() const { return path_; }

private:
    // /dev/shm when there is one: a file per execution, hundreds of thousands of them.
    static std::string directory() { return ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp"; }
    std::string path_;
};

/// Runs \p read; a refusal must be an isodel::Error naming \p path.
template <class Read>
void expect_clean_refusal(const std::string& path, Read&& read)
{
    try {
        read();
    } catch (const isodel::Error& e) {
        if (std::string(e.what()).find(path) == std::string::npos) {
            std::fprintf(stderr, "refusal without the file's name: %s\n", e.what());
            std::abort();
        }
    }
}

/// Aborts with \p what when \p ok is false: a reader returned something a caller cannot use.
inline void require(bool ok, const char* what)
{
    if (!ok) {
        std::fprintf(stderr, "reader returned an unusable result: %s\n", what);
        std::abort();
    }
}

} // namespace isodel::fuzz
