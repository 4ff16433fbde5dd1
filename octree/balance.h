#pragma once
/// \file balance.h
/// The level-difference bound of the adaptive grid (paper Section 4.2).
///
/// Our k: any two leaf cells whose closed spans meet (sharing a face, an edge or only a vertex)
/// differ by at most k levels, i.e. their edge lengths differ by a factor of at most 2^k; the
/// paper's k is the same "level difference between two adjacent cells". Vertex contacts count
/// because a Voronoi cell near a grid vertex meets every cell around that vertex.
///
/// The voxel bound (Theorem 2) on such a grid, in leaves: the Voronoi cell of an E point meets at
/// most 3k + 1 of them (voronoi_bound_e), of an N point at most a leaf and every leaf touching
/// it (voronoi_bound_n). The mesher does not take either count on trust: it measures every
/// Voronoi cell (src/closed_ball/voxel_bound.h) and repairs G around any that exceeds its bound
/// (a hole in G), so the bound holds of the mesh it returns.
#include "octree/adaptive_grid.h"

#include <cstddef>
#include <vector>

namespace isodel::octree {

/// The smallest level of a leaf touching \p c (closed spans meet, \p c excluded), or INT_MAX when
/// none; the search stops as soon as a level <= \p stop_at is found.
int min_touching_level(const AdaptiveGrid::Reader& r, const CellId& c, int stop_at = -1);

/// True when a leaf of level < \p level touches \p c.
inline bool touches_finer_than(const AdaptiveGrid::Reader& r, const CellId& c, int level)
{
    return min_touching_level(r, c, level - 1) < level;
}

/// True when \p p (level >= 1) may replace its children: its closed span lies in the domain, its
/// 8 children are leaves, and no leaf touching it is finer than p.level - k (the merge keeps the
/// grid k-balanced). The structural half of every bottom-up coarsening (decimate.h,
/// certified_coarsening.h); what the values must satisfy is theirs.
bool may_merge(const AdaptiveGrid::Reader& r, const CellId& p, int k);

/// The parents of level \p l whose children may all be leaves, sorted: at level 1 the parents of
/// the unit cells touching allocated samples (value_cells_sparse: constant regions stay level 0,
/// which costs no storage), above it the parents of the leaves of level l - 1.
std::vector<CellId> merge_candidates(const AdaptiveGrid& g, int l);

/// Merges the candidates whose flag is set (in order); returns how many.
std::size_t merge_flagged(AdaptiveGrid& g, const std::vector<CellId>& candidates, const std::vector<char>& flags);

/// Largest level difference between touching leaves (0 for a uniform grid).
int max_level_difference(const AdaptiveGrid& g);

/// Splits leaves until every touching pair differs by at most \p k levels (k >= 1); sets g.k().
/// Only refines, so the interpolant stays exact wherever it was. Returns the number of splits.
std::size_t balance(AdaptiveGrid& g, int k);

/// Leaves a Voronoi cell of an E point may meet (Theorem 2, see above): 3k + 1. The mesher holds
/// E points to the larger of this and the uniform lattice's bound (4 on a cubic lattice).
inline int voronoi_bound_e(int k) { return 3 * k + 1; }
/// Leaves a Voronoi cell of an N point may meet: a leaf and every leaf touching it, at most
/// 1 + 8 + 12 2^k + 6 4^k (8 vertex, 12 2^k edge and 6 4^k face neighbours).
inline int voronoi_bound_n(int k) { return 1 + 8 + 12 * (1 << k) + 6 * (1 << (2 * k)); }

} // namespace isodel::octree
