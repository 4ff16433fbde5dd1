// compare_bench: the benchmark of the speed targets against the field. For each volume and each eps it runs, in
// one process and interleaved within every repetition, each method in its own forked child (so
// the peak memory, getrusage's ru_maxrss through wait4, is per method, and a crash or a timeout
// only loses that row):
//
//   isodel 1thr    isodel::mesh_isosurface, surface, threads = 1
//   isodel 2thr    the same, threads = 2
//   isodel blocks  the same, partitioned: MeshOptions::block_voxels = --blocks (32), threads = 2
//   isodel adaptive  MeshOptions::adaptive (certified octree, guarantees against the input), threads = 2
//   isodel adapt-in  the same with adaptive_field = Input (the input's own F, seeds from the octree)
//   isodel+tets    the same with MeshOptions::tets = Inside, threads = 2
//   Mesh_3 surf    CGAL Mesh_3 on an implicit domain evaluating the same trilinear interpolant F
//                  (as tools/bench/tet_quality_vs_mesh3.cpp): facet_distance = eps, facet_angle 30,
//                  facet_size 4 voxels, no cell criteria, no perturb, no exude
//   Mesh_3 tets    the same facet criteria + cell_radius_edge_ratio 3, cell_size 4 voxels,
//                  perturb + exude
//   VDB v2m        openvdb::tools::volumeToMesh(grid, points, tris, quads, isovalue), adaptivity 0
//                  (no guarantees: the speed floor; uses TBB's default thread count, here 2)
//   DT(E+G+N)      CGAL Delaunay_triangulation_3<EPICK>, spatially sorted insertion
//                  (dt.insert(begin, end)), of isodel's own final point set E u G u N
//                  (MeshResult::points of the "isodel 2thr" run of the same repetition, with
//                  mesher::mesh_keeping_points). Only the insertion is timed.
//   DT traits      the same with isodel's Delaunay traits (src/delaunay/delaunay_traits.h)
//
// Times are wall-clock (steady_clock) around the method only (the volume is read before the
// clock starts), medians over --reps. Peak memory is the child's whole peak RSS (it includes the
// volume and the small parent image it forked from). The column "isodel/this" is the median time
// of "isodel 2thr" (of "isodel+tets" for the Mesh_3 tets row) divided by this row's median time.
//
//   compare_bench [--data DIR] [--filter S1,S2] [--all] [--eps-voxels 0.5,0.1] [--reps 3]
//                 [--timeout SECONDS] [--methods i1,i2,ib,ia,ii,it,ms,mt,vdb,dt,dtx] [--blocks 32] [--quick]
// --quick = --reps 1 --eps-voxels 0.5 on 3 volumes (molmap protein, torus, skull).
#include <isodel/mesh.h>
#include <isodel/volume.h>

#include "octree/sample_field.h"
#include "octree/segment_walk.h"
#include "surface/final_points.h"

#include "support/bench_support.h"
#include "delaunay/delaunay_traits.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace {

using isodel::bench::isodel_topology;
using isodel::bench::soup_topology;
using isodel::bench::split;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using DT = CGAL::Delaunay_triangulation_3<K>;
using V3 = std::array<double, 3>;
using Tri = std::array<std::int64_t, 3>;

enum Method { I1, I2, IB, IA, IAI, IT, MS, MT, VDB, DTM, DTX, NMETHODS };
const char* kKey[NMETHODS] = {"i1", "i2", "ib", "ia", "ii", "it", "ms", "mt", "vdb", "dt", "dtx"};
const char* kLabel[NMETHODS] = {"isodel 1thr", "isodel 2thr", "isodel blocks 2thr", "isodel adaptive 2thr", "isodel adapt-in 2thr", "isodel+tets 2thr", "Mesh_3 surf",
                                "Mesh_3 tets", "VDB volumeToMesh", "DT(E+G+N)", "DT(E+G+N) traits"};
