// mesh_isosurface_file (include/isodel/mesh.h, src/surface/partitioned_file.cpp): processes that
// each read one slab of the file and then only their blocks' boxes mesh, byte for byte, what one
// process meshes on the whole volume; the tie rule's level (samples and saddles at v) is the
// whole volume's; and no process reads the whole file. The processes are threads here, joined
// by an in-process transport that does what MPI's all-gather does.
#include "support/mesher_test_support.h"
#include "support/random_volume.h"
#include "support/test_files.h"
#include "support/verify_test_support.h"

#include <isodel/errors.h>
#include <isodel/mesh.h>
#include <isodel/volume.h>

#include <catch2/catch.hpp>

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

using namespace isodel;
using namespace isodel::test;

namespace {

/// The collective steps of \p size threads: every all_gather waits for all of them.
class InProcessRun {
public:
    explicit InProcessRun(int size) : size_(size), slots_(std::size_t(size)) {}
    int size() const { return size_; }
    std::vector<double> all_gather(int rank, const std::vector<double>& mine)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        slots_[std::size_t(rank)] = mine;
        const long generation = generation_;
        if (++arrived_ == size_) {
            result_.clear();
            for (const auto& s : slots_) result_.insert(result_.end(), s.begin(), s.end());
            arrived_ = 0;
            ++generation_;
            done_.notify_all();
        } else {
            done_.wait(lock, [&] { return generation_ != generation; });
        }
        return result_; // the next round cannot finish before this thread has taken its copy
    }

private:
    int size_;
    std::mutex mutex_;
    std::condition_variable done_;
    std::vector<std::vector<double>> slots_;
    std::vector<double> result_;
    int arrived_ = 0;
    long generation_ = 0;
};

class InProcessTransport : public BlockTransport {
public:
    InProcessTransport(InProcessRun& run, int rank) : run_(run), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return run_.size(); }
    std::vector<double> all_gather(const std::vector<double>& mine) override { return run_.all_gather(rank_, mine); }
    std::vector<double> gather_to_first(const std::vector<double>& mine) override
    {
        std::vector<double> all = run_.all_gather(rank_, mine);
        return rank_ == 0 ? all : std::vector<double>{};
    }

private:
    InProcessRun& run_;
    int rank_;
};

/// Writes \p grid's samples on \p lattice as a float MRC file (x fastest, index = file index).
void write_mrc(const std::string& path, const openvdb::FloatGrid& grid, const openvdb::CoordBBox& lattice)
{
    REQUIRE(lattice.min() == openvdb::Coord(0));
    MrcSpec s;
    s.n = {lattice.dim().x(), lattice.dim().y(), lattice.dim().z()};
    const auto acc = grid.getConstAccessor();
    write_bytes(path, mrc_bytes(s, [&](int x, int y, int z) { return double(acc.getValue(openvdb::Coord(x, y, z))); }));
}

/// Which overload of mesh_isosurface_file every process calls: the path, or the header read
/// first, as `isodel mesh` does (every process the same one: both read the header collectively).
enum class Entry { Path, Header };

/// \p processes threads run mesh_isosurface_file on \p path; the first one's result.
MeshResult mesh_on_processes(const std::string& path, MeshOptions mo, int processes, Entry entry = Entry::Path)
{
    InProcessRun run(processes);
    std::vector<MeshResult> results(static_cast<std::size_t>(processes));
    std::vector<std::exception_ptr> failures(static_cast<std::size_t>(processes));
    std::vector<std::thread> threads;
    for (int r = 0; r < processes; ++r)
        threads.emplace_back([&, r] {
            try {
                InProcessTransport t(run, r);
                MeshOptions mine = mo;
                mine.transport = &t;
                ReadOptions header;
                header.regions = std::vector<openvdb::CoordBBox>{};
                results[std::size_t(r)] = entry == Entry::Header
                                              ? mesh_isosurface_file(read_volume(path, header), ReadOptions{}, mine)
                                              : mesh_isosurface_file(path, ReadOptions{}, mine);
            } catch (...) {
                failures[std::size_t(r)] = std::current_exception();
            }
        });
    for (auto& t : threads) t.join();
    for (const auto& f : failures)
        if (f) std::rethrow_exception(f);
    for (int r = 1; r < processes; ++r) CHECK(results[std::size_t(r)].surface.vertices.empty());
    return results[0];
}

void check_same_mesh(const SurfaceMesh& a, const SurfaceMesh& b)
{
    REQUIRE(a.vertices.size() == b.vertices.size());
    REQUIRE(a.triangles.size() == b.triangles.size());
    CHECK(a.vertices == b.vertices);
    CHECK(a.triangles == b.triangles);
}

