// MRC2014 / legacy CCP4 maps (cryo-EM, crystallography). Reference: the MRC2014 specification
// (Cheng et al. 2015, J. Struct. Biol.) and CCP4's map format description.
#include "dense_volume.h"
#include "readers.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace isodel::io {
namespace {

constexpr int kHeaderBytes = 1024;

struct Header {
    const unsigned char* bytes;
    bool swap;
    std::int32_t i(int word) const
    {
        unsigned char b[4];
        std::memcpy(b, bytes + 4 * word, 4);
        if (swap) { std::swap(b[0], b[3]); std::swap(b[1], b[2]); }
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
    }
    float f(int word) const
    {
        std::int32_t v = i(word);
        float x;
        std::memcpy(&x, &v, 4);
        return x;
    }
};

bool plausible(const Header& h)
{
    for (int w = 0; w < 3; ++w)
        if (h.i(w) <= 0 || h.i(w) > (1 << 24)) return false;
    return h.i(3) >= 0 && h.i(3) <= 12;
}

// The machine stamp (bytes 212-213) gives the byte order; writers that leave it blank are
// handled by checking which order makes NC/NR/NS/MODE plausible.
bool file_is_little_endian(const unsigned char* hdr)
{
    const unsigned char s0 = hdr[212], s1 = hdr[213];
    if (s0 == 0x44 && (s1 == 0x41 || s1 == 0x44 || s1 == 0x00)) return true;
    if (s0 == 0x11 && (s1 == 0x11 || s1 == 0x00)) return false;
    const bool host_le = host_is_little_endian();
    Header as_host{hdr, false};
    return plausible(as_host) ? host_le : !host_le;
}

SampleType mode_type(const std::string& path, int mode)
{
    switch (mode) {
    case 0: return SampleType::Int8;
    case 1: return SampleType::Int16;
    case 2: return SampleType::Float32;
    case 6: return SampleType::UInt16;
    default:
        invalid(path, "unsupported MRC mode " + std::to_string(mode) +
                          " (supported: 0 int8, 1 int16, 2 float32, 6 uint16)");
    }
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

} // namespace

Volume read_mrc(const std::string& path, const ReadOptions& opt)
{
    const std::uint64_t fsize = file_size_or_throw(path);
    std::ifstream in(path, std::ios::binary);
    unsigned char hdr[kHeaderBytes];
    if (fsize < kHeaderBytes || !in.read(reinterpret_cast<char*>(hdr), kHeaderBytes))
        io_failure(path, "truncated: an MRC/CCP4 map needs a 1024-byte header, the file has " +
                             std::to_string(fsize) + " bytes");
    if (std::memcmp(hdr + 208, "MAP", 3) != 0) {
        std::string got;
        for (int b = 208; b < 212; ++b) got += (hdr[b] >= 32 && hdr[b] < 127) ? char(hdr[b]) : '?';
        invalid(path, "wrong magic number: bytes 208-211 are '" + got + "', expected 'MAP ' (not an MRC/CCP4 map)");
    }
    const bool host_le = host_is_little_endian();
    const Header h{hdr, file_is_little_endian(hdr) != host_le};

    const std::array<long long, 3> n{h.i(0), h.i(1), h.i(2)};
    const SampleType type = mode_type(path, h.i(3));
    const std::array<int, 3> start{h.i(4), h.i(5), h.i(6)};
    const std::array<int, 3> m{h.i(7), h.i(8), h.i(9)};
    const std::array<double, 3> cell{h.f(10), h.f(11), h.f(12)};
    std::array<double, 3> angle{h.f(13), h.f(14), h.f(15)};
    std::array<int, 3> map{h.i(16), h.i(17), h.i(18)};
    const long long nsymbt = h.i(23);
    const std::array<double, 3> origin{h.f(49), h.f(50), h.f(51)};

    const std::uint64_t count = checked_sample_count(path, n, opt.max_voxels);
    if (map == std::array<int, 3>{0, 0, 0}) map = {1, 2, 3}; // some writers leave it blank
    {
        int seen = 0;
        for (int a : map)
            if (a >= 1 && a <= 3) seen |= 1 << (a - 1);
        if (seen != 7) {
            std::ostringstream msg;
            msg << "invalid axis order MAPC/MAPR/MAPS = " << map[0] << "/" << map[1] << "/" << map[2]
                << " (must be a permutation of 1/2/3)";
            invalid(path, msg.str());
        }
    }
    if (nsymbt < 0) invalid(path, "negative extended header size NSYMBT = " + std::to_string(nsymbt));
    const std::uint64_t expected = kHeaderBytes + std::uint64_t(nsymbt) + count * sample_bytes(type);
    if (fsize < expected)
        io_failure(path, "truncated: the header (" + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                             std::to_string(n[2]) + ", mode " + std::to_string(h.i(3)) + ", NSYMBT " +
                             std::to_string(nsymbt) + ") needs " + std::to_string(expected) +
                             " bytes, the file has " + std::to_string(fsize));
    if (fsize > expected)
        invalid(path, "header dims " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
                          std::to_string(n[2]) + " (mode " + std::to_string(h.i(3)) + ", NSYMBT " +
                          std::to_string(nsymbt) + ") disagree with the file size: expected " +
                          std::to_string(expected) + " bytes, the file has " + std::to_string(fsize));

    // Voxel size along the cell axes a, b, c (= x, y, z) is the cell length over the sampling.
    for (int a = 0; a < 3; ++a)
        if (m[a] <= 0) invalid(path, "invalid sampling MX/MY/MZ = " + std::to_string(m[0]) + "/" +
                                         std::to_string(m[1]) + "/" + std::to_string(m[2]) + " (must be > 0)");
    const std::array<double, 3> step{cell[0] / m[0], cell[1] / m[1], cell[2] / m[2]};
    check_voxel_size(path, step, "cell dimensions / MX,MY,MZ");
    if (angle == std::array<double, 3>{0, 0, 0}) angle = {90, 90, 90};
    for (double a : angle)
        if (!(a > 0 && a < 180)) invalid(path, "invalid cell angle " + std::to_string(a) + " degrees");

    // Fractional -> Cartesian (the crystallographic convention: a along x, b in the xy plane).
    const double ca = std::cos(angle[0] * kDegree), cb = std::cos(angle[1] * kDegree),
                 cg = std::cos(angle[2] * kDegree), sg = std::sin(angle[2] * kDegree);
    const double cy = (ca - cb * cg) / sg;
    const double cz2 = 1.0 - cb * cb - cy * cy;
    if (!(cz2 > 0)) invalid(path, "cell angles do not describe a valid cell");
    // Exactly orthogonal cells get exact zeros, not cos(90 deg) = 6e-17.
    auto clean = [](double v) { return std::abs(v) < 1e-12 ? 0.0 : v; };
    const openvdb::Vec3d av(1, 0, 0), bv(clean(cg), clean(sg), 0), cv(clean(cb), clean(cy), std::sqrt(cz2));
    const openvdb::Vec3d rows[3] = {av * step[0], bv * step[1], cv * step[2]};

    // Sample (0,0,0) of the lattice: the MRC2014 origin field when set, else the start indices
    // (legacy CCP4 maps) on the cell lattice.
    std::array<int, 3> xyz_start{0, 0, 0};
    for (int f = 0; f < 3; ++f) xyz_start[map[f] - 1] = start[f];
    openvdb::Vec3d t(0, 0, 0);
    if (origin[0] != 0 || origin[1] != 0 || origin[2] != 0) {
        for (double o : origin)
            if (!std::isfinite(o)) invalid(path, "non-finite origin in the header");
        t = openvdb::Vec3d(origin[0], origin[1], origin[2]);
    } else {
        for (int a = 0; a < 3; ++a) t += rows[a] * double(xyz_start[a]);
    }
    openvdb::math::Mat4d mat = openvdb::math::Mat4d::identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) mat(r, c) = rows[r][c];
    for (int c = 0; c < 3; ++c) mat(3, c) = t[c];
    openvdb::math::Transform::Ptr xform;
    if (bv == openvdb::Vec3d(0, 1, 0) && cv == openvdb::Vec3d(0, 0, 1))
        xform = openvdb::math::Transform::Ptr(new openvdb::math::Transform(openvdb::math::MapBase::Ptr(
            new openvdb::math::ScaleTranslateMap(openvdb::Vec3d(step[0], step[1], step[2]), t))));
    else
        xform = openvdb::math::Transform::createLinearTransform(mat);

