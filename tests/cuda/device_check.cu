/* Compile check of include/oblique_eval.h in CUDA device code (scripts/check_cuda.sh): one
   kernel calls every function the header marks OBLQ_FN, so that a host-only call in any of
   them (memcmp, printf, ...) fails the build under `-Werror all-warnings`. Compiled, never run. */
#define OBLQ_FN __host__ __device__ static inline
#include "oblique_eval.h"

__global__ void every_function(const unsigned char *data, size_t size, double *out, int *rc) {
    oblq_table t, moved;
    oblq_curve c, found;
    oblq_body b1 = {1e-3, 1e-3, 0.4}, b2 = {2e-3, 2e-3, 0.4};
    oblq_material m1 = {2e11, 0.3}, m2 = {7e10, 0.33};
    oblq_pair pair, wall, damped;
    oblq_incident3 s = {{{0.1, 0.0, 1.0}, {0.0, 0.0, 0.0}}, {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}},
                        {0.0, 0.0, 1.0}};
    oblq_rebound3 r3;
    oblq_state s1 = {0.1, 1.0, 0.0}, s2 = {0.0, 0.0, 0.0};
    oblq_rebound2 r2;
    double gamma = 0.0, p = 0.0, e_t = 0.0, e_lo = 0.0, e_hi = 0.0;
    double x[3] = {1.45, 0.3, 0.8};
    int regime = 0, k = 0, axes = 0;
    rc[k++] = oblq_open(&t, data, size);
    moved = t;
    rc[k++] = oblq_rebase(&moved, data);
    rc[k++] = oblq_p(&t, 1.754, 0.3, 0, &p);
    rc[k++] = oblq_p_e(&t, 1.45, 0.3, 0.8, 1, &p);
    rc[k++] = oblq_e_n_range(&t, &e_lo, &e_hi);
    rc[k++] = oblq_axis_count(&t, &axes);
    rc[k++] = oblq_axis_name(&t, axes - 1)[0];
    rc[k++] = oblq_p_at(&t, x, axes, 1, &p);
    rc[k++] = oblq_curve_get(&t, 0, &c);
    rc[k++] = oblq_curve_find(&t, 1.75, 1e-12, &found);
    rc[k++] = oblq_curve_rebase(&found, &t, &moved);
    rc[k++] = oblq_curve_p(&c, 0.3, 1, &p);
    rc[k++] = oblq_e_t(p, 0.4, &e_t);
    rc[k++] = oblq_regime(1.754, 0.3, &regime);
    rc[k++] = oblq_gamma_of(&b1, &b2, &m1, &m2, &gamma);
    rc[k++] = oblq_pair_init(&pair, &b1, &b2, gamma, 0.3);
    rc[k++] = oblq_pair_init(&wall, &b1, NULL, gamma, 0.3);
    rc[k++] = oblq_pair_init_e(&damped, &b1, &b2, gamma, 0.3, 0.8);
    rc[k++] = oblq_rebound_3d(&t, &damped, &s, 1, &r3);
    rc[k++] = oblq_rebound_3d(&t, &pair, &s, 0, &r3);
    rc[k++] = oblq_rebound_3d_curve(&c, &pair, &s, 1, &r3);
    rc[k++] = oblq_rebound_2d(&t, &c, &wall, &s1, &s2, 0, &r2);
    rc[k++] = oblq_error_message(rc[0])[0];
    out[0] = p + e_t + gamma + r3.p + r2.p + (double)regime + oblq_alpha_c1(gamma) +
             oblq_alpha_c2(gamma) + oblq_linear_limit(gamma) + moved.gamma_min + e_lo + e_hi;
}