struct Case {
    const char* name;
    openvdb::FloatGrid::Ptr grid;
    double isovalue;
    Inside inside;
};

std::vector<Case> cases()
{
    return {{"torus", testing::make_grid(32, 1.0, openvdb::Vec3d(0.0),
                                         [](const openvdb::Vec3d& x) {
                                             return testing::torus_f(x, openvdb::Vec3d(15.5, 15.3, 15.7), 8.0, 3.0);
                                         }),
             0.0, Inside::Above},
            // Quantized samples: many equal v, and so do face and cell saddles; the tie rule's
            // level must be the whole volume's, not a slab's.
            {"quantized", testing::random_volume(11, 7, true), 0.0, Inside::Above}};
}

} // namespace

TEST_CASE("processes reading only their slab and blocks mesh what one process meshes on the whole file",
          "[mesher][partition][io]")
{
    TempDir tmp;
    for (const Case& c : cases()) {
        const std::string path = tmp / (std::string(c.name) + ".mrc");
        write_mrc(path, *c.grid, c.grid->evalActiveVoxelBoundingBox());
        const Volume whole = read_volume(path);
        for (const bool count : {true, false})
            for (int processes : {2, 3}) {
                // Three processes start from the header read first: both entry points mesh alike.
                const Entry entry = processes == 3 ? Entry::Header : Entry::Path;
                INFO(c.name << (count ? ": a balanced block per process" : ": blocks of 12 voxels") << ", "
                            << processes << " processes" << (entry == Entry::Header ? ", from the header" : ""));
                MeshOptions mo;
                mo.isovalue = c.isovalue;
                mo.inside = c.inside;
                mo.eps_voxels = 0.5;
                mo.threads = 1;
                if (count) mo.block_count = processes;
                else mo.block_voxels = 12;
                const MeshResult one = mesh_isosurface(*whole.grid, mo);
                const MeshResult parts = mesh_on_processes(path, mo, processes, entry);
                check_same_mesh(parts.surface, one.surface);
                CHECK(parts.stats.effective_isovalue == one.stats.effective_isovalue);
                if (std::string(c.name) == "quantized") CHECK(one.stats.effective_isovalue < c.isovalue); // a tie
                const PartitionStats& ps = parts.stats.partition;
                CHECK(ps.processes == processes);
                CHECK(ps.file_samples == whole.grid->tree().leafCount() * 512); // leaves covering the lattice
                // Its slab, or its block with its collar: not the whole file (counted in leaves of
                // 8^3 samples; on volumes this small, cubes with collars and the quantized
                // volume's slabs meet every leaf).
                CHECK(ps.max_process_samples_read > 0);
                if (count && std::string(c.name) == "torus") CHECK(ps.max_process_samples_read < ps.file_samples);
            }
    }
}

TEST_CASE("processes reading a delay-loaded .vdb level set mesh what one process meshes on the whole file",
          "[mesher][partition][io]")
{
    const std::string path = std::string(ISODEL_TEST_DATA) + "/torus.vdb";
    const Volume whole = read_volume(path);
    for (int processes : {2, 3}) {
        INFO(processes << " processes");
        MeshOptions mo;
        mo.isovalue = 0.0;
        mo.eps_voxels = 0.5;
        mo.threads = 1;
        mo.block_count = processes;
        const MeshResult one = mesh_isosurface(*whole.grid, mo);
        const MeshResult parts = mesh_on_processes(path, mo, processes, processes == 3 ? Entry::Header : Entry::Path);
        check_same_mesh(parts.surface, one.surface);
        const PartitionStats& ps = parts.stats.partition;
        CHECK(ps.file_samples == whole.grid->tree().leafCount() * 512);
        CHECK(ps.max_process_samples_read > 0);
        CHECK(ps.max_process_samples_read < ps.file_samples); // some leaves never loaded
    }
}

TEST_CASE("an isovalue outside the file's samples is refused on every process, naming the file",
          "[mesher][partition][io]")
{
    TempDir tmp;
    const Case c = cases()[0];
    const std::string path = tmp / "torus.mrc";
    write_mrc(path, *c.grid, c.grid->evalActiveVoxelBoundingBox());
    MeshOptions mo;
    mo.isovalue = 1e6;
    mo.inside = Inside::Above;
    mo.block_count = 2;
    try {
        mesh_on_processes(path, mo, 2);
        FAIL("expected InvalidInput");
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        CHECK(what.find(path) != std::string::npos);
        CHECK(what.find("outside the value range") != std::string::npos);
    }
}
