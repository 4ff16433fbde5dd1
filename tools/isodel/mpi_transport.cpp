#include "mpi_transport.h"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#ifdef ISODEL_WITH_MPI
#include <mpi.h>
#endif

namespace isodel::cli {
namespace {

MpiSession* g_session = nullptr;

#ifdef ISODEL_WITH_MPI
/// MPI_COMM_WORLD as a BlockTransport: each collective is an MPI collective, called from the
/// thread that started MPI (MPI_THREAD_FUNNELED): the blocks' threads never call MPI.
class MpiTransport final : public BlockTransport {
public:
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    std::vector<double> all_gather(const std::vector<double>& mine) override { return gather(mine, true); }
    std::vector<double> gather_to_first(const std::vector<double>& mine) override { return gather(mine, false); }

    MpiTransport()
    {
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }

private:
    std::vector<double> gather(const std::vector<double>& mine, bool everywhere)
    {
        if (mine.size() > std::size_t(1) << 30) throw std::length_error("isodel: a block message of over 2^30 numbers");
        const int count = int(mine.size());
        std::vector<int> counts(std::size_t(size_), 0), offsets(std::size_t(size_), 0);
        MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
        long long total = 0;
        for (int r = 0; r < size_; ++r) {
            if (total > (1LL << 31) - 1) throw std::length_error("isodel: the gathered block messages exceed 2^31 numbers");
            offsets[std::size_t(r)] = int(total);
            total += counts[std::size_t(r)];
        }
        std::vector<double> all(everywhere || rank_ == 0 ? std::size_t(total) : 0);
        if (everywhere)
            MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                           MPI_COMM_WORLD);
        else
            MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
                        MPI_COMM_WORLD);
        return all;
    }

    int rank_ = 0, size_ = 1;
};
#endif

/// Did mpirun (Open MPI or a PMI launcher such as Slurm's srun) start this process?
bool launched_by_mpirun()
{
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

} // namespace

MpiSession::MpiSession(int& argc, char**& argv)
{
    g_session = this;
#ifdef ISODEL_WITH_MPI
    if (!launched_by_mpirun()) return;
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    started_ = true;
    transport_ = std::make_unique<MpiTransport>();
    rank_ = transport_->rank();
    size_ = transport_->size();
#else
    (void)argc;
    (void)argv;
#endif
}

MpiSession::~MpiSession()
{
#ifdef ISODEL_WITH_MPI
    if (started_) MPI_Finalize();
#endif
    g_session = nullptr;
}

MpiSession& mpi_session()
{
    if (!g_session) throw std::logic_error("isodel: no MPI session (main() starts one)");
    return *g_session;
}

} // namespace isodel::cli
