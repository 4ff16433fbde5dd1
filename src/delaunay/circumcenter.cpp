#include "delaunay/circumcenter.h"

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

namespace isodel::mesher {

Point robust_circumcenter(const Point& a, const Point& b, const Point& c, const Point& d)
{
    const Vector ba = b - a, ca = c - a, da = d - a;
    const double det = ba * CGAL::cross_product(ca, da);
    const double lb = std::sqrt(ba.squared_length()), lc = std::sqrt(ca.squared_length()),
                 ld = std::sqrt(da.squared_length());
    // Relative conditioning of the 3x3 system: the volume against the product of edge lengths.
    if (std::abs(det) > 1e-6 * lb * lc * ld) return CGAL::circumcenter(a, b, c, d);
    using EK = CGAL::Exact_predicates_exact_constructions_kernel;
    const CGAL::Cartesian_converter<K, EK> to_exact;
    const CGAL::Cartesian_converter<EK, K> to_double;
    return to_double(CGAL::circumcenter(to_exact(a), to_exact(b), to_exact(c), to_exact(d)));
}

} // namespace isodel::mesher
