#pragma once
/// \file block_transport.h
/// Partitioned meshing across processes (MeshOptions::block_voxels or block_count with
/// MeshOptions::transport): how the processes of one run, MPI ranks for example, share what
/// their blocks produce. The library never calls MPI itself; it asks these three questions. The
/// isodel command line supplies an MPI implementation (tools/isodel/mpi_transport.h) when it is
/// built with MPI and started by mpirun.
///
/// The blocks are dealt to the P processes by their estimated work (the grid-edge crossings in
/// each block's box, largest first to the least loaded process; every process computes the same
/// deal from the same volume). The rounds of point exchange are collective, so every process must
/// call mesh_isosurface with the same volume and options. The mesh is the same for every P and for
/// the thread engine (transport = nullptr); process 0 returns it, the others an empty surface.

#include <vector>

namespace isodel {

class BlockTransport {
public:
    virtual ~BlockTransport() = default;
    /// This process's index, 0 .. size() - 1.
    virtual int rank() const = 0;
    /// The number of processes of the run.
    virtual int size() const = 0;
    /// Every process's \p mine, concatenated in rank order, returned on every process.
    virtual std::vector<double> all_gather(const std::vector<double>& mine) = 0;
    /// Every process's \p mine, concatenated in rank order, returned on process 0 (empty on the
    /// others).
    virtual std::vector<double> gather_to_first(const std::vector<double>& mine) = 0;
};

} // namespace isodel
