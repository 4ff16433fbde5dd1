// Dealing blocks to processes (surface/block_ranks.h): every block goes to exactly one process,
// the same deal on every process, and the work is balanced where round robin is not.
#include "surface/block_ranks.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

namespace {

// A process of a run of \p size, for the deal only (no collective step is called).
class FakeTransport : public isodel::BlockTransport {
public:
    FakeTransport(int rank, int size) : rank_(rank), size_(size) {}
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    std::vector<double> all_gather(const std::vector<double>& mine) override { return mine; }
    std::vector<double> gather_to_first(const std::vector<double>& mine) override { return mine; }

private:
    int rank_, size_;
};

// owner[i] for each block, read from every process's mine().
std::vector<int> owners(const std::vector<double>& work, int size)
{
    std::vector<int> owner(work.size(), -1);
    for (int r = 0; r < size; ++r) {
        FakeTransport t(r, size);
        isodel::mesher::BlockRanks ranks(&t);
        ranks.deal(work);
        const auto mine = ranks.mine(work.size());
        CHECK(std::is_sorted(mine.begin(), mine.end()));
        for (std::size_t i : mine) {
            CHECK(owner[i] == -1); // one owner only
            owner[i] = r;
        }
    }
    return owner;
}

std::vector<double> loads(const std::vector<double>& work, const std::vector<int>& owner, int size)
{
    std::vector<double> load(std::size_t(size), 0.0);
    for (std::size_t i = 0; i < work.size(); ++i) load[std::size_t(owner[i])] += work[i];
    return load;
}

} // namespace

TEST_CASE("blocks are dealt by work: each to one process, balanced where round robin is not", "[mesher][partition]")
{
    // Dense layers at even block indices: round robin over 2 processes gives one all of them.
    std::vector<double> work;
    for (int i = 0; i < 12; ++i) work.push_back(i % 2 == 0 ? 100.0 + i : 1.0);
    const auto owner = owners(work, 2);
    CHECK(std::count(owner.begin(), owner.end(), -1) == 0);
    const auto load = loads(work, owner, 2);
    double total = 0;
    for (double w : work) total += w;
    const double largest = *std::max_element(work.begin(), work.end());
    // The longest processing time rule ends within the largest block of the even split.
    CHECK(*std::max_element(load.begin(), load.end()) <= total / 2 + largest);
    // Round robin put every dense block on process 0.
    double round_robin0 = 0;
    for (std::size_t i = 0; i < work.size(); i += 2) round_robin0 += work[i];
    CHECK(*std::max_element(load.begin(), load.end()) < round_robin0 * 0.6);

    // Ties go the same way on every process; more processes than blocks leave some idle.
    const std::vector<double> equal(5, 7.0);
    const auto o8 = owners(equal, 8);
    CHECK(o8 == std::vector<int>{0, 1, 2, 3, 4});
}

TEST_CASE("without a deal, and with one process, blocks go round robin or all to it", "[mesher][partition]")
{
    FakeTransport t(1, 3);
    const isodel::mesher::BlockRanks ranks(&t);
    CHECK(ranks.mine(7) == std::vector<std::size_t>{1, 4});
    isodel::mesher::BlockRanks alone(nullptr);
    alone.deal({5, 1, 3});
    CHECK(alone.mine(3) == std::vector<std::size_t>{0, 1, 2});
}