int g_block_voxels = 32; ///< --blocks: block size of the "isodel blocks" row

/// What a child sends back (fixed size), followed for isodel 2thr by the vertices of M.
struct ChildResult {
    int ok = 0;
    double secs = 0;
    long long vertices = -1, triangles = -1, tets = -1;
    long long extra = -1; ///< isodel: |E|+|G|+|N|; DT: |P|
    char topo[200] = "";
    char msg[300] = "";
    long long payload_points = 0;
};

struct Run {
    bool ok = false, timeout = false;
    double secs = 0, peak_mib = 0;
    long long vertices = -1, triangles = -1, tets = -1, extra = -1;
    std::string topo, msg;
};

struct Dataset {
    std::string file, grid_name, dims;
    double isovalue = 0;
    isodel::Inside inside = isodel::Inside::Above;
};

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void copy_str(char* dst, std::size_t n, const std::string& s)
{
    std::snprintf(dst, n, "%s", s.c_str());
}

std::string phases(const isodel::MeshStats& st)
{
    std::string s;
    char buf[64];
    for (const char* k : {"blocks", "points", "delaunay", "closed_ball", "refine", "tets"}) {
        auto it = st.seconds.find(k);
        if (it == st.seconds.end()) continue;
        std::snprintf(buf, sizeof buf, "%s%s %.2f", s.empty() ? "" : ", ", k, it->second);
        s += buf;
    }
    // The three largest steps of closed_ball + refine (MeshStats::refinement_seconds).
    std::vector<std::pair<double, std::string>> steps;
    for (const auto& [k, v] : st.refinement_seconds) steps.emplace_back(-v, k);
    std::sort(steps.begin(), steps.end());
    for (std::size_t i = 0; i < steps.size() && i < 3; ++i) {
        std::snprintf(buf, sizeof buf, "%s%s %.2f", i ? ", " : "; steps: ", steps[i].second.c_str(), -steps[i].first);
        s += buf;
    }
    return s;
}

/// Mesh_3 on the implicit trilinear domain (negative inside, as Labeled_mesh_domain_3 wants).
void run_mesh3(const isodel::octree::SampleField& field, double eps, bool tets, ChildResult& out)
{
    const auto t0 = std::chrono::steady_clock::now();
    const isodel::octree::SampleField::Reader reader(field);
    auto f = [&](const K::Point_3& p) {
        const auto q = field.world_to_index({p.x(), p.y(), p.z()});
        return -isodel::octree::phi_at(reader, q);
    };
    const openvdb::CoordBBox box = field.domain();
    const auto lo_w = field.index_to_world(box.min().asVec3d()), hi_w = field.index_to_world(box.max().asVec3d());
    const K::Point_3 centre((lo_w[0] + hi_w[0]) / 2, (lo_w[1] + hi_w[1]) / 2, (lo_w[2] + hi_w[2]) / 2);
    const double r2 = 0.26 * ((hi_w - lo_w).lengthSqr()) + 4 * eps * eps;
    namespace params = CGAL::parameters;
    Domain domain = Domain::create_implicit_mesh_domain(f, K::Sphere_3(centre, r2), params::relative_error_bound = 1e-6);
    const double h = 4 * field.min_voxel_edge();
    C3t3 c3t3;
    if (tets) {
        Criteria criteria(params::facet_angle = 30, params::facet_size = h, params::facet_distance = eps,
                          params::cell_radius_edge_ratio = 3, params::cell_size = h);
        c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::perturb(), params::exude());
    } else {
        Criteria criteria(params::facet_angle = 30, params::facet_size = h, params::facet_distance = eps);
        c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude());
    }
    out.secs = seconds_since(t0);
    // Counts and topology (untimed).
    std::unordered_map<const void*, std::int64_t> id;
    auto vid = [&](Tr::Vertex_handle v) {
        auto it = id.find(&*v);
        if (it != id.end()) return it->second;
        const std::int64_t n = std::int64_t(id.size());
        id.emplace(&*v, n);
        return n;
    };
    std::vector<Tri> tris;
    for (auto fit = c3t3.facets_in_complex_begin(); fit != c3t3.facets_in_complex_end(); ++fit) {
        const auto c = fit->first;
        const int i = fit->second;
        Tri t;
        for (int j = 0, k = 0; j < 4; ++j)
            if (j != i) t[k++] = vid(c->vertex(j));
        tris.push_back(t);
    }
    const std::size_t surface_vertices = id.size();
    long long ncells = 0;
    for (auto cit = c3t3.cells_in_complex_begin(); cit != c3t3.cells_in_complex_end(); ++cit) {
        ++ncells;
        for (int j = 0; j < 4; ++j) vid(cit->vertex(j));
    }
    out.vertices = (long long)id.size();
    out.triangles = (long long)tris.size();
    out.tets = tets ? ncells : 0;
    out.extra = (long long)surface_vertices;
    copy_str(out.topo, sizeof out.topo, soup_topology(tris));
    out.ok = 1;
}

