#pragma once
// The MPI ranks of `mpirun -np N isodel mesh ... --blocks B`: the BlockTransport of
// partitioned meshing (include/isodel/block_transport.h, docs/partitioned.md). MPI is started
// only when mpirun launched the process, so a plain `isodel` never initialises it, and only in a
// build with MPI (ISODEL_WITH_MPI); elsewhere the session is inactive.
#include <isodel/block_transport.h>

#include <memory>

namespace isodel::cli {

class MpiSession {
public:
    MpiSession(int& argc, char**& argv);
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    /// More than one process: the blocks are spread over them.
    bool several() const { return size_ > 1; }
    int rank() const { return rank_; }
    int size() const { return size_; }
    /// The transport when several() processes run, else null.
    BlockTransport* transport() { return several() ? transport_.get() : nullptr; }

private:
    bool started_ = false;
    int rank_ = 0, size_ = 1;
    std::unique_ptr<BlockTransport> transport_;
};

/// The session main() started (never null while a command runs).
MpiSession& mpi_session();

} // namespace isodel::cli
