// sparse_bench: does isodel's work follow the active voxels or the bounding box? Generates
// sparse narrow-band level sets with OpenVDB itself and prints one row per scene: isodel's time
// per phase (medians), peak memory, active voxels, bounding box, vertices, and OpenVDB's
// volumeToMesh on the same grid in the same run. Each measurement runs in its own forked child
// (its peak memory is its own), the methods interleaved within each repetition.
//
//   sparse_bench [--reps 3] [--eps-voxels 0.5] [--threads 2] [--big] [--huge] [--adaptive] [--adaptive-field-input]
// Scenes: two spheres of radius 20 voxels 50 voxels apart on every axis ("near pair") and 1500
// apart ("far pair"); with --big, about 2.4 10^6 active voxels as many spheres and tori
// scattered through a 3000^3 box ("scattered") and the same shapes packed into a compact box
// ("packed"); with --huge, about 2 10^7 active voxels as larger spheres and tori (radii 80-200
// voxels) scattered through a 4100^3 box, two of them at opposite corners ("huge": an active
// box over 4000 voxels per axis), meshed with MeshOptions::adaptive only (a uniform run of it
// needs more memory than a 24 GiB machine has). --adaptive meshes every scene with
// MeshOptions::adaptive; the "grid" column is the certified octree's construction.
// --adaptive-field-input: adaptive runs mesh the input's own F (AdaptiveField::Input).
#include <isodel/mesh.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace {

using Grid = openvdb::FloatGrid;
constexpr float kHalfWidth = 3.f;

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A narrow-band torus (major radius R, minor r, axis z) centred at \p c, in index units.
Grid::Ptr torus(const openvdb::Vec3d& c, double R, double r)
{
    auto g = Grid::create(kHalfWidth);
    g->setGridClass(openvdb::GRID_LEVEL_SET);
    auto acc = g->getAccessor();
    const int ext = int(std::ceil(R + r + kHalfWidth + 1));
    for (int z = -int(r) - 5; z <= int(r) + 5; ++z)
        for (int y = -ext; y <= ext; ++y)
            for (int x = -ext; x <= ext; ++x) {
                const double q = std::hypot(double(x), double(y)) - R;
                const double d = std::hypot(q, double(z)) - r;
                if (std::abs(d) < kHalfWidth)
                    acc.setValueOn(openvdb::Coord(x + int(c[0]), y + int(c[1]), z + int(c[2])), float(d));
            }
    openvdb::tools::signedFloodFill(g->tree());
    return g;
}

Grid::Ptr sphere(const openvdb::Vec3d& c, double r)
{
    return openvdb::tools::createLevelSetSphere<Grid>(float(r), openvdb::Vec3f(c), 1.f, kHalfWidth);
}

Grid::Ptr union_of(std::vector<Grid::Ptr> parts)
{
    Grid::Ptr out = parts.front();
    for (std::size_t i = 1; i < parts.size(); ++i) openvdb::tools::csgUnion(out->tree(), parts[i]->tree());
    out->setGridClass(openvdb::GRID_LEVEL_SET);
    return out;
}

Grid::Ptr pair(double distance)
{
    return union_of({sphere(openvdb::Vec3d(0.0), 20), sphere(openvdb::Vec3d(distance), 20)});
}

/// Spheres and tori of radii \p r0 to \p r1 voxels at random places of a box of \p side voxels
/// (or, with \p packed, on a lattice with 100-voxel spacing), until about \p target active voxels.
/// With \p span, the first two sit at opposite corners of the box, so that the active box spans
/// it whatever the random places.
Grid::Ptr scattered(double side, bool packed, std::size_t target, double r0 = 8, double r1 = 40, bool span = false)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<Grid::Ptr> parts;
    std::size_t active = 0;
    for (int i = 0; active < target; ++i) {
        const double r = r0 + (r1 - r0) * U(rng);
        openvdb::Vec3d c(side * U(rng), side * U(rng), side * U(rng));
        if (packed) c = openvdb::Vec3d(100.0 * (i % 8), 100.0 * ((i / 8) % 8), 100.0 * (i / 64));
        if (span && i < 2) c = openvdb::Vec3d(i == 0 ? r + 4 : side - r - 4);
        Grid::Ptr g = i % 3 == 2 ? torus(c, r, 0.3 * r) : sphere(c, r);
        active += g->activeVoxelCount();
        parts.push_back(g);
    }
    return union_of(parts);
}

/// One measurement, as the child hands it back.
struct Sample {
    double total = 0, grid = 0, points = 0, delaunay = 0, closed_ball = 0, refine = 0, extract = 0;
    double peak_mib = 0;
    long long vertices = 0;
    int ok = 0;
    char message[160] = {};
};

