/* Test driver of include/oblique_eval.h for tests/c_evaluator.rs (also compiled as C++).

     eval_check open FILE                        status code and message of oblq_open
     eval_check p EXPORT CLAMP                   stdin "gamma alpha" -> P or "error CODE"
     eval_check pe EXPORT CLAMP                  stdin "gamma alpha e_n" -> P (oblq_p_e) or
                                                 "error CODE"; first line: the e_n range
     eval_check curve EXPORT INDEX CLAMP         stdin "alpha" -> P of curve INDEX
     eval_check rebound EXPORT SOURCE m1 R1 k1 m2 R2 k2 GAMMA MU
                                                 SOURCE: table or curve (the curve of GAMMA);
                                                 m2 = 0: a wall. stdin: v1 w1 v2 w2 n (15
                                                 numbers) -> v1' w1' v2' w2' p e_t energy_lost
                                                 alpha slip_before
     eval_check rebound2 EXPORT m1 R1 k1 m2 R2 k2 GAMMA MU
                                                 stdin: v_x v_z omega (x2) -> the 2-D answer
     eval_check rebound EXPORT SOURCE m1 R1 k1 m2 R2 k2 GAMMA MU E_N
     eval_check rebound2 EXPORT m1 R1 k1 m2 R2 k2 GAMMA MU E_N
                                                 the same at normal restitution E_N
                                                 (oblq_pair_init_e), two more fields:
                                                 normal_impulse e_n
     eval_check fuzz EXPORT N SEED               N mutated copies through oblq_open and queries
     eval_check fuzz EXPORT N SEED FROM TO       the same, the bytes and doubles mutated only in
                                                 [FROM, TO) (a block of the export)
     eval_check headers EXPORT                   every header field set to NaN, +-inf, 0,
                                                 negative, huge, a critical value, the other
                                                 end of its range (resealed): refused with a
                                                 code, or every answer finite with |P| <= 1

   Numbers are printed with %.17g (they read back to the same double). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oblique_eval.h"

/* oblq_e_t's refusal of P is OBLQ_E_P_RANGE; OBLQ_E_KAPPA_P stays as its deprecated alias. */
typedef char oblq_check_p_range[(OBLQ_E_P_RANGE == 23 && OBLQ_E_KAPPA_P == OBLQ_E_P_RANGE) ? 1 : -1];

static unsigned char *read_all(const char *path, size_t *size) {
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    long len;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) != 0 || (len = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return NULL;
    }
    buf = (unsigned char *)malloc((size_t)len + 8);
    if (!buf || fread(buf, 1, (size_t)len, f) != (size_t)len) {
        free(buf);
        fclose(f);
        return NULL;
    }
    fclose(f);
    *size = (size_t)len;
    return buf;
}

static void g17(double x) { printf("%.17g", x); }

static int open_or_die(oblq_table *t, unsigned char *d, size_t n) {
    int rc = oblq_open(t, d, n);
    if (rc != OBLQ_OK) {
        fprintf(stderr, "eval_check: %s\n", oblq_error_message(rc));
        exit(3);
    }
    return rc;
}

/* Open the export at *d, then move the table (and the curve `index`, when >= 0, made from the
   first copy) to a fresh copy of the bytes with oblq_rebase and oblq_curve_rebase, as a GPU code
   does for its device copy, and wipe and free the first copy: every query then reads the new
   copy only (a pointer left behind reads wiped bytes, or freed memory under AddressSanitizer). */
