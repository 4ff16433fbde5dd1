// Check 5: triangle quality (reported, never failing): smallest angle per triangle (histogram in
// 10 degree bins) and the radius-edge ratio (circumradius / shortest edge; 1/sqrt(3) is optimal,
// the usual Delaunay refinement bound is 1 to 2).
#include "verify/checks.h"

#include <algorithm>
#include <cmath>

namespace isodel::verify {

QualityReport triangle_quality(const SurfaceMesh& mesh)
{
    QualityReport q;
    if (mesh.triangles.empty()) return q;
    q.min_angle_deg = 180.0;
    double sum_angle = 0.0, sum_re = 0.0;
    std::size_t n = 0;
    for (const auto& t : mesh.triangles) {
        Vec3d p[3];
        for (int i = 0; i < 3; ++i) {
            const auto& v = mesh.vertices[std::size_t(t[std::size_t(i)])];
            p[i] = Vec3d(v[0], v[1], v[2]);
        }
        const double a = (p[1] - p[2]).length(), b = (p[2] - p[0]).length(), c = (p[0] - p[1]).length();
        const double area2 = (p[1] - p[0]).cross(p[2] - p[0]).length(); // twice the area
        double amin = 0.0, re = 1e300;
        if (area2 > 0) {
            // Angles from the law of cosines, clamped against roundoff.
            auto angle = [](double opp, double s1, double s2) {
                return std::acos(std::clamp((s1 * s1 + s2 * s2 - opp * opp) / (2 * s1 * s2), -1.0, 1.0));
            };
            amin = std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * 180.0 / M_PI;
            const double R = a * b * c / (2.0 * area2); // circumradius = abc / (4 area)
            re = R / std::min({a, b, c});
        }
        ++q.min_angle_histogram[std::size_t(std::min(5, int(amin / 10.0)))];
        q.min_angle_deg = std::min(q.min_angle_deg, amin);
        q.max_radius_edge = std::max(q.max_radius_edge, re);
        sum_angle += amin;
        if (re < 1e300) {
            sum_re += re;
            ++n;
        }
    }
    q.mean_min_angle_deg = sum_angle / double(mesh.triangles.size());
    q.mean_radius_edge = n ? sum_re / double(n) : 0.0;
    return q;
}

} // namespace isodel::verify
