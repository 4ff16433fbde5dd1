#pragma once
// Internal: the processes partitioned meshing runs on (partitioned_meshing.cpp): this one alone
// (MeshOptions::transport null, the blocks on its threads) or a BlockTransport's, MPI ranks for
// example. Every collective step goes through here, so the thread engine and the processes run
// the same code and make the same mesh.
#include <isodel/block_transport.h>
#include <isodel/errors.h>

#include <cstddef>
#include <exception>
#include <numeric>
#include <string>
#include <vector>

namespace isodel::mesher {

class BlockRanks {
public:
    explicit BlockRanks(BlockTransport* transport) : t_(transport) {}
    int rank() const { return t_ ? t_->rank() : 0; }
    int size() const { return t_ ? t_->size() : 1; }
    bool first() const { return rank() == 0; }
    /// This process's blocks of \p n, in block order: every size()-th from rank(). Dealt round
    /// robin, since blocks in block order are layers of the volume, and the surface's share of a
    /// layer varies: contiguous runs would give one process the dense layers.
    std::vector<std::size_t> mine(std::size_t n) const
    {
        std::vector<std::size_t> out;
        for (std::size_t i = std::size_t(rank()); i < n; i += std::size_t(size())) out.push_back(i);
        return out;
    }

    std::vector<double> all_gather(const std::vector<double>& mine) const { return t_ ? t_->all_gather(mine) : mine; }
    std::vector<double> gather_to_first(const std::vector<double>& mine) const
    {
        return t_ ? t_->gather_to_first(mine) : mine;
    }
    double sum(double x) const
    {
        const std::vector<double> all = all_gather({x});
        return std::accumulate(all.begin(), all.end(), 0.0);
    }

    /// Collective: every process passes what its own work threw (or null); if any threw, every
    /// process throws, the one that failed its own exception and the others its message, so
    /// that no process waits forever for a failed one at the next step.
    void agree(std::exception_ptr failure) const
    {
        if (!t_) {
            if (failure) std::rethrow_exception(failure);
            return;
        }
        std::vector<double> mine{0.0, 0.0};
        if (failure) {
            int kind = 3;
            std::string what;
            try {
                std::rethrow_exception(failure);
            } catch (const GuaranteeViolated& e) {
                kind = 1, what = e.what();
            } catch (const Cancelled& e) {
                kind = 2, what = e.what();
            } catch (const std::exception& e) {
                what = e.what();
            }
            mine = {double(kind), double(what.size())};
            for (char c : what) mine.push_back(double(static_cast<unsigned char>(c)));
        }
        const std::vector<double> all = all_gather(mine);
        for (std::size_t i = 0, r = 0; i + 1 < all.size(); ++r) {
            const int kind = int(all[i]);
            const std::size_t len = std::size_t(all[i + 1]);
            if (kind != 0) {
                if (failure) std::rethrow_exception(failure);
                std::string what;
                for (std::size_t k = 0; k < len; ++k) what.push_back(char(int(all[i + 2 + k])));
                what = "process " + std::to_string(r) + ": " + what;
                if (kind == 1) throw GuaranteeViolated(what);
                if (kind == 2) throw Cancelled(what);
                throw InvalidInput(what);
            }
            i += 2 + len;
        }
    }

private:
    BlockTransport* t_;
};

} // namespace isodel::mesher