/// Body of a child: run one method, fill \p out (and \p payload for isodel 2thr).
void child_run(Method m, const std::string& path, const Dataset& ds, double eps_voxels, const std::vector<V3>& dt_input,
               ChildResult& out, std::vector<V3>& payload)
{
    isodel::ReadOptions ro;
    ro.grid_name = ds.grid_name;
    const isodel::Volume vol = isodel::read_volume(path, ro);
    if (m == I1 || m == I2 || m == IB || m == IA || m == IAI || m == IT) {
        isodel::MeshOptions mo;
        mo.isovalue = ds.isovalue;
        mo.inside = ds.inside;
        mo.eps_voxels = eps_voxels;
        mo.threads = m == I1 ? 1 : 2;
        if (m == IT) mo.tets = isodel::TetRegion::Inside;
        if (m == IB) mo.block_voxels = g_block_voxels;
        mo.adaptive = m == IA || m == IAI; // MeshOptions::adaptive, certified against the input
        if (m == IAI) mo.adaptive_field = isodel::AdaptiveField::Input; // seeds from the octree, F from the input
        std::vector<std::array<double, 3>> points; // for the DT(E+G+N) row
        const auto t0 = std::chrono::steady_clock::now();
        isodel::MeshResult r =
            m == I2 ? isodel::mesher::mesh_keeping_points(*vol.grid, mo, points) : isodel::mesh_isosurface(*vol.grid, mo);
        out.secs = seconds_since(t0);
        out.vertices = (long long)(m == IT ? r.tets.vertices.size() : r.surface.vertices.size());
        out.triangles = (long long)r.surface.triangles.size();
        out.tets = (long long)r.tets.tets.size();
        out.extra = (long long)(r.stats.e_points + r.stats.g_points + r.stats.n_topology + r.stats.n_geometry);
        copy_str(out.topo, sizeof out.topo, isodel_topology(r.stats));
        copy_str(out.msg, sizeof out.msg, phases(r.stats));
        if (m == I2) payload = std::move(points);
        out.ok = 1;
        return;
    }
    const isodel::octree::SampleField field(vol.grid, ds.isovalue, ds.inside);
    const double eps = eps_voxels * field.min_voxel_edge();
    if (m == MS || m == MT) {
        run_mesh3(field, eps, m == MT, out);
        return;
    }
    if (m == VDB) {
        std::vector<openvdb::Vec3s> points;
        std::vector<openvdb::Vec3I> tris;
        std::vector<openvdb::Vec4I> quads;
        const auto t0 = std::chrono::steady_clock::now();
        openvdb::tools::volumeToMesh(*vol.grid, points, tris, quads, ds.isovalue, 0.0);
        out.secs = seconds_since(t0);
        out.vertices = (long long)points.size();
        out.triangles = (long long)(tris.size() + 2 * quads.size());
        out.tets = 0;
        out.ok = 1;
        return;
    }
    if (m == DTM || m == DTX) {
        if (dt_input.empty()) {
            copy_str(out.msg, sizeof out.msg, "no isodel 2thr mesh in this repetition");
            return;
        }
        std::vector<K::Point_3> pts;
        pts.reserve(dt_input.size());
        for (const auto& v : dt_input) pts.emplace_back(v[0], v[1], v[2]);
        // DT: CGAL's EPICK, the baseline. DTX: the same points with isodel's own
        // Delaunay traits (src/delaunay/delaunay_traits.h: exact shortcuts for the in-sphere tests
        // that are exactly 0 on grid points), what isodel's triangulation of them costs.
        const auto triangulate = [&](auto dt) {
            const auto t0 = std::chrono::steady_clock::now();
            dt.insert(pts.begin(), pts.end());
            out.secs = seconds_since(t0);
            out.vertices = (long long)dt.number_of_vertices();
            out.tets = (long long)dt.number_of_finite_cells();
        };
        if (m == DTM) triangulate(DT());
        else triangulate(CGAL::Delaunay_triangulation_3<isodel::mesher::DelaunayTraits>());
        out.triangles = 0;
        out.extra = (long long)pts.size();
        out.ok = 1;
    }
}

