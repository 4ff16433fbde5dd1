#include "dense_volume.h"

#include <isodel/errors.h>

#include <cerrno>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <sys/stat.h>

namespace isodel::io {

void invalid(const std::string& path, const std::string& what) { throw InvalidInput(path + ": " + what); }
void io_failure(const std::string& path, const std::string& what) { throw IoError(path + ": " + what); }

std::uint64_t file_size_or_throw(const std::string& path)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) io_failure(path, std::string("cannot open: ") + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) io_failure(path, "cannot open: is a directory");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) io_failure(path, std::string("cannot open: ") + std::strerror(errno));
    return static_cast<std::uint64_t>(st.st_size);
}

std::uint64_t checked_sample_count(const std::string& path, const std::array<long long, 3>& dims,
                                   std::uint64_t max_voxels)
{
    std::ostringstream d;
    d << dims[0] << " x " << dims[1] << " x " << dims[2];
    for (long long n : dims)
        if (n <= 0) invalid(path, "invalid dimensions " + d.str() + " (every dimension must be >= 1)");
    // Multiply in long double first: three int32 dims can overflow 64 bits only in theory, but a
    // corrupt header must never make the cap check wrap around.
    long double count = static_cast<long double>(dims[0]) * dims[1] * dims[2];
    if (count > static_cast<long double>(max_voxels)) {
        std::ostringstream msg;
        msg << "header announces " << d.str() << " = " << static_cast<double>(count)
            << " samples, more than the limit of " << max_voxels
            << " (set ISODEL_MAX_VOXELS to raise it)";
        invalid(path, msg.str());
    }
    // OpenVDB coordinates are int32: the lattice must fit.
    for (long long n : dims)
        if (n > std::numeric_limits<int>::max() / 2) invalid(path, "dimensions " + d.str() + " are too large");
    return static_cast<std::uint64_t>(count);
}

void check_voxel_size(const std::string& path, const std::array<double, 3>& size, const char* what)
{
    for (double s : size) {
        if (!(std::isfinite(s) && s > 0)) {
            std::ostringstream msg;
            msg << "invalid voxel size (" << size[0] << ", " << size[1] << ", " << size[2] << ") from "
                << what << ": every component must be finite and > 0";
            invalid(path, msg.str());
        }
    }
}

int sample_bytes(SampleType t)
{
    switch (t) {
    case SampleType::Int8: case SampleType::UInt8: return 1;
    case SampleType::Int16: case SampleType::UInt16: return 2;
    case SampleType::Int32: case SampleType::UInt32: case SampleType::Float32: return 4;
    default: return 8;
    }
}

bool host_is_little_endian()
{
    const std::uint16_t one = 1;
    unsigned char b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}

namespace {
template <typename T>
void convert_as(const unsigned char* bytes, std::size_t count, bool swap, float* out)
{
    unsigned char tmp[sizeof(T)];
    for (std::size_t n = 0; n < count; ++n) {
        const unsigned char* src = bytes + n * sizeof(T);
        if (swap) {
            for (std::size_t b = 0; b < sizeof(T); ++b) tmp[b] = src[sizeof(T) - 1 - b];
            src = tmp;
        }
        T v;
        std::memcpy(&v, src, sizeof(T));
        out[n] = static_cast<float>(v);
    }
}
} // namespace

void convert_samples(const unsigned char* bytes, std::size_t count, SampleType t, bool swap, float* out)
{
    switch (t) {
    case SampleType::Int8: convert_as<std::int8_t>(bytes, count, false, out); break;
    case SampleType::UInt8: convert_as<std::uint8_t>(bytes, count, false, out); break;
    case SampleType::Int16: convert_as<std::int16_t>(bytes, count, swap, out); break;
    case SampleType::UInt16: convert_as<std::uint16_t>(bytes, count, swap, out); break;
    case SampleType::Int32: convert_as<std::int32_t>(bytes, count, swap, out); break;
    case SampleType::UInt32: convert_as<std::uint32_t>(bytes, count, swap, out); break;
    case SampleType::Int64: convert_as<std::int64_t>(bytes, count, swap, out); break;
    case SampleType::UInt64: convert_as<std::uint64_t>(bytes, count, swap, out); break;
    case SampleType::Float32: convert_as<float>(bytes, count, swap, out); break;
    case SampleType::Float64: convert_as<double>(bytes, count, swap, out); break;
    }
}

