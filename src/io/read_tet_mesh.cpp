// Reader for Medit .mesh tetrahedral meshes (the format isodel mesh --tets writes, and most FEM
// tools read): Vertices, Triangles and Tetrahedra sections with their refs; other sections are
// skipped. Used by isodel verify --tets, which must not trust the writer.
#include "dense_volume.h"

#include <isodel/errors.h>
#include <isodel/surface_mesh.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>
#include <sstream>

namespace isodel {

TetMesh read_tet_mesh(const std::string& path)
{
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || path.substr(dot) != ".mesh")
        io::invalid(path, "isodel verify reads tetrahedral meshes in Medit .mesh format");
    // A section of n entries of k numbers needs at least 2k bytes per entry ("0 "): a count the
    // file cannot hold is refused before anything is allocated for it.
    const std::uint64_t file_bytes = io::file_size_or_throw(path);
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot open");
    TetMesh m;
    std::string word;
    bool have_vertices = false;
    auto count = [&](const char* section, int numbers_per_entry) {
        long long n = -1;
        if (!(in >> n) || n < 0) io::invalid(path, std::string("bad count in section ") + section);
        if (std::uint64_t(n) > file_bytes / std::uint64_t(2 * numbers_per_entry))
            io::invalid(path, std::string("section ") + section + " announces " + std::to_string(n) +
                                  " entries, more than the file's " + std::to_string(file_bytes) + " bytes can hold");
        return std::size_t(n);
    };
    auto index = [&](long long i, std::size_t nv) {
        if (i < 1 || std::size_t(i) > nv) io::invalid(path, "vertex index " + std::to_string(i) + " out of range");
        return std::int32_t(i - 1);
    };
    // Each section once: a second Vertices section would replace the vertices the earlier
    // sections' indices were checked against (a fuzz finding), and a second Triangles or
    // Tetrahedra section would silently drop the first.
    std::set<std::string> seen;
    while (in >> word) {
        if (word == "End") break;
        if ((word == "Vertices" || word == "Triangles" || word == "Tetrahedra") && !seen.insert(word).second)
            io::invalid(path, "section " + word + " appears twice");
        if (word == "MeshVersionFormatted" || word == "Dimension") {
            in >> word;
        } else if (word == "Vertices") {
            const std::size_t n = count("Vertices", 4);
            m.vertices.resize(n);
            for (auto& v : m.vertices) {
                long long ref;
                if (!(in >> v[0] >> v[1] >> v[2] >> ref)) io::invalid(path, "truncated Vertices section");
                if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
                    io::invalid(path, "non-finite vertex coordinate");
            }
            have_vertices = true;
        } else if (word == "Triangles") {
            if (!have_vertices) io::invalid(path, "Triangles before Vertices");
            const std::size_t n = count("Triangles", 4);
            m.triangles.resize(n);
            for (auto& t : m.triangles) {
                long long a, b, c, ref;
                if (!(in >> a >> b >> c >> ref)) io::invalid(path, "truncated Triangles section");
                t = {index(a, m.vertices.size()), index(b, m.vertices.size()), index(c, m.vertices.size())};
            }
        } else if (word == "Tetrahedra") {
            if (!have_vertices) io::invalid(path, "Tetrahedra before Vertices");
            const std::size_t n = count("Tetrahedra", 5);
            m.tets.resize(n);
            m.tet_region.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                long long a, b, c, d, ref;
                if (!(in >> a >> b >> c >> d >> ref)) io::invalid(path, "truncated Tetrahedra section");
                const std::size_t nv = m.vertices.size();
                m.tets[i] = {index(a, nv), index(b, nv), index(c, nv), index(d, nv)};
                m.tet_region[i] = std::int32_t(ref);
            }
        } else {
            io::invalid(path, "unsupported Medit section '" + word + "'");
        }
    }
    if (m.tets.empty()) io::invalid(path, "no tetrahedra");
    return m;
}

} // namespace isodel