static void open_moved(oblq_table *t, unsigned char **d, size_t n, long index, oblq_curve *c) {
    oblq_table first, other;
    unsigned char *copy = (unsigned char *)malloc(n + 8);
    int rc;
    open_or_die(&first, *d, n);
    if (index >= 0) {
        rc = oblq_curve_get(&first, (size_t)index, c);
        if (rc != OBLQ_OK) {
            fprintf(stderr, "eval_check: %s\n", oblq_error_message(rc));
            exit(3);
        }
    }
    if (!copy) exit(1);
    memcpy(copy, *d, n);
    *t = first;
    /* Refusals first: they leave the table and curve unchanged. */
    if (oblq_rebase(NULL, copy) != OBLQ_E_NULL || oblq_rebase(t, NULL) != OBLQ_E_NULL ||
        oblq_rebase(t, copy + 4) != OBLQ_E_CORRUPT || t->data != *d) {
        fprintf(stderr, "eval_check: oblq_rebase: a refusal failed\n");
        exit(4);
    }
    rc = oblq_rebase(t, copy);
    if (rc != OBLQ_OK || t->data != copy) {
        fprintf(stderr, "eval_check: oblq_rebase: %d\n", rc);
        exit(4);
    }
    if (index >= 0) {
        other = first;
        other.size -= 8;
        if (oblq_curve_rebase(c, t, &first) != OBLQ_E_NO_CURVE ||
            oblq_curve_rebase(c, &first, &other) != OBLQ_E_CORRUPT ||
            oblq_curve_rebase(NULL, &first, t) != OBLQ_E_NULL ||
            (rc = oblq_curve_rebase(c, &first, t)) != OBLQ_OK) {
            fprintf(stderr, "eval_check: oblq_curve_rebase: wrong status\n");
            exit(4);
        }
    }
    memset(*d, 0xa5, n);
    free(*d);
    *d = copy;
}

