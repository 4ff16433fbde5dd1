#pragma once
/// \file adaptive_queries.h
/// Leaf adjacency on an adaptive grid (paper Section 4.2): the leaves touching a leaf, and how
/// they meet. The mesher's G on the leaves (src/seeding/adaptive_points.h) and the candidate
/// leaves of the tests' reference implementations (tests/support/adaptive_reference.h) use it.
#include "octree/adaptive_grid.h"

#include <vector>

namespace isodel::octree {

/// How two touching leaves meet: dimension of the intersection of their closed spans.
enum class Contact : int { Vertex = 0, Edge = 1, Face = 2 };

struct Neighbour {
    CellId cell;
    Contact contact;
};

/// Every leaf touching \p c whose contact is in \p kinds (bit 1 << int(Contact)), sorted by cell.
std::vector<Neighbour> neighbours(const AdaptiveGrid::Reader& r, const CellId& c, int kinds = 7);

} // namespace isodel::octree