namespace {
std::string coord_text(const openvdb::Coord& c)
{
    std::ostringstream s;
    s << "(" << c.x() << ", " << c.y() << ", " << c.z() << ")";
    return s.str();
}
} // namespace

Volume make_dense_volume(const std::string& path, const std::string& format, const DenseBlock& block,
                         openvdb::math::Transform::Ptr transform)
{
    const auto& fd = block.file_dims;
    const std::size_t count = std::size_t(fd[0]) * fd[1] * fd[2];
    if (block.values.size() != count) invalid(path, "internal error: sample count mismatch");
    // Refuse non-finite samples before building anything: the first one in file order is named.
    for (std::size_t n = 0; n < count; ++n) {
        if (!std::isfinite(block.values[n])) {
            std::array<int, 3> f{int(n % fd[0]), int((n / fd[0]) % fd[1]), int(n / (std::size_t(fd[0]) * fd[1]))};
            openvdb::Coord ijk;
            for (int a = 0; a < 3; ++a) ijk[block.axis_of[a]] = f[a];
            invalid(path, std::string(std::isnan(block.values[n]) ? "NaN" : "Inf") + " sample at index (i,j,k) = " +
                              coord_text(ijk) + "; non-finite samples are not accepted");
        }
    }
    Volume vol;
    vol.path = path;
    vol.format = format;
    vol.grid = openvdb::FloatGrid::create(0.0f);
    vol.grid->setName("density");
    vol.grid->setTransform(transform);
    vol.default_inside = Inside::Above;
    auto acc = vol.grid->getAccessor();
    openvdb::Coord ijk;
    std::size_t n = 0;
    // setValue() marks every sample active, including those equal to the background: the
    // lattice of a dense file is exactly its active bounding box.
    for (int s = 0; s < fd[2]; ++s)
        for (int r = 0; r < fd[1]; ++r)
            for (int c = 0; c < fd[0]; ++c, ++n) {
                ijk[block.axis_of[0]] = c;
                ijk[block.axis_of[1]] = r;
                ijk[block.axis_of[2]] = s;
                acc.setValue(ijk, block.values[n]);
            }
    finish_volume(vol);
    return vol;
}

void check_transform_and_background(const Volume& vol)
{
    const auto& tree = vol.grid->tree();
    // A .vdb's transform is the file's: the dense readers check their voxel sizes, OpenVDB's
    // map readers check nothing, and a zero, NaN or infinite voxel or origin leaves no world
    // coordinates for the mesh.
    const auto& xf = vol.grid->transform();
    const openvdb::Vec3d voxel = xf.voxelSize(), origin = xf.indexToWorld(openvdb::Vec3d(0.0));
    for (int a = 0; a < 3; ++a)
        if (!(voxel[a] > 0) || !std::isfinite(voxel[a]) || !std::isfinite(origin[a])) {
            std::ostringstream why;
            why << "grid '" << vol.grid->getName() << "' has a transform without a finite, positive voxel size "
                << "and a finite origin (axis " << a << ": voxel " << voxel[a] << ", origin " << origin[a] << ")";
            invalid(vol.path, why.str());
        }
    const float bg = tree.background();
    if (!std::isfinite(bg)) invalid(vol.path, "non-finite background value in grid '" + vol.grid->getName() + "'");
}

