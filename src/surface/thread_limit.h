#pragma once
// Internal: MeshOptions::threads as TBB's limit for the scope of a run (0: no limit, TBB's
// default of every hardware thread). Only the time depends on it: every parallel stage merges
// its results in a fixed order, so the mesh is the same at any thread count.
#include <tbb/global_control.h>

#include <cstddef>
#include <memory>

namespace isodel::mesher {

class ThreadLimit {
public:
    explicit ThreadLimit(int threads)
    {
        if (threads > 0)
            limit_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                           std::size_t(threads));
    }

private:
    std::unique_ptr<tbb::global_control> limit_;
};

} // namespace isodel::mesher
