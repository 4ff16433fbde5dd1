// Surface mesh writers: PLY (binary little-endian, double coordinates so nothing is rounded),
// OBJ and OFF (17 significant digits: doubles round-trip exactly), STL (binary; float32 by format).
#include "atomic_file.h"
#include "little_endian.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>

#include <cmath>
#include <cstring>
#include <iomanip>

namespace isodel {
namespace {


void write_ply(std::ostream& out, const SurfaceMesh& m)
{
    out << "ply\nformat binary_little_endian 1.0\ncomment written by isodel\n"
        << "element vertex " << m.vertices.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
        << "element face " << m.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& v : m.vertices)
        for (double c : v) io::put_little_endian(out, c);
    for (const auto& t : m.triangles) {
        io::put_little_endian<std::uint8_t>(out, 3);
        for (auto i : t) io::put_little_endian<std::int32_t>(out, i);
    }
}

void write_obj(std::ostream& out, const SurfaceMesh& m)
{
    out << "# written by isodel\n" << std::setprecision(17);
    for (const auto& v : m.vertices) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    for (const auto& t : m.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

void write_off(std::ostream& out, const SurfaceMesh& m)
{
    out << "OFF\n" << m.vertices.size() << ' ' << m.triangles.size() << " 0\n" << std::setprecision(17);
    for (const auto& v : m.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    for (const auto& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

void write_stl(std::ostream& out, const SurfaceMesh& m)
{
    char header[80] = {};
    std::strncpy(header, "binary STL written by isodel", sizeof(header));
    out.write(header, sizeof(header));
    io::put_little_endian<std::uint32_t>(out, std::uint32_t(m.triangles.size()));
    for (const auto& t : m.triangles) {
        const auto &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
        double n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                       (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                       (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (double x : n) io::put_little_endian<float>(out, len > 0 ? float(x / len) : 0.0f);
        for (const auto* v : {&a, &b, &c})
            for (double x : *v) io::put_little_endian<float>(out, float(x));
        io::put_little_endian<std::uint16_t>(out, 0);
    }
}

} // namespace

void write_surface_mesh(const std::string& path, const SurfaceMesh& mesh)
{
    const std::string ext = io::extension_of(path);
    void (*writer)(std::ostream&, const SurfaceMesh&) = nullptr;
    if (ext == ".ply") writer = write_ply;
    else if (ext == ".obj") writer = write_obj;
    else if (ext == ".off") writer = write_off;
    else if (ext == ".stl") writer = write_stl;
    else throw InvalidInput(path + ": unknown surface mesh extension '" + ext + "' (expected .ply, .obj, .off or .stl)");
    const auto n = std::int64_t(mesh.vertices.size());
    for (const auto& t : mesh.triangles)
        for (auto i : t)
            if (i < 0 || i >= n) throw InvalidInput(path + ": triangle refers to vertex " + std::to_string(i) +
                                                    " of " + std::to_string(n));
    io::AtomicFile file(path);
    writer(file.stream(), mesh);
    file.commit();
}

} // namespace isodel
