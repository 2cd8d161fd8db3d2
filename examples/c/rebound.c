/* P and one 3-D rebound from an export, in C with the header and libm alone: an alumina sphere
   (R = 2.5 mm) hits a steel sphere (R = 6 mm), with spins, mu = 0.15.

       sweep export tables/full.h5 -o full.oblq
       cc -std=c99 -O2 -I include -o rebound examples/c/rebound.c -lm && ./rebound full.oblq */
#include <stdio.h>

#include "oblique_eval.h"

static int check(int rc, const char *what) {
    if (rc != OBLQ_OK) fprintf(stderr, "error: %s: %s\n", what, oblq_error_message(rc));
    return rc;
}

int main(int argc, char **argv) {
    oblq_table t;
    oblq_body alumina_ball = {2.4e-4, 2.5e-3, 0.4}, steel_ball = {2.4e-3, 6e-3, 0.4}; /* kg, m, kappa */
    oblq_material alumina = {3.7e11, 0.25}, steel = {2.1e11, 0.3};                    /* Pa, nu */
    oblq_incident3 s = {{{0.8, 0.3, 1.5}, {20.0, 120.0, -40.0}},  /* sphere 1: v (m/s), w (rad/s) */
                        {{-0.2, 0.1, -0.4}, {0.0, -50.0, 10.0}},  /* sphere 2 */
                        {0.1, -0.2, 0.97}};                        /* normal, 1 towards 2 */
    oblq_pair pair;
    oblq_rebound3 r;
    double gamma, p;
    int rc;
    if (argc != 2) {
        fprintf(stderr, "usage: %s EXPORT\n", argv[0]);
        return 2;
    }
    rc = oblq_load_file(&t, argv[1]); /* reads the file and checks it (oblq_open) */
    if (rc != OBLQ_OK) {
        fprintf(stderr, "error: %s: %s\n", argv[1], oblq_error_message(rc));
        return rc == OBLQ_E_FILE || rc == OBLQ_E_NOT_FILE || rc == OBLQ_E_NO_MEMORY ? 1 : 2;
    }
    if (check(oblq_p(&t, 1.754, 0.3, 0, &p), "P")) {
        oblq_free_file(&t);
        return 2;
    }
    printf("P(1.754, 0.3) = %.17g  (+/- %.2g)\n", p, t.error_bound);
    if (check(oblq_gamma_of(&alumina_ball, &steel_ball, &alumina, &steel, &gamma), "gamma") ||
        check(oblq_pair_init(&pair, &alumina_ball, &steel_ball, gamma, 0.15), "pair") ||
        check(oblq_rebound_3d(&t, &pair, &s, 0, &r), "rebound")) {
        oblq_free_file(&t);
        return 2;
    }
    printf("gamma = %.17g, alpha = %.17g, P = %.17g\n", r.gamma, r.alpha, r.p);
    printf("sphere 1: v = [%.9f, %.9f, %.9f] m/s, w = [%.6f, %.6f, %.6f] rad/s\n", r.sphere.v[0],
           r.sphere.v[1], r.sphere.v[2], r.sphere.w[0], r.sphere.w[1], r.sphere.w[2]);
    printf("sphere 2: v = [%.9f, %.9f, %.9f] m/s, w = [%.6f, %.6f, %.6f] rad/s\n", r.other.v[0],
           r.other.v[1], r.other.v[2], r.other.w[0], r.other.w[1], r.other.w[2]);
    printf("e_t = %.9f, energy lost = %.6e J\n", r.e_t, r.energy_lost);
    oblq_free_file(&t);
    return 0;
}
