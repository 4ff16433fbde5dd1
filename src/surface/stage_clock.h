#pragma once
// The clock of the stage timings (MeshStats::seconds): steady, so a wall-clock jump cannot make
// a stage take negative time.
#include <chrono>

namespace isodel::mesher {

using StageClock = std::chrono::steady_clock;

inline double seconds_since(StageClock::time_point t0)
{
    return std::chrono::duration<double>(StageClock::now() - t0).count();
}

} // namespace isodel::mesher