void finish_volume(Volume& vol)
{
    const auto& tree = vol.grid->tree();
    if (tree.activeVoxelCount() == 0) invalid(vol.path, "empty grid '" + vol.grid->getName() + "' (no active voxels)");
    vol.lattice = vol.grid->evalActiveVoxelBoundingBox();
    vol.samples_read = tree.activeVoxelCount();
    check_transform_and_background(vol);
    const float bg = tree.background();
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (auto it = vol.grid->cbeginValueOn(); it; ++it) {
        const float v = *it;
        if (!std::isfinite(v))
            invalid(vol.path, std::string(std::isnan(v) ? "NaN" : "Inf") + " sample at index (i,j,k) = " +
                                  coord_text(it.getCoord()) + "; non-finite samples are not accepted");
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    // Inactive voxels inside the lattice are samples too: they read as their inactive value
    // (a narrow-band level set's interior is -background) or, where no node exists, the background.
    if (tree.activeVoxelCount() < vol.lattice.volume()) {
        lo = std::min(lo, bg);
        hi = std::max(hi, bg);
        for (auto it = vol.grid->cbeginValueOff(); it; ++it) {
            if (!vol.lattice.hasOverlap(it.getBoundingBox())) continue;
            const float v = *it;
            if (!std::isfinite(v))
                invalid(vol.path, std::string(std::isnan(v) ? "NaN" : "Inf") + " inactive value at index (i,j,k) = " +
                                      coord_text(it.getCoord()) + "; non-finite samples are not accepted");
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    vol.value_min = lo;
    vol.value_max = hi;
}

} // namespace isodel::io

namespace isodel::io {

Volume read_dense_regions(const std::string& path, const std::string& format, const DenseLayout& layout,
                          const std::vector<openvdb::CoordBBox>& regions, openvdb::math::Transform::Ptr transform)
{
    const auto& fd = layout.file_dims;
    openvdb::Coord top;
    for (int f = 0; f < 3; ++f) top[layout.axis_of[f]] = fd[f] - 1;
    Volume vol;
    vol.path = path;
    vol.format = format;
    vol.partial = true;
    vol.lattice = openvdb::CoordBBox(openvdb::Coord(0), top);
    vol.grid = openvdb::FloatGrid::create(0.0f);
    vol.grid->setName("density");
    vol.grid->setTransform(transform);
    vol.default_inside = Inside::Above;
    std::ifstream in(path, std::ios::binary);
    if (!in) io_failure(path, "cannot open for reading");
    const int bytes = sample_bytes(layout.type);
    std::vector<unsigned char> raw;
    std::vector<float> run;
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    auto acc = vol.grid->getAccessor();
    for (openvdb::CoordBBox box : regions) {
        box.intersect(vol.lattice);
        if (box.empty()) continue;
        // The box's extent along each file axis.
        std::array<int, 3> from{}, to{};
        for (int f = 0; f < 3; ++f) from[f] = box.min()[layout.axis_of[f]], to[f] = box.max()[layout.axis_of[f]];
        const std::size_t length = std::size_t(to[0] - from[0] + 1);
        raw.resize(length * std::size_t(bytes));
        run.resize(length);
        openvdb::Coord ijk;
        for (int s = from[2]; s <= to[2]; ++s)
            for (int r = from[1]; r <= to[1]; ++r) {
                const std::uint64_t first = (std::uint64_t(s) * std::uint64_t(fd[1]) + std::uint64_t(r)) *
                                                std::uint64_t(fd[0]) + std::uint64_t(from[0]);
                in.seekg(std::streamoff(layout.data_offset + first * std::uint64_t(bytes)));
                if (!in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size())))
                    io_failure(path, "truncated: read failed in section " + std::to_string(s));
                convert_samples(raw.data(), length, layout.type, layout.swap, run.data());
                ijk[layout.axis_of[1]] = r;
                ijk[layout.axis_of[2]] = s;
                for (std::size_t c = 0; c < length; ++c) {
                    ijk[layout.axis_of[0]] = from[0] + int(c);
                    const float v = run[c];
                    if (!std::isfinite(v))
                        invalid(path, std::string(std::isnan(v) ? "NaN" : "Inf") + " sample at index (i,j,k) = " +
                                          coord_text(ijk) + "; non-finite samples are not accepted");
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                    acc.setValue(ijk, v);
                }
            }
    }
    vol.value_min = lo, vol.value_max = hi; // min > max: nothing read
    vol.samples_read = vol.grid->activeVoxelCount();
    return vol;
}

} // namespace isodel::io