bool write_all(int fd, const void* p, std::size_t n)
{
    const char* c = static_cast<const char*>(p);
    while (n) {
        const ssize_t w = ::write(fd, c, n);
        if (w <= 0) return false;
        c += w;
        n -= std::size_t(w);
    }
    return true;
}

/// Forks, runs \p m in the child, collects its result, time and peak RSS.
Run run_forked(Method m, const std::string& path, const Dataset& ds, double eps_voxels, int timeout,
               std::vector<V3>& dt_input)
{
    Run run;
    int fds[2];
    if (::pipe(fds) != 0) {
        run.msg = "pipe failed";
        return run;
    }
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t pid = ::fork();
    if (pid < 0) {
        run.msg = "fork failed";
        return run;
    }
    if (pid == 0) {
        ::close(fds[0]);
        if (timeout > 0) ::alarm(unsigned(timeout));
        ChildResult out;
        std::vector<V3> payload;
        try {
            child_run(m, path, ds, eps_voxels, dt_input, out, payload);
        } catch (const std::exception& e) {
            out.ok = 0;
            copy_str(out.msg, sizeof out.msg, e.what());
        }
        out.payload_points = (long long)payload.size();
        write_all(fds[1], &out, sizeof out);
        if (!payload.empty()) write_all(fds[1], payload.data(), payload.size() * sizeof(V3));
        ::close(fds[1]);
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string buf;
    char chunk[1 << 16];
    for (;;) {
        const ssize_t r = ::read(fds[0], chunk, sizeof chunk);
        if (r <= 0) break;
        buf.append(chunk, std::size_t(r));
    }
    ::close(fds[0]);
    int status = 0;
    struct rusage ru {};
    ::wait4(pid, &status, 0, &ru);
    run.peak_mib = double(ru.ru_maxrss) / 1024.0; // KiB on Linux
    if (WIFSIGNALED(status)) {
        run.timeout = WTERMSIG(status) == SIGALRM;
        run.msg = run.timeout ? "timeout after " + std::to_string(timeout) + " s"
                              : "killed by signal " + std::to_string(WTERMSIG(status));
        if (run.timeout) run.secs = timeout;
        return run;
    }
    if (buf.size() < sizeof(ChildResult)) {
        run.msg = "child exited without a result (status " + std::to_string(WEXITSTATUS(status)) + ")";
        return run;
    }
    ChildResult out;
    std::memcpy(&out, buf.data(), sizeof out);
    run.ok = out.ok;
    run.secs = out.secs;
    run.vertices = out.vertices;
    run.triangles = out.triangles;
    run.tets = out.tets;
    run.extra = out.extra;
    run.topo = out.topo;
    run.msg = out.msg;
    if (m == I2) {
        dt_input.clear();
        if (out.ok && buf.size() == sizeof out + std::size_t(out.payload_points) * sizeof(V3)) {
            dt_input.resize(std::size_t(out.payload_points));
            std::memcpy(dt_input.data(), buf.data() + sizeof out, dt_input.size() * sizeof(V3));
        }
    }
    return run;
}

double median(std::vector<double> v)
{
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Summary {
    bool have = false, timed_out = false;
    double secs = NAN, mib = NAN;
    Run last; ///< counts and topology of the last successful run (or the last failure)
    int failures = 0;
};

Summary summarise(const std::vector<Run>& runs)
{
    Summary s;
    std::vector<double> t, mem;
    for (const auto& r : runs) {
        if (r.ok) {
            t.push_back(r.secs);
            mem.push_back(r.peak_mib);
            s.last = r;
        } else {
            ++s.failures;
            s.timed_out |= r.timeout;
            if (!s.have) s.last = r;
        }
        s.have = s.have || r.ok;
    }
    s.secs = median(t);
    s.mib = median(mem);
    return s;
}

std::string fmt_count(long long n) { return n < 0 ? "-" : std::to_string(n); }

std::string fmt_ratio(double num, double den)
{
    if (!(num > 0) || !(den > 0)) return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%.3g", num / den);
    return b;
}

} // namespace

int main(int argc, char** argv)
{
    std::string f = __FILE__;
    std::string data = f.substr(0, f.rfind("/tools/bench/")) + "/../shared/data";
    std::vector<std::string> filters{"ct/skull_2.9.vdb",       "protein/1hpv_molmap_6A_2A.vdb", "protein/1hpv_blobby_1A.vdb",
                                     "em/emd3001.vdb",         "levelset/bunny.vdb",            "analytic/torus.vdb",
                                     "analytic/genus3.vdb",    "analytic/tangle_cube.vdb",      "analytic/gyroid_ball.vdb",
                                     "analytic/marschner_lobb.vdb"};
    std::vector<double> eps_list{0.5, 0.1};
    int reps = 3, timeout = 600;
    bool all = false, quick = false;
    std::vector<bool> enabled(NMETHODS, true);
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::cerr << "compare_bench: " << a << " needs a value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--data") data = next();
        else if (a == "--filter") filters = split(next());
        else if (a == "--all") all = true;
        else if (a == "--eps-voxels") {
            eps_list.clear();
            for (const auto& e : split(next())) eps_list.push_back(std::stod(e));
        } else if (a == "--reps") reps = std::max(1, std::stoi(next()));
        else if (a == "--timeout") timeout = std::stoi(next());
        else if (a == "--blocks") g_block_voxels = std::max(1, std::stoi(next()));
        else if (a == "--methods") {
            std::fill(enabled.begin(), enabled.end(), false);
            for (const auto& k : split(next()))
                for (int m = 0; m < NMETHODS; ++m)
                    if (k == kKey[m]) enabled[std::size_t(m)] = true;
        } else if (a == "--quick") quick = true;
        else {
            std::cerr << "usage: compare_bench [--data DIR] [--filter S1,S2] [--all] [--eps-voxels 0.5,0.1] [--reps 3]\n"
                         "                     [--timeout SECONDS] [--methods i1,i2,ib,ia,ii,it,ms,mt,vdb,dt,dtx] [--blocks 32] [--quick]\n";
            return 2;
        }
    }
    if (quick) {
        reps = 1;
        eps_list = {0.5};
        filters = {"protein/1hpv_molmap_6A_2A.vdb", "analytic/torus.vdb", "ct/skull_2.9.vdb"};
    }
    if (enabled[DTM] || enabled[DTX]) enabled[I2] = true; // the Delaunay rows need isodel 2thr's points
    openvdb::initialize(); // registers grid types only; no TBB work happens in this (forking) process

    std::ifstream in(data + "/manifest.json");
    if (!in) {
        std::cerr << "compare_bench: cannot read " << data << "/manifest.json\n";
        return 2;
    }
    std::stringstream ss;
    ss << in.rdbuf();
    const nlohmann::json manifest = nlohmann::json::parse(ss.str());
    std::vector<Dataset> sets;
    using isodel::bench::json_string;
    for (const auto& e : manifest) {
        if (isodel::bench::expects_error(e)) continue;
        if (json_string(e, "format") != "vdb") continue;
        const std::string file = json_string(e, "file");
        if (all) {
            if (json_string(e, "category") == "invalid" || file.rfind("cells/", 0) == 0) continue;
        } else if (std::none_of(filters.begin(), filters.end(),
                                [&](const std::string& s) { return file.find(s) != std::string::npos; }))
            continue;
        Dataset d;
        d.file = file;
        d.grid_name = json_string(e, "grid_name");
        d.isovalue = isodel::bench::json_number(e, "isovalue");
        d.inside = json_string(e, "inside") == "below" ? isodel::Inside::Below : isodel::Inside::Above;
        d.dims = isodel::bench::dims_string(e);
        sets.push_back(d);
    }
    if (sets.empty()) {
        std::cerr << "compare_bench: no volume matches\n";
        return 2;
    }

    char host[128] = "";
    ::gethostname(host, sizeof host);
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    std::printf("compare_bench: %s, %ld cores online, reps %d (medians), timeout %d s per run\n", date,
                ::sysconf(_SC_NPROCESSORS_ONLN), reps, timeout);
    std::printf("isodel/this = median time of isodel 2thr (isodel+tets 2thr for Mesh_3 tets) / this row's; < 1: isodel faster.\n"
                "DT(E+G+N) = CGAL Delaunay_triangulation_3<EPICK>, spatially sorted insert, of isodel 2thr's final point\n"
                "          set E u G u N (MeshResult::points). DT(E+G+N) traits = the same with isodel's Delaunay traits\n"
                "          (src/delaunay/delaunay_traits.h).\n"
                "Peak MiB = the forked child's whole ru_maxrss (volume included). VDB volumeToMesh runs on TBB's default threads.\n");

    struct Totals {
        std::string file, dims;
        Summary s[NMETHODS];
    };
    for (double eps : eps_list) {
        std::printf("\n== eps = %.2f voxel ==\n", eps);
        std::printf("%-30s %-11s %-18s %9s %8s %9s %9s %9s %8s  %s\n", "dataset", "dims", "method", "time_s", "peak_MiB",
                    "vertices", "triangles", "tets", "isodel/this", "topology / notes");
        std::vector<Totals> totals;
        for (const auto& ds : sets) {
            const std::string path = data + "/" + ds.file;
            std::vector<Run> runs[NMETHODS];
            for (int rep = 0; rep < reps; ++rep) {
                std::vector<V3> dt_input;
                for (int m = 0; m < NMETHODS; ++m) {
                    if (!enabled[std::size_t(m)]) continue;
                    std::fprintf(stderr, "[%s eps %.2f rep %d] %s ...\n", ds.file.c_str(), eps, rep + 1, kLabel[m]);
                    runs[m].push_back(run_forked(Method(m), path, ds, eps, timeout, dt_input));
                }
            }
            Totals t;
            t.file = ds.file;
            t.dims = ds.dims;
            for (int m = 0; m < NMETHODS; ++m) t.s[m] = summarise(runs[m]);
            const double iso2 = t.s[I2].have ? t.s[I2].secs : NAN, isot = t.s[IT].have ? t.s[IT].secs : NAN;
            for (int m = 0; m < NMETHODS; ++m) {
                if (!enabled[std::size_t(m)]) continue;
                const Summary& s = t.s[m];
                std::string notes = s.last.topo;
                if (m == I1 || m == I2 || m == IB || m == IA || m == IAI || m == IT) {
                    if (s.last.extra >= 0) notes += (notes.empty() ? "" : "; ") + std::string("|E+G+N| ") + std::to_string(s.last.extra);
                    if (!s.last.msg.empty()) notes += (s.have ? "; phases: " : "ERROR: ") + s.last.msg;
                } else if (m == DTM || m == DTX) {
                    if (s.last.extra >= 0) notes = "|P| " + std::to_string(s.last.extra);
                    if (!s.have && !s.last.msg.empty()) notes += "ERROR: " + s.last.msg;
                } else if (m == MS || m == MT) {
                    if (!s.have) notes = "ERROR: " + s.last.msg;
                    else if (m == MT) notes += "; surface vertices " + std::to_string(s.last.extra);
                } else if (!s.have) notes = "ERROR: " + s.last.msg;
                if (s.failures && s.have) notes += " (" + std::to_string(s.failures) + " failed runs: " + s.last.msg + ")";
                char tbuf[32], mbuf[32];
                if (s.have) std::snprintf(tbuf, sizeof tbuf, "%.3f", s.secs);
                else if (s.timed_out) std::snprintf(tbuf, sizeof tbuf, ">%d", timeout);
                else std::snprintf(tbuf, sizeof tbuf, "-");
                if (s.have) std::snprintf(mbuf, sizeof mbuf, "%.0f", s.mib);
                else std::snprintf(mbuf, sizeof mbuf, "-");
                const double num = m == MT ? isot : iso2;
                std::string ratio = (m == I2) ? (s.have ? "1" : "-") : (m == IT) ? "-" : fmt_ratio(num, s.have ? s.secs : NAN);
                if (!s.have && s.timed_out && num > 0) ratio = "<" + fmt_ratio(num, double(timeout));
                std::printf("%-30s %-11s %-18s %9s %8s %9s %9s %9s %8s  %s\n", ds.file.c_str(), ds.dims.c_str(), kLabel[m],
                            tbuf, mbuf, s.have ? fmt_count(s.last.vertices).c_str() : "-",
                            s.have ? fmt_count(s.last.triangles).c_str() : "-", s.have ? fmt_count(s.last.tets).c_str() : "-",
                            ratio.c_str(), notes.c_str());
            }
            std::fflush(stdout);
            totals.push_back(t);
        }
        std::printf("\n-- issue 7 targets at eps = %.2f voxel (medians) --\n", eps);
        std::printf("%-30s %-11s %16s %16s %16s %14s %16s\n", "dataset", "dims", "Mesh3surf/isodel", "Mesh3tets/i+tets",
                    "isodel/DT(E+G+N)", "1thr/2thr", "1thr/blocks2thr");
        std::printf("%-30s %-11s %16s %16s %16s %14s %16s\n", "target", "", ">= 3", ">= 20", "<= 3", ">= 1.6", "(>= 1.6)");
        for (const auto& t : totals) {
            auto sec = [&](Method m) { return t.s[m].have ? t.s[m].secs : NAN; };
            std::string mt = fmt_ratio(sec(MT), sec(IT));
            if (!t.s[MT].have && t.s[MT].timed_out && t.s[IT].have) mt = ">" + fmt_ratio(double(timeout), sec(IT));
            std::string ms = fmt_ratio(sec(MS), sec(I2));
            if (!t.s[MS].have && t.s[MS].timed_out && t.s[I2].have) ms = ">" + fmt_ratio(double(timeout), sec(I2));
            std::printf("%-30s %-11s %16s %16s %16s %14s %16s\n", t.file.c_str(), t.dims.c_str(), ms.c_str(), mt.c_str(),
                        fmt_ratio(sec(I2), sec(DTM)).c_str(), fmt_ratio(sec(I1), sec(I2)).c_str(),
                        fmt_ratio(sec(I1), sec(IB)).c_str());
        }
        std::fflush(stdout);
    }
    return 0;
}
