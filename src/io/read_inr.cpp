// INRIMAGE-4 (.inr, .inr.gz), the image format of CGAL's Mesh_3 examples: a text header padded to
// a multiple of 256 bytes, then raw samples, x fastest. zlib's gzread reads plain and gzipped
// files alike, so one code path serves both.
#include "dense_volume.h"
#include "readers.h"

#include <map>
#include <memory>
#include <sstream>
#include <zlib.h>

namespace isodel::io {
namespace {

constexpr int kBlock = 256;
constexpr int kMaxHeaderBlocks = 64;

struct GzCloser {
    void operator()(gzFile_s* f) const { if (f) gzclose(f); }
};
using GzPtr = std::unique_ptr<gzFile_s, GzCloser>;

// Reads up to n bytes; returns how many were read (less only at end of file).
std::size_t read_some(const std::string& path, gzFile f, unsigned char* dst, std::size_t n)
{
    std::size_t got = 0;
    while (got < n) {
        const unsigned chunk = unsigned(std::min<std::size_t>(n - got, 1u << 30));
        const int r = gzread(f, dst + got, chunk);
        if (r < 0) {
            int err = 0;
            const char* msg = gzerror(f, &err);
            io_failure(path, std::string("read error: ") + (msg ? msg : "zlib error"));
        }
        if (r == 0) break;
        got += std::size_t(r);
    }
    return got;
}

std::string trim(std::string s)
{
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.pop_back();
    std::size_t b = 0;
    while (b < s.size() && (s[b] == ' ' || s[b] == '\t')) ++b;
    return s.substr(b);
}

long long to_int(const std::string& path, const std::map<std::string, std::string>& kv, const std::string& key,
                 long long fallback, bool required)
{
    auto it = kv.find(key);
    if (it == kv.end()) {
        if (required) invalid(path, "header has no " + key + " field");
        return fallback;
    }
    try {
        std::size_t used = 0;
        long long v = std::stoll(it->second, &used);
        return v;
    } catch (const std::exception&) {
        invalid(path, "header field " + key + "=" + it->second + " is not an integer");
    }
}

double to_double(const std::string& path, const std::map<std::string, std::string>& kv, const std::string& key,
                 double fallback)
{
    auto it = kv.find(key);
    if (it == kv.end()) return fallback;
    try {
        return std::stod(it->second);
    } catch (const std::exception&) {
        invalid(path, "header field " + key + "=" + it->second + " is not a number");
    }
}

} // namespace

Volume read_inr(const std::string& path, const ReadOptions& opt)
{
    const std::uint64_t fsize = file_size_or_throw(path);
    GzPtr f(gzopen(path.c_str(), "rb"));
    if (!f) io_failure(path, "cannot open");

    std::string header;
    unsigned char block[kBlock];
    for (int b = 0; b < kMaxHeaderBlocks; ++b) {
        const std::size_t got = read_some(path, f.get(), block, kBlock);
        header.append(reinterpret_cast<const char*>(block), got);
        if (b == 0 && header.compare(0, 13, "#INRIMAGE-4#{") != 0)
            invalid(path, "wrong magic number: an INRIMAGE file starts with '#INRIMAGE-4#{'");
        if (got < kBlock)
            io_failure(path, "truncated header: " + std::to_string(header.size()) +
                                 " bytes, a multiple of 256 ending in '##}' expected");
        if (header.find("##}") != std::string::npos) break;
    }
    if (header.find("##}") == std::string::npos) invalid(path, "header has no '##}' terminator");

    std::map<std::string, std::string> kv;
    std::istringstream lines(header.substr(0, header.find("##}")));
    for (std::string line; std::getline(lines, line);) {
        const auto eq = line.find('=');
        if (eq == std::string::npos || line[0] == '#') continue;
        kv[trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
    }
    const std::array<long long, 3> dims{to_int(path, kv, "XDIM", 0, true), to_int(path, kv, "YDIM", 0, true),
                                        to_int(path, kv, "ZDIM", 0, true)};
    const long long vdim = to_int(path, kv, "VDIM", 1, false);
    if (vdim != 1)
        invalid(path, "non-scalar image: VDIM=" + std::to_string(vdim) + " (only scalar images, VDIM=1, are read)");
    const std::uint64_t count = checked_sample_count(path, dims, opt.max_voxels);

    const std::string type = kv.count("TYPE") ? kv["TYPE"] : "";
    const long long bits = to_int(path, kv, "PIXSIZE", 0, true); // "32 bits": stoll stops at the space
    SampleType st;
    if (type == "float" && bits == 32) st = SampleType::Float32;
    else if (type == "float" && bits == 64) st = SampleType::Float64;
    else if (type == "unsigned fixed" && bits == 8) st = SampleType::UInt8;
    else if (type == "unsigned fixed" && bits == 16) st = SampleType::UInt16;
    else if (type == "unsigned fixed" && bits == 32) st = SampleType::UInt32;
    else if (type == "unsigned fixed" && bits == 64) st = SampleType::UInt64;
    else if (type == "signed fixed" && bits == 8) st = SampleType::Int8;
    else if (type == "signed fixed" && bits == 16) st = SampleType::Int16;
    else if (type == "signed fixed" && bits == 32) st = SampleType::Int32;
    else if (type == "signed fixed" && bits == 64) st = SampleType::Int64;
    else invalid(path, "unsupported sample type TYPE=" + type + " PIXSIZE=" + std::to_string(bits) + " bits");

    const std::string cpu = kv.count("CPU") ? kv["CPU"] : "decm";
    bool little;
    if (cpu == "decm" || cpu == "alpha" || cpu == "pc") little = true;
    else if (cpu == "sun" || cpu == "sgi") little = false;
    else invalid(path, "unknown byte order CPU=" + cpu + " (expected decm, alpha, pc, sun or sgi)");

    const std::array<double, 3> vox{to_double(path, kv, "VX", 1.0), to_double(path, kv, "VY", 1.0),
                                    to_double(path, kv, "VZ", 1.0)};
    check_voxel_size(path, vox, "VX/VY/VZ");
    const openvdb::Vec3d origin(to_double(path, kv, "TX", 0.0), to_double(path, kv, "TY", 0.0),
                                to_double(path, kv, "TZ", 0.0));

    const std::uint64_t data_bytes = count * sample_bytes(st);
    const bool gz = gzdirect(f.get()) == 0;
    // A plain file's size is known up front: refuse a mismatch before allocating.
    if (!gz && fsize != header.size() + data_bytes) {
        const std::uint64_t expected = header.size() + data_bytes;
        if (fsize < expected)
            io_failure(path, "truncated: the header (" + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                                 " x " + std::to_string(dims[2]) + ", " + std::to_string(bits) +
                                 "-bit samples) needs " + std::to_string(expected) + " bytes, the file has " +
                                 std::to_string(fsize));
        invalid(path, "header dims " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                          std::to_string(dims[2]) + " disagree with the file size: expected " +
                          std::to_string(expected) + " bytes, the file has " + std::to_string(fsize));
    }

    std::vector<unsigned char> raw(data_bytes);
    const std::size_t got = read_some(path, f.get(), raw.data(), raw.size());
    if (got < data_bytes)
        io_failure(path, "truncated: the header announces " + std::to_string(data_bytes) +
                             " data bytes, only " + std::to_string(got) + " follow it");
    std::uint64_t extra = 0;
    for (std::size_t r; (r = read_some(path, f.get(), block, kBlock)) > 0;) extra += r;
    if (extra > 0)
        invalid(path, "header dims disagree with the data size: expected " + std::to_string(data_bytes) +
                          " data bytes, the (decompressed) file has " + std::to_string(data_bytes + extra));

    DenseBlock blockv;
    blockv.file_dims = {int(dims[0]), int(dims[1]), int(dims[2])};
    blockv.values.resize(count);
    convert_samples(raw.data(), count, st, little != host_is_little_endian(), blockv.values.data());
    raw = {};
    auto xform = openvdb::math::Transform::Ptr(new openvdb::math::Transform(openvdb::math::MapBase::Ptr(
        new openvdb::math::ScaleTranslateMap(openvdb::Vec3d(vox[0], vox[1], vox[2]), origin))));
    return make_dense_volume(path, "inr", blockv, xform);
}

} // namespace isodel::io
