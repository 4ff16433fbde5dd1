// Writes the fuzz targets' seed corpora: small valid files of every format and variant the
// readers accept, made by the test suite's byte-level writers (tests/support/test_files.h) and
// by isodel's own writers, plus the volumes of tests/data. Run by CTest before the fuzz smoke
// tests (fixture "fuzz_seeds"), so the seeds follow the writers.
//   make_fuzz_seeds <output folder> <tests/data folder>
#include "support/test_files.h"

#include <isodel/adaptive.h>
#include <isodel/surface_mesh.h>
#include <isodel/volume.h>

#include <openvdb/tools/LevelSetSphere.h>
#include <zlib.h>

#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;
using namespace isodel;

namespace {

void write(const fs::path& p, const std::string& bytes)
{
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
}

std::string read(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string gzip(const std::string& bytes, const fs::path& tmp)
{
    gzFile f = gzopen(tmp.c_str(), "wb");
    gzwrite(f, bytes.data(), unsigned(bytes.size()));
    gzclose(f);
    const std::string out = read(tmp);
    fs::remove(tmp);
    return out;
}

double blob(int i, int j, int k) { return 4.0 - std::hypot(i - 2.0, j - 2.0, k - 2.0); }

void volume_seeds(const fs::path& out, const fs::path& data)
{
    for (int mode : {0, 1, 2, 6})
        for (bool be : {false, true}) {
            test::MrcSpec s;
            s.n = {5, 4, 3};
            s.mode = mode;
            s.big_endian = be;
            write(out / "fuzz_read_mrc" / ("mode" + std::to_string(mode) + (be ? "_be" : "_le") + ".mrc"),
                  test::mrc_bytes(s, blob));
        }
    test::MrcSpec permuted;
    permuted.n = {3, 4, 5};
    permuted.map = {3, 1, 2};
    permuted.start = {-2, 1, 0};
    permuted.nsymbt = 80;
    write(out / "fuzz_read_mrc" / "permuted_axes.map", test::mrc_bytes(permuted, blob));
    write(out / "fuzz_read_mrc" / "two_blobs.mrc", read(data / "two_blobs.mrc"));

    const std::array<int, 3> d{4, 3, 5};
    const std::string inr = test::inr_bytes(d, "float", 32, "decm", {1, 1, 1}, blob);
    write(out / "fuzz_read_inr" / "float32.inr", inr);
    write(out / "fuzz_read_inr" / "float64_sun.inr", test::inr_bytes(d, "float", 64, "sun", {0.5, 1, 2}, blob));
    write(out / "fuzz_read_inr" / "u8.inr", test::inr_bytes(d, "unsigned fixed", 8, "decm", {1, 1, 1}, blob));
    write(out / "fuzz_read_inr" / "s16_sgi.inr", test::inr_bytes(d, "signed fixed", 16, "sgi", {1, 1, 1}, blob));
    write(out / "fuzz_read_inr" / "float32.inr.gz", gzip(inr, out / "tmp.gz"));

    // Raw: 4 layout bytes (fuzz_read_raw.cpp) then the samples: 2x3x4 float32 and uint8.
    std::string f32("\x02\x03\x04\x00", 4), u8("\x02\x03\x04\x01", 4);
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 2; ++i) {
                const float v = float(blob(i, j, k));
                f32.append(reinterpret_cast<const char*>(&v), 4);
                u8.push_back(char(std::uint8_t(10 * v + 100)));
            }
    write(out / "fuzz_read_raw" / "float32", f32);
    write(out / "fuzz_read_raw" / "uint8", u8);

    for (const char* name : {"cell_c04_f00_p1e0.vdb"}) write(out / "fuzz_read_vdb" / name, read(data / name));
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.f, openvdb::Vec3f(0.f), 1.f, 2.f);
    write_vdb((out / "fuzz_read_vdb" / "sphere.vdb").string(), {sphere});
}

