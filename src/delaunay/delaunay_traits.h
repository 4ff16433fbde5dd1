#pragma once
// Internal: the geometric traits of the mesher's Delaunay triangulation (delaunay.h): EPICK,
// with two exact shortcuts in the in-sphere test.
//
// Why: the grid points G of the protective layer are cospherical in every grid cube (the eight
// corners of a box lie on one sphere), so the initial triangulation meets in-sphere tests whose
// determinant is exactly 0. CGAL's floating-point filters cannot decide those, so each one would
// fall to EPICK's multiprecision (Mpzf) evaluation, which is slow, and G makes such tests by the
// million. Most are five corners of one box, which InSphereAfterFilter::on_one_box recognises
// from a few comparisons of coordinates; nearly all the others are exact zeros too (lattice
// points cospherical across cubes), which geometry::exact_in_sphere_sign evaluates exactly in
// 320-bit fixed-width integers, at a fraction of multiprecision's cost.
//
// The decisions stay EPICK's: both shortcuts are exact, and whatever they decline goes through
// EPICK's own predicate. CGAL's Delaunay_triangulation_3 breaks ties (0) by symbolic
// perturbation as before.
#include "geometry/exact_in_sphere.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>

namespace isodel::mesher {

/// What EPICK's in-sphere test does after its semi-static filter failed, with two exact
/// shortcuts first: box corners (exactly 0), then the determinant in 320-bit integers
/// (geometry/exact_in_sphere.h) where the differences allow; EPICK's own evaluation otherwise.
struct InSphereAfterFilter {
    using Point = CGAL::Epick::Point_3;
    using result_type = CGAL::Oriented_side;

    CGAL::Oriented_side operator()(const Point& p, const Point& q, const Point& r, const Point& s, const Point& t) const
    {
        if (on_one_box({&p, &q, &r, &s, &t})) return CGAL::ON_ORIENTED_BOUNDARY;
        const double xyz[5][3] = {{p.x(), p.y(), p.z()}, {q.x(), q.y(), q.z()}, {r.x(), r.y(), r.z()},
                                  {s.x(), s.y(), s.z()}, {t.x(), t.y(), t.z()}};
        int sign;
        if (geometry::exact_in_sphere_sign(xyz[0], xyz[1], xyz[2], xyz[3], xyz[4], sign))
            return CGAL::Oriented_side(sign);
        // EPICK's whole predicate: its semi-static filter fails again (cheaply), then its
        // interval and exact stages decide.
        return CGAL::Epick().side_of_oriented_sphere_3_object()(p, q, r, s, t);
    }

    /// Whether each coordinate takes at most two values on the points. They are then corners of
    /// one axis-aligned box, all as far from its centre, or all in one plane x, y or z = const:
    /// cospherical or coplanar either way, so the in-sphere determinant is exactly 0 (the
    /// points lifted to the paraboloid lie in one hyperplane). Comparisons of doubles: exact.
    static bool on_one_box(const std::array<const Point*, 5>& points)
    {
        for (int k = 0; k < 3; ++k) {
            const double a = points[0]->cartesian(k);
            double b = a;
            for (int i = 1; i < 5; ++i) {
                const double x = points[i]->cartesian(k);
                if (x == a || x == b) continue;
                if (b != a) return false; // a third value
                b = x;
            }
        }
        return true;
    }
};

/// EPICK, but its in-sphere test is CGAL's semi-static filter (EPICK's own first stage) falling
/// back to InSphereAfterFilter.
struct DelaunayTraits : CGAL::Epick {
    struct FilterBase { // what CGAL's static filter reads from its kernel: the point and the fallback
        using Point_3 = CGAL::Epick::Point_3;
        using Side_of_oriented_sphere_3 = InSphereAfterFilter;
    };
    using Side_of_oriented_sphere_3 = CGAL::internal::Static_filters_predicates::Side_of_oriented_sphere_3<FilterBase>;
    Side_of_oriented_sphere_3 side_of_oriented_sphere_3_object() const { return {}; }
};

} // namespace isodel::mesher