static unsigned long long rng_state;
static unsigned long long next_u64(void) {
    unsigned long long z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static void reseal(unsigned char *d, size_t n) {
    unsigned long long sum = 0xcbf29ce484222325ULL, len;
    size_t i;
    if (n < 96) return;
    len = oblq__u64(d + 16);
    if (len > n) len = n;
    for (i = 32; i < len; i++) sum = (sum ^ d[i]) * 0x100000001b3ULL;
    for (i = 0; i < 8; i++) d[24 + i] = (unsigned char)(sum >> (8 * i));
}

/* Mutate copies of the export (bytes, words, lengths), half of them with the checksum
   recomputed so that the structural checks are exercised; every one that opens is queried. */
/* The bytes the fuzz mutates (besides header words and the length): [fuzz_from, fuzz_to), or
   all of them when fuzz_to is 0. */
static size_t fuzz_from = 0, fuzz_to = 0;

static int fuzz(const unsigned char *orig, size_t n, long count) {
    unsigned char *d = (unsigned char *)malloc(n + 8);
    long k, opened = 0, refused = 0;
    static const double gs[] = {0.05, 0.1, 0.5, 0.99, 1.0, 1.01, 1.5, 2.2, 2.9, 3.2, 3.5, 4.0};
    static const double as[] = {0.0, 0.01, 0.1, 0.2, 0.3, 0.5, 0.8, 1.0, 2.0, 10.0, 1e300};
    if (!d) return 1;
    for (k = 0; k < count; k++) {
        size_t len = n, i, edits;
        oblq_table t;
        int rc;
        memcpy(d, orig, n);
        edits = 1 + next_u64() % 8;
        for (i = 0; i < edits; i++) {
            unsigned long long r = next_u64();
            size_t at = fuzz_to > fuzz_from ? fuzz_from + (size_t)(next_u64() % (fuzz_to - fuzz_from))
                                            : (size_t)(next_u64() % n);
            switch (r % 5) {
            case 0: d[at] ^= (unsigned char)(1u << (r >> 8) % 8); break;
            case 1: d[at] = (unsigned char)(r >> 16); break;
            case 2: /* a header or directory word */
                at = (size_t)(next_u64() % (n < 1024 ? n : 1024)) & ~(size_t)3;
                if (at + 4 <= n) memcpy(d + at, &r, 4);
                break;
            case 3: len = (size_t)(next_u64() % (n + 1)); break;
            default: /* a double somewhere: NaN, inf, huge, negative */
                at &= ~(size_t)7;
                if (at + 8 <= n) {
                    static const double bad[] = {0.0 / 1.0, -1.0, 1e308, 1e-310, 2.0};
                    double v = bad[(r >> 20) % 5];
                    if ((r >> 24) % 3 == 0) v = INFINITY;
                    if ((r >> 24) % 3 == 1) v = NAN;
                    memcpy(d + at, &v, 8);
                }
            }
        }
        if (k % 2 == 0) reseal(d, len);
        rc = oblq_open(&t, d, len);
        if (rc != OBLQ_OK) {
            refused++;
            if (strlen(oblq_error_message(rc)) == 0) {
                free(d);
                return 1;
            }
            continue;
        }
        opened++;
        for (i = 0; i <= sizeof gs / sizeof gs[0]; i++) {
            size_t j;
            /* The fixed gammas, then the table's lowest (the gamma of a table of one pair). */
            double g = i < sizeof gs / sizeof gs[0] ? gs[i] : t.gamma_min;
            for (j = 0; j < sizeof as / sizeof as[0]; j++) {
                double p = 0.0;
                if (oblq_p(&t, g, as[j], (int)(j % 2), &p) == OBLQ_OK && !(p >= -1.0 && p <= 1.0)) {
                    fprintf(stderr, "fuzz: mutation %ld: P(%g, %g) = %g\n", k, g, as[j], p);
                    free(d);
                    return 1;
                }
                /* And across the e_n range of a table with the axis. */
                if (t.has_e_n) {
                    double e = t.e_n_min + (t.e_n_max - t.e_n_min) * (double)(j % 4) / 3.0;
                    if (oblq_p_e(&t, g, as[j], e, (int)(j % 2), &p) == OBLQ_OK &&
                        !(p >= -1.0 && p <= 1.0)) {
                        fprintf(stderr, "fuzz: mutation %ld: P(%g, %g, %g) = %g\n", k, g,
                                as[j], e, p);
                        free(d);
                        return 1;
                    }
                }
            }
        }
        for (i = 0; i < t.n_curves; i++) {
            oblq_curve c;
            size_t j;
            if (oblq_curve_get(&t, i, &c) != OBLQ_OK) continue;
            for (j = 0; j < sizeof as / sizeof as[0]; j++) {
                double p = 0.0;
                if (oblq_curve_p(&c, as[j], 1, &p) == OBLQ_OK && !(p >= -1.0 && p <= 1.0)) {
                    fprintf(stderr, "fuzz: mutation %ld: curve %lu P(%g) = %g\n", k,
                            (unsigned long)i, as[j], p);
                    free(d);
                    return 1;
                }
            }
        }
    }
    printf("fuzz: %ld mutations, %ld refused, %ld opened and queried\n", count, refused, opened);
    free(d);
    return 0;
}

/* Whether every answer of the export at d (opened as t) is finite with |P| <= 1, at points
   around its domain, its critical curves and alpha_max, with and without clamping, along the
   e_n range of a table with the axis, and on every curve. Prints the first bad one. */
static int answers_bounded(const oblq_table *t, const char *what) {
    static const double gs0[] = {1e-300, 0.05, 0.1, 0.5, 0.99, 1.0, 1.01, 1.5, 2.2, 2.9, 3.5,
                                 4.0, 70.0, 1e100, 3.6e153, 1.4e154, 1e200, 1.7e308};
    double gs[sizeof gs0 / sizeof gs0[0] + 6], as[40];
    size_t ng = 0, i, j, c;
    for (i = 0; i < sizeof gs0 / sizeof gs0[0]; i++) gs[ng++] = gs0[i];
    gs[ng++] = t->gamma_min;
    gs[ng++] = t->gamma_max;
    gs[ng++] = nextafter(t->gamma_min, 0.0);
    gs[ng++] = nextafter(t->gamma_max, INFINITY);
    gs[ng++] = 0.5 * (t->gamma_min + t->gamma_max);
    gs[ng++] = sqrt(t->gamma_min * t->gamma_max);
    for (i = 0; i < ng; i++) {
        double g = gs[i], base[] = {0.0, 0.01, 0.1, 0.2, 0.3, 0.5, 1.0, 10.0, 1e300, INFINITY};
        size_t na = 0;
        if (!(g > 0.0 && g < INFINITY)) continue;
        for (j = 0; j < sizeof base / sizeof base[0]; j++) as[na++] = base[j];
        as[na++] = t->alpha_max;
        as[na++] = nextafter(t->alpha_max, 0.0);
        as[na++] = oblq_linear_limit(g);
        as[na++] = nextafter(oblq_linear_limit(g), INFINITY);
        as[na++] = oblq_alpha_c2(g);
        as[na++] = nextafter(oblq_alpha_c2(g), 0.0);
        as[na++] = g * g * (2.0 / 7.0);
        as[na++] = 0.5 * (oblq_linear_limit(g) + oblq_alpha_c2(g));
        for (j = 0; j < na; j++) {
            int clamp;
            for (clamp = 0; clamp < 2; clamp++) {
                double p = 0.0;
                int rc = oblq_p(t, g, as[j], clamp, &p);
                if (rc == OBLQ_OK && !(p >= -1.0 && p <= 1.0)) {
                    fprintf(stderr, "%s: P(%.17g, %.17g) = %g (clamp %d)\n", what, g, as[j], p,
                            clamp);
                    return 0;
                }
                for (c = 0; t->has_e_n && c < 5; c++) {
                    double e = c == 4 ? t->e_n_max : t->e_n_min + (t->e_n_max - t->e_n_min) * c / 4.0;
                    rc = oblq_p_e(t, g, as[j], e, clamp, &p);
                    if (rc == OBLQ_OK && !(p >= -1.0 && p <= 1.0)) {
                        fprintf(stderr, "%s: P(%.17g, %.17g, %.17g) = %g (clamp %d)\n", what, g,
                                as[j], e, p, clamp);
                        return 0;
                    }
                }
            }
        }
    }
    for (c = 0; c < t->n_curves; c++) {
        oblq_curve cv;
        if (oblq_curve_get(t, c, &cv) != OBLQ_OK) continue;
        for (j = 0; j < 6; j++) {
            double a[] = {0.1, cv.alpha_lin, cv.alpha_c2, cv.stick_c2, cv.alpha_max, INFINITY};
            int clamp;
            for (clamp = 0; clamp < 2; clamp++) {
                double p = 0.0;
                if (oblq_curve_p(&cv, a[j], clamp, &p) == OBLQ_OK && !(p >= -1.0 && p <= 1.0)) {
                    fprintf(stderr, "%s: curve %lu P(%.17g) = %g\n", what, (unsigned long)c, a[j],
                            p);
                    return 0;
                }
            }
        }
    }
    return 1;
}

static void put_f64(unsigned char *d, double v) { memcpy(d, &v, 8); }

/* Each header field of the export set to values that the data contradicts or that stress
   the rule, resealed; every copy is refused with a code and a message, or answers within
   [-1, 1]. */
static int headers(const unsigned char *orig, size_t n) {
    unsigned char *d = (unsigned char *)malloc(n + 8);
    long refused = 0, opened = 0, tried = 0;
    oblq_table t0;
    size_t f, v, i;
    size_t header;
    if (!d) return 1;
    if (oblq_open(&t0, orig, n) != OBLQ_OK) {
        fprintf(stderr, "headers: the export does not open\n");
        free(d);
        return 1;
    }
    header = oblq__u32(orig + 12);
    /* The reals: gamma_min, gamma_max, alpha_max, error_bound (and e_n_min, e_n_max). */
    for (f = 32; f < header; f += 8) {
        double o, vals[48];
        size_t nv = 0;
        static const size_t reals[] = {32, 40, 48, 56, 96, 104};
        int real = 0;
        for (i = 0; i < sizeof reals / sizeof reals[0]; i++) real |= reals[i] == f;
        if (!real) continue;
        o = oblq__f64(orig + f);
        vals[nv++] = NAN;
        vals[nv++] = INFINITY;
        vals[nv++] = -INFINITY;
        vals[nv++] = 0.0;
        vals[nv++] = -0.0;
        vals[nv++] = -1.0;
        vals[nv++] = -o;
        vals[nv++] = 1e-310;
        vals[nv++] = 1e100;
        vals[nv++] = 1e101;
        vals[nv++] = 1e300;
        vals[nv++] = 1.7976931348623157e308;
        vals[nv++] = 2.0 * o;
        vals[nv++] = 0.5 * o;
        vals[nv++] = nextafter(o, 0.0);
        vals[nv++] = nextafter(o, INFINITY);
        vals[nv++] = 1.0;
        vals[nv++] = nextafter(1.0, 0.0);
        vals[nv++] = nextafter(1.0, 2.0);
        vals[nv++] = 2.0 / 7.0;
        vals[nv++] = t0.gamma_min;
        vals[nv++] = t0.gamma_max;
        /* alpha_c2 in both of the rule's forms where queries fall, and at the domain's ends */
        {
            double gs[] = {1.0, 1.5, 2.2, t0.gamma_min, t0.gamma_max, 0.5, 0.99};
            for (i = 0; i < sizeof gs / sizeof gs[0] && nv + 3 <= 48; i++) {
                vals[nv++] = oblq_alpha_c2(gs[i]);
                vals[nv++] = gs[i] * gs[i] * (2.0 / 7.0);
                vals[nv++] = oblq_linear_limit(gs[i]);
            }
        }
        for (v = 0; v < nv; v++) {
            oblq_table t;
            char what[96];
            int rc;
            memcpy(d, orig, n);
            put_f64(d + f, vals[v]);
            reseal(d, n);
            tried++;
            rc = oblq_open(&t, d, n);
            if (rc != OBLQ_OK) {
                refused++;
                if (strlen(oblq_error_message(rc)) == 0 || rc == OBLQ_E_CHECKSUM) {
                    fprintf(stderr, "headers: offset %lu = %g: status %d\n", (unsigned long)f,
                            vals[v], rc);
                    free(d);
                    return 1;
                }
                continue;
            }
            opened++;
            snprintf(what, sizeof what, "headers: offset %lu = %.17g", (unsigned long)f, vals[v]);
            if (!answers_bounded(&t, what)) {
                free(d);
                return 1;
            }
        }
    }
    /* The ranges swapped: gamma_min <-> gamma_max, e_n_min <-> e_n_max. */
    for (f = 32; f <= 96 && f + 16 <= header; f += 64) {
        oblq_table t;
        memcpy(d, orig, n);
        memcpy(d + f, orig + f + 8, 8);
        memcpy(d + f + 8, orig + f, 8);
        reseal(d, n);
        tried++;
        if (oblq_open(&t, d, n) == OBLQ_OK) {
            opened++;
            if (!answers_bounded(&t, "headers: a range swapped")) {
                free(d);
                return 1;
            }
        } else {
            refused++;
        }
    }
    /* The integers: version, header size, length, stencil, reserved words, the offsets and
       the number of curves. */
    {
        static const size_t words[] = {8, 12, 64, 68, 80, 84};
        static const size_t longs[] = {16, 72, 88};
        uint64_t vals[] = {0, 1, 2, 3, 4, 7, 8, 96, 112, 0xffffffffULL, 0x80000000ULL};
        for (f = 0; f < sizeof words / sizeof words[0] + sizeof longs / sizeof longs[0]; f++) {
            int wide = f >= sizeof words / sizeof words[0];
            size_t at = wide ? longs[f - sizeof words / sizeof words[0]] : words[f];
            uint64_t o = wide ? oblq__u64(orig + at) : oblq__u32(orig + at);
            for (v = 0; v < sizeof vals / sizeof vals[0] + 4; v++) {
                oblq_table t;
                uint64_t x;
                char what[96];
                if (v < sizeof vals / sizeof vals[0]) x = vals[v];
                else x = o + (v % 2 ? 8 : -8) * (v >= sizeof vals / sizeof vals[0] + 2 ? 2 : 1);
                memcpy(d, orig, n);
                for (i = 0; i < (wide ? 8u : 4u); i++) d[at + i] = (unsigned char)(x >> (8 * i));
                reseal(d, n);
                tried++;
                if (oblq_open(&t, d, n) != OBLQ_OK) {
                    refused++;
                    continue;
                }
                opened++;
                snprintf(what, sizeof what, "headers: offset %lu = %llu", (unsigned long)at,
                         (unsigned long long)x);
                if (!answers_bounded(&t, what)) {
                    free(d);
                    return 1;
                }
            }
        }
    }
    if (!answers_bounded(&t0, "headers: the export itself")) {
        free(d);
        return 1;
    }
    printf("headers: %ld mutations, %ld refused, %ld opened and queried\n", tried, refused,
           opened);
    free(d);
    return 0;
}

int main(int argc, char **argv) {
    size_t n = 0;
    unsigned char *d;
    oblq_table t;
    if (argc < 3) {
        fprintf(stderr, "usage: eval_check MODE FILE ...\n");
        return 2;
    }
    d = read_all(argv[2], &n);
    if (!d) {
        fprintf(stderr, "eval_check: cannot read %s: %s\n", argv[2], strerror(errno));
        return 1;
    }
    if (!strcmp(argv[1], "open")) {
        int rc = oblq_open(&t, d, n);
        printf("%d %s\n", rc, oblq_error_message(rc));
    } else if (!strcmp(argv[1], "p") && argc == 4) {
        double g, a, p;
        int clamp = atoi(argv[3]);
        open_moved(&t, &d, n, -1, NULL);
        while (scanf("%lf %lf", &g, &a) == 2) {
            int rc = oblq_p(&t, g, a, clamp, &p);
            if (rc == OBLQ_OK) g17(p);
            else printf("error %d", rc);
            printf("\n");
        }
    } else if (!strcmp(argv[1], "pe") && argc == 4) {
        double g, a, e, p, lo = 0.0, hi = 0.0;
        int clamp = atoi(argv[3]);
        open_moved(&t, &d, n, -1, NULL);
        if (oblq_e_n_range(&t, &lo, &hi) != OBLQ_OK ||
            oblq_e_n_range(&t, NULL, &hi) != OBLQ_E_NULL ||
            oblq_p_e(NULL, 1.5, 0.3, 1.0, 0, &p) != OBLQ_E_NULL ||
            oblq_p_e(&t, 1.5, 0.3, 1.0, 0, NULL) != OBLQ_E_NULL) {
            fprintf(stderr, "eval_check: oblq_e_n_range or oblq_p_e: wrong status\n");
            exit(4);
        }
        printf("e_n %d ", t.has_e_n);
        g17(lo);
        printf(" ");
        g17(hi);
        printf("\n");
        while (scanf("%lf %lf %lf", &g, &a, &e) == 3) {
            int rc = oblq_p_e(&t, g, a, e, clamp, &p);
            if (rc == OBLQ_OK) g17(p);
            else printf("error %d", rc);
            printf("\n");
        }
    } else if (!strcmp(argv[1], "pat") && argc == 5) {
        /* oblq_p_at: lines of N values (N from the command line, any number of axes). */
        double x[8], p;
        int clamp = atoi(argv[3]), k = atoi(argv[4]), i, axes = 0;
        open_moved(&t, &d, n, -1, NULL);
        if (k < 0 || k > 8 || oblq_axis_count(&t, &axes) != OBLQ_OK ||
            oblq_axis_name(&t, axes) != NULL || oblq_axis_name(&t, -1) != NULL ||
            oblq_p_at(NULL, x, 2, 0, &p) != OBLQ_E_NULL ||
            oblq_p_at(&t, x, 2, 0, NULL) != OBLQ_E_NULL) {
            fprintf(stderr, "eval_check: oblq_axis_* or oblq_p_at: wrong status\n");
            exit(4);
        }
        printf("axes");
        for (i = 0; i < axes; i++) printf(" %s", oblq_axis_name(&t, i));
        printf("\n");
        for (;;) {
            int rc;
            for (i = 0; i < k; i++)
                if (scanf("%lf", &x[i]) != 1) break;
            if (i < k) break;
            rc = oblq_p_at(&t, x, k, clamp, &p);
            if (rc == OBLQ_OK) g17(p);
            else printf("error %d", rc);
            printf("\n");
        }
    } else if (!strcmp(argv[1], "curve") && argc == 5) {
        oblq_curve c;
        double a, p;
        int rc, clamp = atoi(argv[4]);
        open_moved(&t, &d, n, atol(argv[3]), &c);
        while (scanf("%lf", &a) == 1) {
            rc = oblq_curve_p(&c, a, clamp, &p);
            if (rc == OBLQ_OK) g17(p);
            else printf("error %d", rc);
            printf("\n");
        }
    } else if ((!strcmp(argv[1], "rebound") && (argc == 12 || argc == 13)) ||
               (!strcmp(argv[1], "rebound2") && (argc == 11 || argc == 12))) {
        int two = !strcmp(argv[1], "rebound2");
        int with_e = argc == (two ? 12 : 13);
        const char **a = (const char **)argv + (two ? 3 : 4);
        int use_curve = !two && !strcmp(argv[3], "curve");
        oblq_body b1, b2;
        oblq_pair k;
        oblq_curve c;
        double gamma, mu;
        int rc;
        open_moved(&t, &d, n, -1, NULL);
        b1.mass = atof(a[0]);
        b1.radius = atof(a[1]);
        b1.kappa = atof(a[2]);
        b2.mass = atof(a[3]);
        b2.radius = atof(a[4]);
        b2.kappa = atof(a[5]);
        gamma = atof(a[6]);
        mu = atof(a[7]);
        rc = with_e ? oblq_pair_init_e(&k, &b1, b2.mass > 0.0 ? &b2 : NULL, gamma, mu, atof(a[8]))
                    : oblq_pair_init(&k, &b1, b2.mass > 0.0 ? &b2 : NULL, gamma, mu);
        if (rc == OBLQ_OK && use_curve) rc = oblq_curve_find(&t, gamma, 0.0, &c);
        if (rc != OBLQ_OK) {
            printf("error %d\n", rc);
            return 0;
        }
        if (two) {
            oblq_state s1, s2;
            oblq_rebound2 r;
            while (scanf("%lf %lf %lf %lf %lf %lf", &s1.v_x, &s1.v_z, &s1.omega, &s2.v_x, &s2.v_z,
                         &s2.omega) == 6) {
                double v[13];
                int i;
                rc = oblq_rebound_2d(&t, NULL, &k, &s1, &s2, 0, &r);
                if (rc != OBLQ_OK) {
                    printf("error %d\n", rc);
                    continue;
                }
                v[0] = r.sphere.v_x; v[1] = r.sphere.v_z; v[2] = r.sphere.omega;
                v[3] = r.other.v_x; v[4] = r.other.v_z; v[5] = r.other.omega;
                v[6] = r.p; v[7] = r.e_t; v[8] = r.energy_lost; v[9] = r.alpha;
                v[10] = r.tangential_impulse;
                v[11] = r.normal_impulse; v[12] = r.e_n;
                for (i = 0; i < (with_e ? 13 : 11); i++) {
                    if (i) printf(" ");
                    g17(v[i]);
                }
                printf("\n");
            }
        } else {
            oblq_incident3 s;
            oblq_rebound3 r;
            double *in[15];
            int i;
            for (i = 0; i < 3; i++) {
                in[i] = &s.sphere.v[i];
                in[3 + i] = &s.sphere.w[i];
                in[6 + i] = &s.other.v[i];
                in[9 + i] = &s.other.w[i];
                in[12 + i] = &s.normal[i];
            }
            for (;;) {
                double v[21];
                for (i = 0; i < 15; i++)
                    if (scanf("%lf", in[i]) != 1) break;
                if (i < 15) break;
                rc = use_curve ? oblq_rebound_3d_curve(&c, &k, &s, 0, &r)
                               : oblq_rebound_3d(&t, &k, &s, 0, &r);
                if (rc != OBLQ_OK) {
                    printf("error %d\n", rc);
                    continue;
                }
                for (i = 0; i < 3; i++) {
                    v[i] = r.sphere.v[i];
                    v[3 + i] = r.sphere.w[i];
                    v[6 + i] = r.other.v[i];
                    v[9 + i] = r.other.w[i];
                }
                v[12] = r.p; v[13] = r.e_t; v[14] = r.energy_lost; v[15] = r.alpha;
                v[16] = r.slip_before;
                v[17] = r.normal_impulse; v[18] = r.e_n;
                for (i = 0; i < (with_e ? 19 : 17); i++) {
                    if (i) printf(" ");
                    g17(v[i]);
                }
                printf("\n");
            }
        }
    } else if (!strcmp(argv[1], "headers") && argc == 3) {
        int rc = headers(d, n);
        free(d);
        return rc;
    } else if (!strcmp(argv[1], "fuzz") && (argc == 5 || argc == 7)) {
        int rc;
        rng_state = strtoull(argv[4], NULL, 10);
        if (argc == 7) {
            fuzz_from = (size_t)strtoull(argv[5], NULL, 10);
            fuzz_to = (size_t)strtoull(argv[6], NULL, 10);
            if (fuzz_to > n || fuzz_from >= fuzz_to) {
                fprintf(stderr, "eval_check: fuzz: FROM TO not a block of the export\n");
                return 2;
            }
        }
        rc = fuzz(d, n, atol(argv[3]));
        free(d);
        return rc;
    } else {
        fprintf(stderr, "eval_check: bad arguments (see the comment at the top)\n");
        return 2;
    }
    free(d);
    return 0;
}
