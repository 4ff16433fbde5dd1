#include "octree/cell_function.h"

namespace isodel::octree {

Trilinear CellFunction::piece(int ix, int iy, int iz) const
{
    if (s_.h == 0) return f_;
    // u_k = alpha_k x_k + beta_k on the box: a slab side is constant (0 or 1), a core stretched.
    const int idx[3] = {ix, iy, iz};
    double alpha[3], beta[3];
    for (int k = 0; k < 3; ++k) {
        alpha[k] = idx[k] == 1 ? 1.0 / (1 - 2 * s_.h) : 0.0;
        beta[k] = idx[k] == 0 ? 0.0 : idx[k] == 1 ? -s_.h / (1 - 2 * s_.h) : 1.0;
    }
    // Trilinear::a by monomial (bit 0: x, bit 1: y, bit 2: z).
    static const int kCoef[8] = {0, 1, 2, 4, 3, 5, 6, 7};
    Trilinear g{};
    for (double& v : g.a) v = 0;
    // prod_{k in S} (alpha_k x_k + beta_k) = sum over T subset S of prod_T alpha x * prod_{S\T} beta.
    for (int S = 0; S < 8; ++S) {
        const double aS = f_.a[kCoef[S]];
        if (aS == 0) continue;
        for (int T = S;; T = (T - 1) & S) {
            double w = aS;
            for (int k = 0; k < 3; ++k)
                if (S >> k & 1) w *= (T >> k & 1) ? alpha[k] : beta[k];
            g.a[kCoef[T]] += w;
            if (T == 0) break;
        }
    }
    return g;
}

} // namespace isodel::octree
