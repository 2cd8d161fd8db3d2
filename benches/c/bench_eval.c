/* Speed of include/oblique_eval.h: CPU time per query, beside the Rust benchmarks of
   crates/lookup/benches/lookup.rs on the same points (the same generator and formulas as
   oblique_lookup::testing). Build and run (README, "From C, C++ and Fortran"; numbers in
   docs/benchmarks.md):

       sweep export tables/full.h5 -o full.oblq --gamma 1.754 --gamma 1.7101671300973298
       cc -std=c99 -O2 -I include -o bench_eval benches/c/bench_eval.c -lm
       ./bench_eval full.oblq [points.bin]

   (1.7101671300973298: gamma of the alumina-on-steel pair of the rebound benchmarks.) Each
   line: name, ns per query (median of 7 runs of CPU time of this thread). Arguments are read
   through volatile variables, so the compiler cannot hoist a query out of its loop. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "oblique_eval.h"

static volatile double sink;
static volatile double g_v = 1.754, a_line = 0.1, a_partial = 0.3, a_stick = 1.0, a_inf = INFINITY;

static double cpu_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* xorshift64 as oblique_lookup::testing::uniform: a double in [0, 1). */
static unsigned long long xs_state;
static double uniform(void) {
    xs_state ^= xs_state << 13;
    xs_state ^= xs_state >> 7;
    xs_state ^= xs_state << 17;
    return (double)(xs_state >> 11) / 9007199254740992.0;
}

