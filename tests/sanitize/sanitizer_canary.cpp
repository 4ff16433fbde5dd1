// The sanitizer builds' canary: one defect per sanitizer, which that sanitizer must report. CTest
// expects each run to fail (WILL_FAIL), so a sanitizer step that silently checks nothing (a
// runtime not loaded, a suppression too wide, UBSan not halting, an uninstrumented scheduler that
// hides a task body's race) fails the build instead of passing it.
//   sanitizer_canary address     reads past the end of a heap array
//   sanitizer_canary undefined   overflows a signed int
//   sanitizer_canary thread      two TBB task bodies running at once add to one int
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <tbb/partitioner.h>

#include <atomic>
#include <climits>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

int heap_overflow()
{
    std::vector<int> v(4, 1);
    const int* p = v.data();
    volatile int i = 4;
    return p[i];
}

int signed_overflow()
{
    volatile int big = INT_MAX;
    return big + 1;
}

int racy_sum()
{
    // Two task bodies that are running at the same time both add to one int. The first to start
    // waits (relaxed atomics: they order nothing for TSan) until the other has started, so
    // neither body's additions can be ordered before the other's by the scheduler's own
    // hand-offs, as they are when a worker steals its task only after the first body is over (a
    // loaded machine). Rounds until two bodies overlapped (bound: 100 rounds, each waiting 2^24
    // polls at most).
    int sum = 0;
    bool overlapped = false;
    int round = 0;
    for (; round < 100 && !overlapped; ++round) {
        std::atomic<int> started{0};
        std::atomic<bool> met{false};
        tbb::parallel_for(
            tbb::blocked_range<int>(0, 2, 1),
            [&](const tbb::blocked_range<int>&) {
                // The body that started first sees the second start while it is still running
                // (so on another thread).
                const bool first = started.fetch_add(1, std::memory_order_relaxed) == 0;
                for (long spin = 0; first && spin < (1L << 24) && started.load(std::memory_order_relaxed) < 2; ++spin) {
                }
                if (first && started.load(std::memory_order_relaxed) == 2) met.store(true, std::memory_order_relaxed);
                for (int i = 0; i < 1000; ++i) sum += i & 1;
            },
            tbb::simple_partitioner());
        overlapped = met.load();
    }
    std::fprintf(stderr, "bodies overlapped: %s (rounds: %d)\n", overlapped ? "yes" : "no", round);
    return sum;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: sanitizer_canary address|undefined|thread\n");
        return 2;
    }
    int r = 0;
    if (!std::strcmp(argv[1], "address")) r = heap_overflow();
    else if (!std::strcmp(argv[1], "undefined")) r = signed_overflow();
    else if (!std::strcmp(argv[1], "thread")) r = racy_sum();
    std::printf("no report (%d)\n", r);
    return 0;
}
