// fork_join_floor: what a second thread can give a job of a few microseconds on this machine,
// the floor under the 1- vs 2-thread ratio of the smallest volumes (docs/benchmarks.md, "The
// stages before the Delaunay triangulation"). A job of W microseconds of dependent arithmetic
// runs alone, then split into two halves with tbb::parallel_invoke, (a) back to back, the
// worker thread still awake from the last job, and (b) after --idle-us of the caller's own
// work, as a pipeline stage comes after the previous stage's serial part. Medians of --reps.
//
//   fork_join_floor [--reps 1001] [--idle-us 300]
#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
volatile double sink;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// n steps of a dependent multiply-add: no vectorisation, no memory traffic.
double work(long n)
{
    double x = 1.0;
    for (long i = 0; i < n; ++i) x = x * 1.0000001 + 1e-9;
    return x;
}

void spin_for(double us)
{
    const auto t0 = Clock::now();
    while (seconds_since(t0) < us * 1e-6) {
    }
}

/// The median time in microseconds of \p reps runs of a job of \p n steps at \p threads.
double median_us(long n, int threads, double idle_us, int reps)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    std::vector<double> t;
    for (int r = 0; r < reps; ++r) {
        if (idle_us > 0) spin_for(idle_us);
        const auto t0 = Clock::now();
        if (threads == 1) {
            sink = work(n);
        } else {
            double a = 0, b = 0;
            tbb::parallel_invoke([&] { a = work(n / 2); }, [&] { b = work(n - n / 2); });
            sink = a + b;
        }
        t.push_back(seconds_since(t0) * 1e6);
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
    int reps = 1001;
    double idle_us = 300;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--reps" && i + 1 < argc) reps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--idle-us" && i + 1 < argc) idle_us = std::atof(argv[++i]);
        else {
            std::fprintf(stderr, "fork_join_floor: unknown option %s\n", a.c_str());
            return 2;
        }
    }
    const auto t0 = Clock::now();
    const long calibration = 100000000;
    sink = work(calibration);
    const double steps_per_us = calibration / (seconds_since(t0) * 1e6);
    std::printf("%8s %9s %13s %6s %13s %6s\n", "job us", "1 thread", "2, awake", "x", "2, after idle", "x");
    for (double w : {2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 1000.0}) {
        const long n = long(w * steps_per_us);
        const double one = median_us(n, 1, 0, reps), awake = median_us(n, 2, 0, reps);
        const double idle = median_us(n, 2, idle_us, reps);
        std::printf("%8.0f %9.2f %13.2f %6.2f %13.2f %6.2f\n", w, one, awake, one / awake, idle, one / idle);
    }
    return 0;
}
