// Surface mesh readers (.ply ascii/binary, .obj, .off, .stl ascii/binary), used by verify and the
// tests. Polygons are fan-triangulated; STL's triangle soup is welded by exact vertex position.
#include "atomic_file.h"

#include "dense_volume.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace isodel {
namespace {


void add_polygon(const std::string& path, SurfaceMesh& m, const std::vector<long long>& poly)
{
    if (poly.size() < 3) io::invalid(path, "face with fewer than 3 vertices");
    for (long long i : poly)
        if (i < 0 || i >= (long long)m.vertices.size()) io::invalid(path, "face refers to missing vertex " + std::to_string(i));
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
        m.triangles.push_back({std::int32_t(poly[0]), std::int32_t(poly[k]), std::int32_t(poly[k + 1])});
}

// ---- PLY ----
struct PlyProp {
    std::string name, type, count_type; // count_type non-empty for lists
};
struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProp> props;
};

int ply_size(const std::string& path, const std::string& t)
{
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    io::invalid(path, "unknown PLY property type '" + t + "'");
}

double ply_binary(std::istream& in, const std::string& t, bool big, const std::string& path)
{
    unsigned char b[8];
    const int n = ply_size(path, t);
    if (!in.read(reinterpret_cast<char*>(b), n)) io::invalid(path, "truncated PLY data");
    if (big) std::reverse(b, b + n);
    auto as = [&](auto v) { std::memcpy(&v, b, sizeof(v)); return double(v); };
    if (t == "char" || t == "int8") return as(std::int8_t());
    if (t == "uchar" || t == "uint8") return as(std::uint8_t());
    if (t == "short" || t == "int16") return as(std::int16_t());
    if (t == "ushort" || t == "uint16") return as(std::uint16_t());
    if (t == "int" || t == "int32") return as(std::int32_t());
    if (t == "uint" || t == "uint32") return as(std::uint32_t());
    if (t == "float" || t == "float32") return as(float());
    return as(double());
}

/// The fewest bytes a record of \p e can take: its properties' sizes (a list's count) in binary,
/// two characters per property ("0 ") in ASCII. Checks every property type on the way.
std::uint64_t ply_min_record_bytes(const std::string& path, const PlyElement& e, bool ascii)
{
    std::uint64_t bytes = 0;
    for (const auto& p : e.props) {
        const int size = ply_size(path, p.type);
        const int count_size = p.count_type.empty() ? 0 : ply_size(path, p.count_type);
        bytes += ascii ? 2 : std::uint64_t(p.count_type.empty() ? size : count_size);
    }
    return bytes;
}

SurfaceMesh read_ply(const std::string& path, std::istream& in, std::uint64_t file_size)
{
    std::string line, format;
    std::getline(in, line);
    if (line.rfind("ply", 0) != 0) io::invalid(path, "wrong magic number: a PLY file starts with 'ply'");
    std::vector<PlyElement> elems;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream s(line);
        std::string w;
        s >> w;
        if (w == "format") s >> format;
        else if (w == "element") { elems.emplace_back(); s >> elems.back().name >> elems.back().count; }
        else if (w == "property") {
            if (elems.empty()) io::invalid(path, "PLY property before any element");
            PlyProp p;
            s >> p.type;
            if (p.type == "list") s >> p.count_type >> p.type;
            s >> p.name;
            elems.back().props.push_back(p);
        } else if (w == "end_header") break;
    }
    if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        io::invalid(path, "unsupported PLY format '" + format + "'");
    const bool ascii = format == "ascii", big = format == "binary_big_endian";
    // Every record takes file bytes, so counts the file cannot hold are refused before any
    // record is read (an element without properties would otherwise loop its count for nothing).
    std::uint64_t needed = 0;
    for (const auto& e : elems) {
        const std::uint64_t record = ply_min_record_bytes(path, e, ascii);
        if (e.count > 0 && record == 0) io::invalid(path, "PLY element '" + e.name + "' has records but no properties");
        if (record > 0 && e.count > file_size / record)
            io::invalid(path, "PLY header announces " + std::to_string(e.count) + " " + e.name +
                                  " records, more than the file can hold");
        needed += e.count * record;
        if (needed > file_size) io::invalid(path, "PLY header announces more records than the file can hold");
    }
    SurfaceMesh m;
    for (const auto& e : elems) {
        for (std::size_t r = 0; r < e.count; ++r) {
            std::array<double, 3> v{0, 0, 0};
            std::vector<long long> poly;
            for (const auto& p : e.props) {
                auto read1 = [&](const std::string& t) {
                    if (!ascii) return ply_binary(in, t, big, path);
                    double x;
                    if (!(in >> x)) io::invalid(path, "truncated PLY data");
                    return x;
                };
                if (!p.count_type.empty()) {
                    const double length = read1(p.count_type);
                    if (!(length >= 0 && length <= double(file_size))) // NaN too
                        io::invalid(path, "PLY list length out of range");
                    const auto n = (long long)length;
                    std::vector<long long> items;
                    for (long long k = 0; k < n; ++k) {
                        // Any list entry may be an index: a float type can spell NaN or 1e300.
                        const double item = read1(p.type);
                        if (!(std::abs(item) < 9.0e18)) io::invalid(path, "PLY list entry out of range");
                        items.push_back((long long)item);
                    }
                    if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) poly = items;
                } else {
                    const double x = read1(p.type);
                    if (e.name == "vertex") {
                        if (p.name == "x") v[0] = x;
                        if (p.name == "y") v[1] = x;
                        if (p.name == "z") v[2] = x;
                    }
                }
            }
            if (e.name == "vertex") m.vertices.push_back(v);
            if (e.name == "face") add_polygon(path, m, poly);
        }
    }
    return m;
}

