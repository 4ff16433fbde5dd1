#pragma once
// Internal (facet_loops.cpp): where, inside a Voronoi facet, F' (octree/face_slabs.h) restricted
// to the facet's plane may have an extremum that a loop of Sigma in the facet would surround
// (facet_loops.h, Detection): inside one cell F restricted to a plane is smooth, so the
// candidates are the points where the plane crosses grid edges (F is only C0 there) and the
// extrema along the lines where it crosses grid faces (F is bilinear on a face). Coordinates are
// in the field's index space.
#include "octree/sample_field.h"
#include "octree/segment_walk.h"

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

// In detail:: because the names (Polygon, Small) are generic; facet_loops.cpp takes them by name.
namespace isodel::mesher::detail {

using Vec3d = openvdb::Vec3d;

// Per-facet scratch lists: a facet has a handful of Voronoi vertices and piece planes, and the
// first scan looks at every facet dual to an edge with an E/N endpoint (millions on a large
// volume); heap lists would cost an allocation each.
template <class T>
using Small = boost::container::small_vector<T, 16>;

/// A Voronoi facet: its vertices in order, the normal from that order, and the squared length
/// below which an edge is rounding noise. Cospherical sites give Voronoi vertices that coincide
/// up to rounding: an edge 1e-16 long has no direction, and the sign it gives is noise.
/// (Trusting it can hide the neck through a face saddle at exactly v, common on quantized data,
/// and M then loses a handle: tests/closed_ball/test_degenerate_voronoi_facets.cpp.)
struct Polygon {
    const Small<Vec3d>& P;
    Vec3d N;
    double noise_edge2;

    Polygon(const Small<Vec3d>& points, const Vec3d& normal) : P(points), N(normal), noise_edge2(0)
    {
        for (std::size_t i = 0; i < P.size(); ++i)
            noise_edge2 = std::max(noise_edge2, (P[(i + 1) % P.size()] - P[i]).lengthSqr());
        noise_edge2 *= 1e-20;
    }

