#pragma once
/// \file balance.h
/// The level-difference bound of the adaptive grid (paper Section 4.2).
///
/// Our k: any two leaf cells whose closed spans meet (sharing a face, an edge or only a vertex)
/// differ by at most k levels, i.e. their edge lengths differ by a factor of at most 2^k.
/// The paper's k is the same "level difference between two adjacent cells". Its counting argument
/// ("an edge is incident on at most k^2 cells in each of the other two directions", bounds 4k^2,
/// then 4 for E points and 3k+1 for N points) counts the fine cells along a coarse edge, which is
/// 2^k for our k; so we quote the Voronoi bounds conservatively with k_paper = 2^k:
///   E points: 4 cells;  N points: 3 * 2^k + 1 cells (4 for k = 0, 7 for k = 1, 13 for k = 2).
/// Vertex contacts are included (the paper says "adjacent") because a Voronoi cell near a grid
/// vertex meets every cell around that vertex.
#include "octree/adaptive_grid.h"

#include <cstddef>

namespace isodel::octree {

/// The smallest level of a leaf touching \p c (closed spans meet, \p c excluded), or INT_MAX when
/// none; the search stops as soon as a level <= \p stop_at is found.
int min_touching_level(const AdaptiveGrid::Reader& r, const CellId& c, int stop_at = -1);

/// True when a leaf of level < \p level touches \p c.
inline bool touches_finer_than(const AdaptiveGrid::Reader& r, const CellId& c, int level)
{
    return min_touching_level(r, c, level - 1) < level;
}

/// Largest level difference between touching leaves (0 for a uniform grid).
int max_level_difference(const AdaptiveGrid& g);

/// Splits leaves until every touching pair differs by at most \p k levels (k >= 1); sets g.k().
/// Only refines, so the interpolant stays exact wherever it was. Returns the number of splits.
std::size_t balance(AdaptiveGrid& g, int k);

/// Paper bound on the cells a Voronoi cell of an N point meets, for our k (see above).
inline int voronoi_bound_n(int k) { return 3 * (1 << k) + 1; }
inline int voronoi_bound_e(int /*k*/) { return 4; }

} // namespace isodel::octree