// ---- OBJ / OFF ----
SurfaceMesh read_obj(const std::string& path, std::istream& in)
{
    SurfaceMesh m;
    for (std::string line; std::getline(in, line);) {
        std::istringstream s(line);
        std::string w;
        s >> w;
        if (w == "v") {
            std::array<double, 3> v;
            if (!(s >> v[0] >> v[1] >> v[2])) io::invalid(path, "malformed vertex line '" + line + "'");
            m.vertices.push_back(v);
        } else if (w == "f") {
            std::vector<long long> poly;
            for (std::string tok; s >> tok;) {
                long long i = std::stoll(tok.substr(0, tok.find('/')));
                poly.push_back(i < 0 ? (long long)m.vertices.size() + i : i - 1); // negative: relative
            }
            add_polygon(path, m, poly);
        }
    }
    return m;
}

SurfaceMesh read_off(const std::string& path, std::istream& in)
{
    // Comments may appear anywhere; strip them, then read the token stream.
    std::stringstream body;
    std::uint64_t body_bytes = 0;
    for (std::string line; std::getline(in, line);) {
        const std::string kept = line.substr(0, line.find('#'));
        body << kept << '\n';
        body_bytes += kept.size() + 1;
    }
    std::string magic;
    body >> magic;
    if (magic != "OFF") io::invalid(path, "wrong magic number: an OFF file starts with 'OFF'");
    long long nv, nf, ne;
    if (!(body >> nv >> nf >> ne) || nv < 0 || nf < 0) io::invalid(path, "malformed OFF counts");
    // A vertex needs at least 6 bytes ("0 0 0 "): a count the file cannot hold is refused before
    // anything is allocated for it.
    if (std::uint64_t(nv) > body_bytes / 6)
        io::invalid(path, "OFF header announces " + std::to_string(nv) + " vertices, more than the file can hold");
    SurfaceMesh m;
    m.vertices.resize(std::size_t(nv));
    for (auto& v : m.vertices)
        if (!(body >> v[0] >> v[1] >> v[2])) io::invalid(path, "truncated OFF vertices");
    for (long long f = 0; f < nf; ++f) {
        long long n;
        if (!(body >> n)) io::invalid(path, "truncated OFF faces");
        // An index needs at least 2 bytes ("0 "): a longer face cannot be in the file.
        if (n < 0 || std::uint64_t(n) > body_bytes / 2) io::invalid(path, "OFF face with an impossible vertex count");
        std::vector<long long> poly(static_cast<std::size_t>(n));
        for (auto& i : poly)
            if (!(body >> i)) io::invalid(path, "truncated OFF faces");
        std::string rest;
        add_polygon(path, m, poly);
    }
    return m;
}

// ---- STL ----
SurfaceMesh read_stl(const std::string& path, std::istream& in, std::uint64_t size)
{
    std::vector<std::array<double, 3>> soup;
    char header[84];
    bool binary = false;
    if (size >= 84 && in.read(header, 84)) {
        std::uint32_t n;
        std::memcpy(&n, header + 80, 4);
        binary = size == 84 + std::uint64_t(n) * 50;
        if (binary) {
            for (std::uint32_t t = 0; t < n; ++t) {
                char rec[50];
                if (!in.read(rec, 50)) io::invalid(path, "truncated STL data");
                for (int k = 0; k < 3; ++k) {
                    float v[3];
                    std::memcpy(v, rec + 12 + 12 * k, 12);
                    soup.push_back({v[0], v[1], v[2]});
                }
            }
        }
    }
    if (!binary) {
        in.clear();
        in.seekg(0);
        std::string w;
        in >> w;
        if (w != "solid") io::invalid(path, "neither a binary STL (size mismatch) nor an ASCII STL ('solid')");
        while (in >> w)
            if (w == "vertex") {
                std::array<double, 3> v;
                if (!(in >> v[0] >> v[1] >> v[2])) io::invalid(path, "malformed STL vertex");
                soup.push_back(v);
            }
        if (soup.size() % 3) io::invalid(path, "STL facet without three vertices");
    }
    SurfaceMesh m;
    std::map<std::array<double, 3>, std::int32_t> index;
    std::vector<long long> tri;
    for (const auto& v : soup) {
        auto [it, fresh] = index.emplace(v, std::int32_t(m.vertices.size()));
        if (fresh) m.vertices.push_back(v);
        tri.push_back(it->second);
        if (tri.size() == 3) {
            add_polygon(path, m, tri);
            tri.clear();
        }
    }
    return m;
}

} // namespace

SurfaceMesh read_surface_mesh(const std::string& path)
{
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw IoError(path + ": cannot open: " + std::strerror(errno));
    const auto size = std::uint64_t(in.tellg());
    in.seekg(0);
    const std::string ext = io::extension_of(path);
    SurfaceMesh m;
    try {
        if (ext == ".ply") m = read_ply(path, in, size);
        else if (ext == ".obj") m = read_obj(path, in);
        else if (ext == ".off") m = read_off(path, in);
        else if (ext == ".stl") m = read_stl(path, in, size);
        else io::invalid(path, "unknown surface mesh extension '" + ext + "' (expected .ply, .obj, .off or .stl)");
    } catch (const std::invalid_argument&) {
        io::invalid(path, "malformed number");
    } catch (const std::out_of_range&) {
        io::invalid(path, "number out of range");
    }
    // Every format can spell NaN or infinity (text "nan", binary bit patterns); the verifier's
    // exact predicates need finite points.
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
        for (double c : m.vertices[i])
            if (!std::isfinite(c)) io::invalid(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    return m;
}

} // namespace isodel