Sample in_child(const std::function<void(Sample&)>& work)
{
    int fd[2];
    if (pipe(fd) != 0) return {};
    const pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        Sample s;
        try {
            work(s);
            s.ok = 1;
        } catch (const std::exception& e) {
            std::snprintf(s.message, sizeof s.message, "%s", e.what());
        }
        rusage ru{};
        getrusage(RUSAGE_SELF, &ru);
        s.peak_mib = double(ru.ru_maxrss) / 1024.0;
        if (write(fd[1], &s, sizeof s) != ssize_t(sizeof s)) _exit(1);
        _exit(0);
    }
    close(fd[1]);
    Sample s;
    if (read(fd[0], &s, sizeof s) != ssize_t(sizeof s)) std::snprintf(s.message, sizeof s.message, "child died");
    close(fd[0]);
    waitpid(pid, nullptr, 0);
    return s;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
    openvdb::initialize();
    int reps = 3, threads = 2;
    double eps_voxels = 0.5;
    bool big = false, huge = false, adaptive = false, field_input = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--reps" && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--eps-voxels" && i + 1 < argc) eps_voxels = std::atof(argv[++i]);
        else if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (a == "--big") big = true;
        else if (a == "--huge") huge = true;
        else if (a == "--adaptive") adaptive = true;
        else if (a == "--adaptive-field-input") field_input = true;
        else {
            std::fprintf(stderr, "usage: sparse_bench [--reps 3] [--eps-voxels 0.5] [--threads 2] [--big] [--huge] [--adaptive] [--adaptive-field-input]\n");
            return 2;
        }
    }
    struct Scene {
        const char* name;
        std::function<Grid::Ptr()> make;
        bool adaptive_only = false;
    };
    std::vector<Scene> scenes = {{"near pair", [] { return pair(50); }}, {"far pair", [] { return pair(1500); }}};
    if (big) {
        scenes.push_back({"scattered", [] { return scattered(3000, false, 2400000); }});
        scenes.push_back({"packed", [] { return scattered(0, true, 2400000); }});
    }
    if (huge) {
        scenes = {};
        scenes.push_back({"huge", [] { return scattered(4100, false, 20000000, 80, 200, true); }, true});
    }
    std::printf("sparse_bench: eps %.3g voxel, %d threads, medians of %d, %s; seconds\n", eps_voxels, threads, reps,
                adaptive || huge ? "MeshOptions::adaptive" : "uniform");
    std::printf("%-10s %10s %16s %7s %7s %7s %7s %7s %7s %7s %8s %9s %8s %8s\n", "scene", "active", "bbox", "total",
                "grid", "points", "dt", "cball", "refine", "extract", "peakMiB", "vertices", "vdb s", "vdbMiB");
    for (const Scene& scene : scenes) {
        const Grid::Ptr grid = scene.make();
        const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
        std::vector<Sample> runs, vdb;
        for (int r = 0; r < reps; ++r) {
            runs.push_back(in_child([&](Sample& s) {
                isodel::MeshOptions mo;
                mo.isovalue = 0;
                mo.inside = isodel::Inside::Below;
                mo.eps_voxels = eps_voxels;
                mo.threads = threads;
                mo.adaptive = adaptive || scene.adaptive_only;
                if (field_input) mo.adaptive_field = isodel::AdaptiveField::Input;
                const auto t0 = std::chrono::steady_clock::now();
                const isodel::MeshResult m = isodel::mesh_isosurface(*grid, mo);
                s.total = seconds_since(t0);
                const auto& sec = m.stats.seconds;
                const auto at = [&](const char* k) { return sec.count(k) ? sec.at(k) : 0.0; };
                s.grid = at("adaptive_grid");
                s.points = at("points");
                s.delaunay = at("delaunay");
                s.closed_ball = at("closed_ball");
                s.refine = at("refine");
                s.extract = at("extract");
                s.vertices = (long long)m.surface.vertices.size();
            }));
            vdb.push_back(in_child([&](Sample& s) {
                std::vector<openvdb::Vec3s> points;
                std::vector<openvdb::Vec3I> tris;
                std::vector<openvdb::Vec4I> quads;
                const auto t0 = std::chrono::steady_clock::now();
                openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0);
                s.total = seconds_since(t0);
                s.vertices = (long long)points.size();
            }));
        }
        const auto med = [&](double Sample::*f, const std::vector<Sample>& v) {
            std::vector<double> x;
            for (const Sample& s : v) x.push_back(s.*f);
            return median(x);
        };
        if (!runs.front().ok) {
            std::printf("%-10s failed: %s\n", scene.name, runs.front().message);
            continue;
        }
        const openvdb::Coord d = box.dim();
        char dims[32];
        std::snprintf(dims, sizeof dims, "%dx%dx%d", d.x(), d.y(), d.z());
        std::printf("%-10s %10llu %16s %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %8.1f %9lld %8.3f %8.1f\n", scene.name,
                    (unsigned long long)grid->activeVoxelCount(), dims, med(&Sample::total, runs),
                    med(&Sample::grid, runs), med(&Sample::points, runs), med(&Sample::delaunay, runs), med(&Sample::closed_ball, runs),
                    med(&Sample::refine, runs), med(&Sample::extract, runs), med(&Sample::peak_mib, runs),
                    runs.front().vertices, med(&Sample::total, vdb), med(&Sample::peak_mib, vdb));
    }
    return 0;
}
