// Tetrahedral mesh writers for the formats FEM tools read (DELVOLMESH's output, paper Section
// 4.1): Medit .mesh (ASCII), VTK XML .vtu
// (raw appended binary, little-endian, UInt64 headers) and Gmsh .msh 4.1 (ASCII). Coordinates
// are written with 17 significant digits (or as raw doubles), so they round-trip exactly and
// the surface triangles stay bit-identical to write_surface_mesh's output. Every format keeps
// the vertex numbering of TetMesh (1-based where the format is), so vertex i of the surface
// mesh is vertex i of the tetrahedral mesh.
#include "atomic_file.h"
#include "little_endian.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <string>
#include <cstring>
#include <iomanip>
#include <limits>
#include <sstream>

namespace isodel {
namespace {

/// Text output through a buffer, numbers formatted by std::to_chars: iostream's << goes through
/// the locale and a virtual call per number, slow on the millions of lines of a large mesh.
/// Doubles as printf's %.17g (to_chars'
/// general format at that precision is specified so), integers in decimal: the same bytes as
/// << with setprecision(17).
class TextOut {
public:
    explicit TextOut(std::ostream& out) : out_(out) { buf_.reserve(kFlush + 512); }
    ~TextOut() { flush(); }
    TextOut& operator<<(double v) { return put_chars([&](char* b, char* e) { return std::to_chars(b, e, v, std::chars_format::general, 17); }); }
    TextOut& operator<<(std::int64_t v) { return put_chars([&](char* b, char* e) { return std::to_chars(b, e, v); }); }
    TextOut& operator<<(std::int32_t v) { return *this << std::int64_t(v); }
    TextOut& operator<<(std::size_t v) { return put_chars([&](char* b, char* e) { return std::to_chars(b, e, v); }); }
    TextOut& operator<<(char c)
    {
        buf_.push_back(c);
        return *this;
    }
    TextOut& operator<<(const char* s)
    {
        buf_.append(s);
        if (buf_.size() >= kFlush) flush();
        return *this;
    }
    void flush()
    {
        out_.write(buf_.data(), std::streamsize(buf_.size()));
        buf_.clear();
    }

private:
    static constexpr std::size_t kFlush = std::size_t(1) << 20;
    template <class F>
    TextOut& put_chars(F&& format)
    {
        char b[32];
        const std::to_chars_result r = format(b, b + sizeof b);
        buf_.append(b, r.ptr);
        if (buf_.size() >= kFlush) flush();
        return *this;
    }
    std::ostream& out_;
    std::string buf_;
};


void write_medit(std::ostream& stream, const TetMesh& m)
{
    TextOut out(stream);
    out << "MeshVersionFormatted 2\nDimension 3\n";
    out << "Vertices\n" << m.vertices.size() << '\n';
    for (const auto& v : m.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << " 0\n";
    out << "Triangles\n" << m.triangles.size() << '\n';
    for (const auto& t : m.triangles) out << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << " 1\n";
    out << "Tetrahedra\n" << m.tets.size() << '\n';
    for (std::size_t i = 0; i < m.tets.size(); ++i) {
        const auto& t = m.tets[i];
        out << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << ' ' << t[3] + 1 << ' ' << std::int32_t(m.tet_region[i]) << '\n';
    }
    out << "End\n";
}

void write_vtu(std::ostream& out, const TetMesh& m)
{
    // Appended raw arrays, each preceded by its byte count (UInt64); offsets count from the '_'.
    const std::uint64_t np = m.vertices.size(), nt = m.tets.size();
    const std::uint64_t sizes[5] = {np * 3 * 8, nt * 4 * 8, nt * 8, nt, nt * 4};
    std::uint64_t off[5];
    off[0] = 0;
    for (int i = 1; i < 5; ++i) off[i] = off[i - 1] + 8 + sizes[i - 1];
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nt << "\">\n"
        << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\""
        << off[0] << "\"/>\n      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"" << off[1] << "\"/>\n"
        << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"" << off[2] << "\"/>\n"
        << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << off[3] << "\"/>\n"
        << "      </Cells>\n      <CellData Scalars=\"region\">\n"
        << "        <DataArray type=\"Int32\" Name=\"region\" format=\"appended\" offset=\"" << off[4] << "\"/>\n"
        << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_";
    io::put_little_endian(out, sizes[0]);
    for (const auto& v : m.vertices)
        for (double c : v) io::put_little_endian(out, c);
    io::put_little_endian(out, sizes[1]);
    for (const auto& t : m.tets)
        for (auto i : t) io::put_little_endian<std::int64_t>(out, i);
    io::put_little_endian(out, sizes[2]);
    for (std::uint64_t i = 1; i <= nt; ++i) io::put_little_endian<std::int64_t>(out, std::int64_t(4 * i));
    io::put_little_endian(out, sizes[3]);
    for (std::uint64_t i = 0; i < nt; ++i) io::put_little_endian<std::uint8_t>(out, 10); // VTK_TETRA
    io::put_little_endian(out, sizes[4]);
    for (auto r : m.tet_region) io::put_little_endian<std::int32_t>(out, r);
    out << "\n  </AppendedData>\n</VTKFile>\n";
}

void write_msh(std::ostream& stream, const TetMesh& m)
{
    // Gmsh 4.1: one surface entity (tag 1, physical 3 "surface") and one volume entity per region
    // present (tag = physical = region: 1 "inside", 2 "outside"); all nodes in the first volume.
    const bool has[3] = {false, std::count(m.tet_region.begin(), m.tet_region.end(), 1) > 0,
                         std::count(m.tet_region.begin(), m.tet_region.end(), 2) > 0};
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    if (!m.vertices.empty()) {
        for (int k = 0; k < 3; ++k) lo[k] = hi[k] = m.vertices[0][k];
        for (const auto& v : m.vertices)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], v[k]);
                hi[k] = std::max(hi[k], v[k]);
            }
    }
    std::ostringstream bbox;
    bbox << std::setprecision(17) << lo[0] << ' ' << lo[1] << ' ' << lo[2] << ' ' << hi[0] << ' ' << hi[1] << ' ' << hi[2];
    TextOut out(stream);
    const int nvol = int(has[1]) + int(has[2]);
    const bool has_tri = !m.triangles.empty();
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n" << std::int32_t(nvol + int(has_tri)) << '\n';
    if (has_tri) out << "2 3 \"surface\"\n";
    if (has[1]) out << "3 1 \"inside\"\n";
    if (has[2]) out << "3 2 \"outside\"\n";
    out << "$EndPhysicalNames\n$Entities\n0 0 " << std::int32_t(has_tri) << ' ' << std::int32_t(nvol) << '\n';
    if (has_tri) out << "1 " << bbox.str().c_str() << " 1 3 0\n";
    for (std::int32_t r = 1; r <= 2; ++r)
        if (has[r]) out << r << ' ' << bbox.str().c_str() << " 1 " << r << ' ' << (has_tri ? "1 1" : "0") << '\n';
    out << "$EndEntities\n";
    const int node_entity = has[1] ? 1 : 2;
    const std::size_t nv = m.vertices.size();
    out << "$Nodes\n1 " << nv << " 1 " << nv << '\n' << std::int32_t(nvol ? 3 : 2) << ' ' << std::int32_t(nvol ? node_entity : 1) << " 0 "
        << nv << '\n';
    for (std::size_t i = 1; i <= nv; ++i) out << i << '\n';
    for (const auto& v : m.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    out << "$EndNodes\n";
    const std::size_t ne = m.triangles.size() + m.tets.size();
    out << "$Elements\n" << std::int32_t(int(has_tri) + nvol) << ' ' << ne << " 1 " << ne << '\n';
    std::size_t tag = 1;
    if (has_tri) {
        out << "2 1 2 " << m.triangles.size() << '\n';
        for (const auto& t : m.triangles) out << tag++ << ' ' << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    }
    for (std::int32_t r = 1; r <= 2; ++r) {
        if (!has[r]) continue;
        out << "3 " << r << " 4 " << std::int64_t(std::count(m.tet_region.begin(), m.tet_region.end(), r)) << '\n';
        for (std::size_t i = 0; i < m.tets.size(); ++i) {
            if (m.tet_region[i] != r) continue;
            const auto& t = m.tets[i];
            out << tag++ << ' ' << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << ' ' << t[3] + 1 << '\n';
        }
    }
    out << "$EndElements\n";
}

} // namespace

bool is_tet_mesh_path(const std::string& path)
{
    const std::string ext = io::extension_of(path);
    return ext == ".mesh" || ext == ".vtu" || ext == ".msh";
}

void write_tet_mesh(const std::string& path, const TetMesh& m)
{
    const std::string ext = io::extension_of(path);
    if (!is_tet_mesh_path(path))
        throw InvalidInput(path + ": unknown tetrahedral mesh format '" + ext + "' (use .mesh, .vtu or .msh)");
    if (m.vertices.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw InvalidInput(path + ": too many vertices for 32-bit indices");
    io::AtomicFile f(path);
    if (ext == ".mesh") write_medit(f.stream(), m);
    else if (ext == ".vtu") write_vtu(f.stream(), m);
    else write_msh(f.stream(), m);
    f.commit();
}

} // namespace isodel