static int cmp(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#define RUNS 7
/* Median over RUNS of the CPU time of `n` calls of `body` (which uses `i`), in ns per call. */
#define MEASURE(name, n, body)                                                               \
    do {                                                                                     \
        double ns_[RUNS];                                                                    \
        int run;                                                                             \
        for (run = 0; run < RUNS; run++) {                                                   \
            size_t i;                                                                        \
            double t0_ = cpu_seconds();                                                     \
            for (i = 0; i < (size_t)(n); i++) { body; }                                      \
            ns_[run] = (cpu_seconds() - t0_) / (double)(n) * 1e9;                               \
        }                                                                                    \
        qsort(ns_, RUNS, sizeof ns_[0], cmp);                                                  \
        printf("%-28s %8.1f ns\n", name, ns_[RUNS / 2]);                                     \
    } while (0)

static unsigned char *read_all(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    long len;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    len = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = (unsigned char *)malloc((size_t)len + 8);
    if (!buf || fread(buf, 1, (size_t)len, f) != (size_t)len) {
        fclose(f);
        free(buf);
        return NULL;
    }
    fclose(f);
    *size = (size_t)len;
    return buf;
}

int main(int argc, char **argv) {
    enum { MIXED = 4096, RANDOM = 1000000 };
    static double mg[MIXED], ma[MIXED];
    static oblq_incident3 stream[MIXED];
    double *rg, *ra, p = 0.0;
    size_t size = 0, k;
    unsigned char *data;
    oblq_table t;
    oblq_curve c;
    oblq_pair pair;
    oblq_body b1 = {2.4e-4, 2.5e-3, 0.4}, b2 = {2.4e-3, 6e-3, 0.4};
    oblq_material alumina = {3.7e11, 0.25}, steel = {2.1e11, 0.3};
    oblq_incident3 s = {{{0.8, 0.3, 1.5}, {20.0, 120.0, -40.0}},
                        {{-0.2, 0.1, -0.4}, {0.0, -50.0, 10.0}},
                        {0.1, -0.2, 0.97}};
    oblq_rebound3 r;
    double gamma;
    int rc;
    if (argc != 2 && argc != 3) {
        fprintf(stderr, "usage: bench_eval EXPORT [POINTS]  (EXPORT with the curve of gamma = 1.754;\n"
                        "POINTS: gamma, alpha pairs as little-endian doubles)\n");
        return 2;
    }
    data = read_all(argv[1], &size);
    if (!data || (rc = oblq_open(&t, data, size)) != OBLQ_OK ||
        (rc = oblq_curve_find(&t, 1.754, 0.0, &c)) != OBLQ_OK) {
        fprintf(stderr, "bench_eval: %s: %s\n", argv[1],
                data ? oblq_error_message(rc) : "cannot read");
        return 2;
    }
    /* The mixed points of the Rust benchmarks (testing::domain_points, seed 0x9E37...). */
    xs_state = 0x9E3779B97F4A7C15ULL;
    for (k = 0; k < MIXED; k++) {
        mg[k] = t.gamma_min + (t.gamma_max - t.gamma_min) * uniform();
        ma[k] = uniform() < 0.1 ? INFINITY : pow(10.0, -3.0 + 6.0 * uniform());
    }
    /* A million random points over the whole domain (alpha uniform in [0, 2]): memory-bound. */
    rg = (double *)malloc(RANDOM * sizeof *rg);
    ra = (double *)malloc(RANDOM * sizeof *ra);
    if (!rg || !ra) return 1;
    xs_state = 2026;
    for (k = 0; k < RANDOM; k++) {
        rg[k] = t.gamma_min + (t.gamma_max - t.gamma_min) * uniform();
        ra[k] = 2.0 * uniform();
    }
    if (argc == 3) {
        /* The first 10^5 points of a file of (gamma, alpha) pairs: the same points as the Rust
           loop p_single of target/release/examples/batch_timing. */
        size_t np = 0, m;
        double *pts = (double *)(void *)read_all(argv[2], &np);
        m = np / 16 < 100000 ? np / 16 : 100000;
        if (!pts || m == 0) {
            fprintf(stderr, "bench_eval: %s: no points\n", argv[2]);
            return 2;
        }
        MEASURE("p/points_file", m, oblq_p(&t, pts[2 * i], pts[2 * i + 1], 0, &p); sink = p);
        free(pts);
    }
    MEASURE("p/line", 2000000, oblq_p(&t, g_v, a_line, 0, &p); sink = p);
    MEASURE("p/partial", 2000000, oblq_p(&t, g_v, a_partial, 0, &p); sink = p);
    MEASURE("p/stick", 2000000, oblq_p(&t, g_v, a_stick, 0, &p); sink = p);
    MEASURE("p/no_slip", 2000000, oblq_p(&t, g_v, a_inf, 0, &p); sink = p);
    MEASURE("p/mixed", 2000000, oblq_p(&t, mg[i % MIXED], ma[i % MIXED], 0, &p); sink = p);
    MEASURE("p/random_1e6", RANDOM, oblq_p(&t, rg[i], ra[i], 0, &p); sink = p);
    MEASURE("curve/partial", 4000000, oblq_curve_p(&c, a_partial, 0, &p); sink = p);
    MEASURE("curve/stick", 4000000, oblq_curve_p(&c, a_stick, 0, &p); sink = p);
    MEASURE("curve/mixed_alpha", 4000000, oblq_curve_p(&c, ma[i % MIXED], 0, &p); sink = p);
    if (oblq_gamma_of(&b1, &b2, &alumina, &steel, &gamma) != OBLQ_OK ||
        oblq_pair_init(&pair, &b1, &b2, gamma, 0.15) != OBLQ_OK ||
        oblq_curve_find(&t, gamma, 1e-9, &c) != OBLQ_OK) {
        /* The pair's curve: export it with --gamma (its value printed here). */
        printf("rebound: export the curve of gamma = %.17g for the rebound benchmarks\n", gamma);
        return 0;
    }
    /* 4096 random sphere-sphere incident states of the Rust batch benchmarks
       (mixed_incidents in crates/lookup/benches/lookup.rs), cycled. */
    xs_state = 0x2545F4914F6CDD1DULL;
    for (k = 0; k < MIXED; k++) {
        double v[15], dn = 0.0;
        int j;
        for (j = 0; j < 15; j++) v[j] = uniform() - 0.5;
        for (j = 0; j < 3; j++) dn += (v[j] - v[6 + j]) * v[12 + j];
        for (j = 0; j < 3; j++) {
            stream[k].sphere.v[j] = v[j];
            stream[k].sphere.w[j] = 400.0 * v[3 + j];
            stream[k].other.v[j] = v[6 + j];
            stream[k].other.w[j] = 200.0 * v[9 + j];
            stream[k].normal[j] = dn < 0.0 ? -v[12 + j] : v[12 + j];
        }
    }
    MEASURE("rebound/stream_prepared", 2000000,
            oblq_rebound_3d(&t, &pair, &stream[i % MIXED], 0, &r); sink = r.p);
    MEASURE("rebound/stream_curve", 2000000,
            oblq_rebound_3d_curve(&c, &pair, &stream[i % MIXED], 0, &r); sink = r.p);
    MEASURE("rebound/spheres_3d_prepared", 2000000,
            s.sphere.v[0] = g_v * 0.5; oblq_rebound_3d(&t, &pair, &s, 0, &r); sink = r.p);
    MEASURE("rebound/spheres_3d_curve", 2000000,
            s.sphere.v[0] = g_v * 0.5; oblq_rebound_3d_curve(&c, &pair, &s, 0, &r); sink = r.p);
    free(rg);
    free(ra);
    free(data);
    return 0;
}
