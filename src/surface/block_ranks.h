#pragma once
// Internal: the processes partitioned meshing runs on (partitioned_meshing.cpp): this one alone
// (MeshOptions::transport null, the blocks on its threads) or a BlockTransport's, MPI ranks for
// example. Every collective step goes through here, so the thread engine and the processes run
// the same code and make the same mesh.
#include <isodel/block_transport.h>
#include <isodel/errors.h>

#include <algorithm>
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
    /// Deals the blocks to the processes by their estimated \p work (the same numbers on every
    /// process): the largest first, each to the process with the least work so far (the longest
    /// processing time rule, within 4/3 of the best split), ties to the lower block and the lower
    /// rank, so that every process computes the same deal. Until deal is called, and with one
    /// process, blocks are dealt round robin. Which process meshes a block never changes the
    /// mesh: everything exchanged is put back in block order.
    void deal(const std::vector<double>& work)
    {
        owner_.assign(work.size(), 0);
        if (size() == 1) return;
        std::vector<std::size_t> order(work.size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return work[a] > work[b]; });
        std::vector<double> load(std::size_t(size()), 0.0);
        for (std::size_t i : order) {
            const std::size_t r = std::size_t(std::min_element(load.begin(), load.end()) - load.begin());
            owner_[i] = int(r);
            load[r] += work[i];
        }
    }
    /// This process's blocks of \p n, in block order.
    std::vector<std::size_t> mine(std::size_t n) const
    {
        std::vector<std::size_t> out;
        if (owner_.size() == n) {
            for (std::size_t i = 0; i < n; ++i)
                if (owner_[i] == rank()) out.push_back(i);
            return out;
        }
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
    std::vector<int> owner_; ///< per block, after deal
};

} // namespace isodel::mesher