/// Small .vdb files that reach every node reader within a few bytes: a partly active leaf and
/// tiles at both internal levels, in each compression, as half floats, as a double grid, with
/// an instance, and written as a stream (no grid offsets).
void small_vdb_seeds(const fs::path& out)
{
    auto g = openvdb::FloatGrid::create(-1.f);
    g->setName("f");
    for (int k = 0; k < 5; ++k)
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 5; ++i) g->tree().setValue({i, j, k}, float(i - 2.5));
    g->tree().setValueOff({7, 7, 7}, 2.f);
    g->tree().addTile(1, {64, 0, 0}, 1.f, true);
    g->tree().addTile(2, {0, 1024, 0}, 3.f, false);
    const auto write_file = [&](const std::string& name, const openvdb::GridPtrVec& grids, std::uint32_t compression) {
        openvdb::io::File f((out / "fuzz_read_vdb" / name).string());
        f.setCompression(compression);
        f.write(grids);
    };
    using namespace openvdb::io;
    write_file("small_none.vdb", {g}, COMPRESS_NONE);
    write_file("small_zip.vdb", {g}, COMPRESS_ZIP);
    write_file("small_zip_mask.vdb", {g}, COMPRESS_ZIP | COMPRESS_ACTIVE_MASK);
    write_file("small_blosc_mask.vdb", {g}, COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK);
    auto half = g->deepCopy();
    half->setSaveFloatAsHalf(true);
    write_file("small_half.vdb", {half}, COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK);
    auto d = openvdb::DoubleGrid::create(0.5);
    d->setName("d");
    for (int i = 0; i < 9; ++i) d->tree().setValue({i, 2 * i, 1}, 0.25 * i);
    auto instance = g->copyGrid();
    instance->setName("instance");
    write_file("small_double_instance.vdb", {d, g, instance}, COMPRESS_ZIP | COMPRESS_ACTIVE_MASK);
    write_vdb((out / "fuzz_read_vdb" / "small_stream.vdb").string(), {g});
}

void adaptive_seeds(const fs::path& out)
{
    auto grid = openvdb::FloatGrid::create(0.f);
    for (int k = 0; k <= 12; ++k)
        for (int j = 0; j <= 12; ++j)
            for (int i = 0; i <= 12; ++i) grid->tree().setValueOn({i, j, k}, float(0.1 * i + 0.05 * j - 0.02 * k));
    DecimateOptions o;
    o.tolerance = 1e-3;
    o.max_level = 3;
    const fs::path p = out / "fuzz_load_adaptive" / "ramp.vdb";
    fs::create_directories(p.parent_path());
    save_adaptive(p.string(), decimate(*grid, o).volume);
    fs::copy_file(p, out / "fuzz_read_vdb" / "adaptive_ramp.vdb", fs::copy_options::overwrite_existing);
}

void mesh_seeds(const fs::path& out)
{
    SurfaceMesh tet;
    tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const fs::path dir = out / "fuzz_read_surface_mesh";
    fs::create_directories(dir);
    // The first byte picks the extension (fuzz_read_surface_mesh.cpp): 0 ply, 1 obj, 2 off, 3 stl.
    const char* ext[] = {".ply", ".obj", ".off", ".stl"};
    for (int e = 0; e < 4; ++e) {
        const fs::path tmp = dir / (std::string("tmp") + ext[e]);
        write_surface_mesh(tmp.string(), tet);
        write(dir / (std::string("binary") + ext[e]), std::string(1, char(e)) + read(tmp));
        fs::remove(tmp);
    }
    write(dir / "ascii.ply", std::string(1, '\0') +
                                 "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                                 "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    write(dir / "ascii.stl", std::string(1, '\3') +
                                 "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\n"
                                 "endloop\nendfacet\nendsolid t\n");
    TetMesh tm;
    tm.vertices = tet.vertices;
    tm.tets = {{0, 1, 2, 3}};
    tm.tet_region = {1};
    tm.triangles = tet.triangles;
    const fs::path mesh = out / "fuzz_read_tet_mesh" / "one_tet.mesh";
    fs::create_directories(mesh.parent_path());
    write_tet_mesh(mesh.string(), tm);
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::cerr << "usage: make_fuzz_seeds <output folder> <tests/data folder>\n";
        return 2;
    }
    openvdb::initialize();
    const fs::path out = argv[1];
    volume_seeds(out, argv[2]);
    small_vdb_seeds(out);
    adaptive_seeds(out);
    mesh_seeds(out);
    return 0;
}
