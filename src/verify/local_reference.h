#pragma once
// Internal to verify: the local reference surface behind the M -> Sigma fallback of the Hausdorff
// check (hausdorff.cpp). Around a sample p, marching tetrahedra at R = 8 in every crossed cell
// meeting the ball B(p, r) give a fine piecewise-linear copy of Sigma (refined_lattice.h). Two of
// its points bound d(p, Sigma) from above: the closest point of the copy to p, Newton-projected
// onto Sigma, and the nearest vertex of the copy that lies on an axis-aligned sub-lattice edge
// (F is linear along an axis line inside a cell, so that vertex is exactly on Sigma).
//
// Neighbouring samples search the same cells, so a LocalReference (one per thread) keeps the
// refined triangles of the cells it visited, up to a number of cells, and then forgets them all
// and starts again: the same values in the same order as refining again, so every bound is
// bit-identical with or without the cache (tests/verify/test_verify_local_reference.cpp
// compares the two).
#include "verify/refined_lattice.h"
#include "verify/trilinear_field.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace isodel::verify {

/// The cells crossed_cells() found, as a set (shared by the threads' LocalReferences).
class CrossedCellSet {
public:
    CrossedCellSet(const std::vector<Coord>& cells, const Coord& base);
    const Coord& base() const { return base_; }
    bool contains(const Coord& c) const;
    /// c - base packed into 63 bits (c >= base).
    std::uint64_t key(const Coord& c) const
    {
        return (std::uint64_t(c[0] - base_[0]) << 42) | (std::uint64_t(c[1] - base_[1]) << 21) |
               std::uint64_t(c[2] - base_[2]);
    }

private:
    Coord base_;
    std::unordered_set<std::uint64_t> keys_;
};

class LocalReference {
public:
    static constexpr int kRefine = 8;
    static constexpr std::size_t kDefaultCacheCells = 4096;

    /// \p cache_cells: how many cells' triangles to keep (0: refine a cell at every visit).
    LocalReference(const TrilinearField& field, const CrossedCellSet& crossed,
                   std::size_t cache_cells = kDefaultCacheCells);

    /// Lowers \p best (world units) to the upper bound of d(p, Sigma) found from the crossed cells
    /// meeting the world ball B(p, r). False, leaving \p best, when no crossed cell meets it.
    bool search(const Vec3d& p, double r, double& best);

    /// Visits served from the cache (for tests: the cache is really used).
    std::size_t cache_hits() const { return hits_; }

private:
    /// A cell's refined triangles in world coordinates, and which of their vertices lie on
    /// axis-aligned sub-lattice edges (bit v: vertex v).
    struct CellTriangles {
        std::vector<std::array<Vec3d, 3>> tri;
        std::vector<std::uint8_t> on_sigma;
    };
    const CellTriangles& triangles(const Coord& c);

    const TrilinearField& field_;
    const CrossedCellSet& crossed_;
    TrilinearField::Evaluator ev_;
    CellRefiner refiner_;
    std::size_t cache_cells_;
    std::unordered_map<std::uint64_t, CellTriangles> cache_;
    CellTriangles scratch_; ///< the triangles of the last cell when nothing is cached
    std::size_t hits_ = 0;
};

} // namespace isodel::verify