    if (opt.regions) {
        DenseLayout layout;
        layout.file_dims = {int(n[0]), int(n[1]), int(n[2])};
        for (int f = 0; f < 3; ++f) layout.axis_of[f] = map[f] - 1;
        layout.type = type;
        layout.swap = h.swap;
        layout.data_offset = kHeaderBytes + std::uint64_t(nsymbt);
        return read_dense_regions(path, "mrc", layout, *opt.regions, xform);
    }
    DenseBlock block;
    block.file_dims = {int(n[0]), int(n[1]), int(n[2])};
    for (int f = 0; f < 3; ++f) block.axis_of[f] = map[f] - 1;
    block.values.resize(count);
    in.seekg(kHeaderBytes + nsymbt);
    // Read one section at a time: the raw bytes never need a second full-size buffer.
    const std::size_t section = std::size_t(n[0]) * n[1];
    std::vector<unsigned char> buf(section * sample_bytes(type));
    for (long long s = 0; s < n[2]; ++s) {
        if (!in.read(reinterpret_cast<char*>(buf.data()), std::streamsize(buf.size())))
            io_failure(path, "truncated: read failed in section " + std::to_string(s));
        convert_samples(buf.data(), section, type, h.swap, block.values.data() + s * section);
    }
    return make_dense_volume(path, "mrc", block, xform);
}

} // namespace isodel::io
