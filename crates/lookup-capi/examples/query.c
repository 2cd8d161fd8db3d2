/* Example of the C ABI of oblique-lookup: open a table, evaluate P, one sphere-sphere rebound
 * (direct and through a prepared pair), and two errors. Build against an installed library
 * (README, "From C, C++ and Fortran"):
 *
 *   scripts/install-capi.sh "$HOME/.local"
 *   export PKG_CONFIG_PATH="$HOME/.local/lib/pkgconfig"
 *   cc -std=c99 -O2 -o query crates/lookup-capi/examples/query.c $(pkg-config --cflags --libs oblique)
 *   LD_LIBRARY_PATH="$HOME/.local/lib" ./query tables/quick.h5
 *
 * Prints `key value` lines (values with 17 significant digits: they round-trip), which
 * crates/lookup-capi/tests/c_abi.rs compares with the Rust API. */
#include <math.h>
#include <stdio.h>

#include "oblique_lookup.h"

static int fail(const char *what, int code) {
    fprintf(stderr, "%s: error %d: %s\n", what, code, oblique_last_error());
    return 1;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s TABLE.h5\n", argv[0]);
        return 2;
    }
    ObliqueTable *table = NULL;
    int rc = oblique_table_open(argv[1], &table);
    if (rc != OBLIQUE_OK) return fail("open", rc);

    double gmin, gmax, amax;
    oblique_table_domain(table, &gmin, &gmax, &amax);
    printf("domain gamma [%g, %g], alpha_max %g\n", gmin, gmax, amax);

    double p;
    if ((rc = oblique_p(table, 1.754, 1.0, 0, &p)) != OBLIQUE_OK) return fail("P", rc);
    printf("P(1.754,1) %.17g\n", p);
    if ((rc = oblique_p(table, 2.0, INFINITY, 0, &p)) != OBLIQUE_OK) return fail("P", rc);
    printf("P(2,inf) %.17g\n", p);

    /* One pair of materials, many alphas: P(alpha) at gamma = 1.754, precomputed once. */
    ObliqueCurve *curve = NULL;
    if ((rc = oblique_curve_new(table, 1.754, 0, &curve)) != OBLIQUE_OK) return fail("curve", rc);
    if ((rc = oblique_curve_p(curve, 1.0, &p)) != OBLIQUE_OK) return fail("curve P", rc);
    printf("curve(1.754) P(1) %.17g\n", p);
    oblique_curve_free(curve);

    double gammas[3] = {0.6, 1.5, 2.4}, alphas[3] = {0.05, 0.4, INFINITY}, ps[3];
    if ((rc = oblique_p_batch(table, gammas, alphas, 3, 0, ps)) != OBLIQUE_OK)
        return fail("batch", rc);
    for (int i = 0; i < 3; i++) printf("batch[%d] %.17g\n", i, ps[i]);

    /* Alumina sphere (R 2.5 mm) on a steel sphere (R 6 mm), mu = 0.15, gamma from materials. */
    ObliqueBody ball = {2.4e-4, 2.5e-3, 0.4}, big = {2.4e-3, 6e-3, 0.4};
    ObliqueContact contact = {0.0, {3.7e11, 0.25}, {2.1e11, 0.3}, 0.15, 0};
    ObliqueMotion m1 = {{0.8, 0.3, 1.5}, {20.0, 120.0, -40.0}};
    ObliqueMotion m2 = {{-0.2, 0.1, -0.4}, {0.0, -50.0, 10.0}};
    double normal[3] = {0.0, 0.0, 1.0};
    ObliqueRebound r;
    rc = oblique_rebound_spheres(table, &ball, &big, &contact, &m1, &m2, normal, &r);
    if (rc != OBLIQUE_OK) return fail("rebound", rc);
    printf("spheres.gamma %.17g\nspheres.alpha %.17g\nspheres.p %.17g\n", r.gamma, r.alpha, r.p);
    printf("spheres.v1x %.17g\nspheres.w2y %.17g\nspheres.e_t %.17g\n", r.sphere.velocity[0],
           r.other.spin[1], r.e_t);
    printf("spheres.energy_lost %.17g\n", r.energy_lost);

    /* The same pair prepared once (bodies and materials checked, gamma computed), for many
     * impacts. */
    ObliquePrepared *prepared = NULL;
    if ((rc = oblique_prepare(&ball, &big, &contact, &prepared)) != OBLIQUE_OK)
        return fail("prepare", rc);
    rc = oblique_rebound_prepared(table, prepared, &m1, &m2, normal, &r);
    if (rc != OBLIQUE_OK) return fail("rebound_prepared", rc);
    printf("prepared.p %.17g\nprepared.v1x %.17g\n", r.p, r.sphere.velocity[0]);
    oblique_prepared_free(prepared);

    /* The same sphere on a steel wall (normal into the wall). */
    rc = oblique_rebound_wall(table, &ball, &contact, &m1, normal, &r);
    if (rc != OBLIQUE_OK) return fail("wall", rc);
    printf("wall.v1z %.17g\nwall.e_t %.17g\n", r.sphere.velocity[2], r.e_t);

    /* Errors: a code and a message naming the field, never a crash. */
    rc = oblique_p(table, -1.0, 0.5, 0, &p);
    printf("bad gamma: code %d: %s\n", rc, oblique_last_error());
    ObliqueTable *none = NULL;
    rc = oblique_table_open("/nonexistent/table.h5", &none);
    printf("missing file: code %d: %s\n", rc, oblique_last_error());

    oblique_table_close(table);
    return 0;
}
