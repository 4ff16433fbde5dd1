// The sanitizer builds' canary: one defect per sanitizer, which that sanitizer must report. CTest
// expects each run to fail (WILL_FAIL), so a sanitizer step that silently checks nothing (a
// runtime not loaded, a suppression too wide, UBSan not halting, an uninstrumented scheduler that
// hides a task body's race) fails the build instead of passing it.
//   sanitizer_canary address     reads past the end of a heap array
//   sanitizer_canary undefined   overflows a signed int
//   sanitizer_canary thread      two TBB tasks add to one int without synchronisation
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <tbb/task_arena.h>

#include <atomic>
#include <bitset>
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
    int sum = 0;
    // Rounds until two threads have run a body (a loaded machine may leave one idle for a
    // round); the thread record is relaxed, so it orders nothing for TSan.
    std::atomic<unsigned> threads_seen{0};
    for (int round = 0; round < 1000 && std::bitset<32>(threads_seen.load()).count() < 2; ++round)
        tbb::parallel_for(tbb::blocked_range<int>(0, 1 << 12, 1), [&](const tbb::blocked_range<int>& r) {
            const int t = tbb::this_task_arena::current_thread_index();
            threads_seen.fetch_or(1u << (t & 31), std::memory_order_relaxed);
            for (int i = r.begin(); i != r.end(); ++i) sum += i & 1;
        });
    std::fprintf(stderr, "threads seen %x\n", threads_seen.load());
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