    /// q (on the facet's plane) strictly inside the convex polygon.
    bool strictly_inside(const Vec3d& q) const
    {
        for (std::size_t i = 0; i < P.size(); ++i) {
            const Vec3d e = P[(i + 1) % P.size()] - P[i];
            if (e.lengthSqr() <= noise_edge2) continue; // coincident Voronoi vertices
            if (e.cross(q - P[i]).dot(N) <= 0) return false;
        }
        return true;
    }
};

/// The planes where F' (octree/face_slabs.h) changes its trilinear piece, on one axis, in
/// [lo, hi]: the grid planes c, or with slabs of half-width h their boundaries c - h and c + h.
inline Small<double> piece_planes(double lo, double hi, double h)
{
    Small<double> out;
    for (int c = int(std::floor(lo)) - 1; c <= int(std::ceil(hi)) + 1; ++c) {
        const double planes[2] = {c - h, c + h};
        for (int i = h == 0 ? 1 : 0; i < 2; ++i)
            if (planes[i] >= lo && planes[i] <= hi) out.push_back(planes[i]);
    }
    return out;
}

/// Points where the facet's plane meets grid edges inside the facet, with phi there. With
/// slabs, the lines where two slab boundaries meet (F' there is F on the grid edge).
template <class Visit>
void grid_edge_points(const Polygon& poly, const Vec3d& lo, const Vec3d& hi, double h, Visit&& visit)
{
    const auto& P = poly.P;
    const Vec3d& N = poly.N;
    const double c = N.dot(P[0]);
    for (int d = 0; d < 3; ++d) {
        const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
        if (std::abs(N[d]) < 1e-9 * N.length()) continue; // plane parallel to these edges
        const Small<double> us = piece_planes(lo[e1], hi[e1], h), vs = piece_planes(lo[e2], hi[e2], h);
        for (const double u : us)
            for (const double v : vs) {
                Vec3d q;
                q[e1] = u;
                q[e2] = v;
                q[d] = (c - N[e1] * u - N[e2] * v) / N[d];
                if (q[d] < lo[d] || q[d] > hi[d]) continue;
                if (poly.strictly_inside(q)) visit(d, q);
            }
    }
}

/// Extrema of F along the lines where the facet's plane crosses grid faces, inside the facet.
/// On a face F is bilinear, so along such a line it is a quadratic per face square: three
/// values give it exactly. A tube of Sigma lying in a grid face (e.g. two blobs joined at a face
/// saddle) has the extremum of its cross-section there, not on a grid edge.
template <class Visit>
void grid_face_extrema(const octree::SampleField::Reader& reader, const Polygon& poly, const Vec3d& lo,
                       const Vec3d& hi, Visit&& visit)
{
    const double h = reader.field().face_slabs().h;
    const auto& P = poly.P;
    const Vec3d& N = poly.N;
    const double c = N.dot(P[0]);
    for (int d = 0; d < 3; ++d) {
        const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
        Vec3d ed(0, 0, 0);
        ed[d] = 1;
        const Vec3d D = N.cross(ed); // the line's direction: in both planes
        if (D.lengthSqr() < 1e-18 * N.lengthSqr()) continue; // facet parallel to these faces
        for (const double u : piece_planes(lo[d], hi[d], h)) {
            // A point of the line: x_d = u, and the facet plane, solved along the larger of e1, e2.
            Vec3d P0(0, 0, 0);
            P0[d] = u;
            const int k = std::abs(N[e1]) >= std::abs(N[e2]) ? e1 : e2;
            const int m = k == e1 ? e2 : e1;
            P0[m] = 0.5 * (lo[m] + hi[m]);
            P0[k] = (c - N[d] * u - N[m] * P0[m]) / N[k];
            // Clip to the bounding box in e1, e2; breakpoints where the line crosses grid lines.
            double t0 = -1e300, t1 = 1e300;
            for (int a : {e1, e2}) {
                if (D[a] == 0) {
                    if (P0[a] < lo[a] || P0[a] > hi[a]) t0 = 1e300;
                    continue;
                }
                const double ta = (lo[a] - P0[a]) / D[a], tb = (hi[a] - P0[a]) / D[a];
                t0 = std::max(t0, std::min(ta, tb));
                t1 = std::min(t1, std::max(ta, tb));
            }
            if (!(t0 < t1)) continue;
            Small<double> ts{t0, t1};
            for (int a : {e1, e2}) {
                if (D[a] == 0) continue;
                const double xa = P0[a] + t0 * D[a], xb = P0[a] + t1 * D[a];
                for (const double g : piece_planes(std::min(xa, xb), std::max(xa, xb), h))
                    ts.push_back((g - P0[a]) / D[a]);
            }
            std::sort(ts.begin(), ts.end());
            // phi at a breakpoint ends one interval and starts the next: evaluated once.
            std::size_t known = ts.size();
            double f_known = 0;
            for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
                const double half = 0.5 * (ts[i + 1] - ts[i]);
                if (!(half > 1e-12)) continue;
                const double tm = ts[i] + half;
                const Vec3d pm = P0 + tm * D;
                const double f0 = known == i ? f_known : octree::phi_at(reader, P0 + ts[i] * D),
                             fm = octree::phi_at(reader, pm), f1 = octree::phi_at(reader, P0 + ts[i + 1] * D);
                known = i + 1;
                f_known = f1;
                const double alpha = (f0 - 2 * fm + f1) / (2 * half * half), beta = (f1 - f0) / (2 * half);
                if (alpha == 0) continue;
                const double x = -beta / (2 * alpha);
                if (!(std::abs(x) < half)) continue;
                const Vec3d q = pm + x * D;
                if (poly.strictly_inside(q)) visit(q);
            }
        }
    }
}

} // namespace isodel::mesher::detail
