/*
 * oblique_eval_f.c: real symbols with plain C types over include/oblique_eval.h (whose
 * functions are all static inline), for Fortran's iso_c_binding (fortran/oblique_eval.f90) or
 * any other language with a C foreign-function interface. Only libc and libm:
 *
 *     gcc -std=c99 -O2 -Wall -Wextra -Werror -pedantic -I include -c fortran/oblique_eval_f.c
 *
 * Every function returns an int status: OBLQ_OK (0), an OBLQ_E_* code of the header, or one of
 * the three codes of this file (OBLQF_E_IO, OBLQF_E_NOMEM, OBLQF_E_NOT_FILE), and writes its
 * outputs only on
 * OBLQ_OK. oblqf_message(code, ...) gives the text of any of them.
 *
 * Handles: oblqf_open makes a table (the export read into memory, checked once); oblqf_close
 * frees it. oblqf_curve_find makes a curve of one gamma of that table; oblqf_curve_free frees
 * it. A curve points into its table's memory: free the curves of a table before the table.
 * Handles are read-only once made and may be shared by threads; NULL handles are refused
 * (OBLQ_E_NULL), and closing or freeing NULL does nothing.
 *
 * Spheres: mass (kg), radius (m), kappa in I = kappa m R^2 (0.4 for a solid sphere). A second
 * mass m2 of exactly 0 means a fixed wall (then r2 and kappa2 are ignored and the wall's
 * velocity and spin must be zero). Vectors are double[3]; the normal points from sphere 1's
 * centre into the wall or towards sphere 2's centre (any non-zero length). clamp != 0: points
 * outside the table's domain get the answer at the nearest point of the domain instead of
 * OBLQ_E_GAMMA_DOMAIN / OBLQ_E_ALPHA_DOMAIN.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(__unix__) || defined(__APPLE__)
#include <sys/stat.h>
#endif

#include "oblique_eval.h"

/* Status codes of this file, beyond the header's. */
#define OBLQF_E_IO 101    /* the file cannot be read */
#define OBLQF_E_NOMEM 102 /* no memory for the export */
#define OBLQF_E_NOT_FILE 103 /* not a regular file: a directory, FIFO, device or socket */

/* The functions of this file (declared for C callers to copy; the Fortran interfaces are in
   fortran/oblique_eval.f90). */
int oblqf_open(const char *path, void **handle);
void oblqf_close(void *handle);
int oblqf_info(const void *handle, double *gamma_min, double *gamma_max, double *alpha_max,
               double *error_bound, int *has_surface, int *n_curves);
int oblqf_p(const void *handle, double gamma, double alpha, int clamp, double *p);
int oblqf_p_e(const void *handle, double gamma, double alpha, double e_n, int clamp, double *p);
int oblqf_e_n_range(const void *handle, double *e_n_min, double *e_n_max);
int oblqf_p_at(const void *handle, const double *x, int n, int clamp, double *p);
int oblqf_axis_count(const void *handle, int *n);
int oblqf_axis_name(const void *handle, int i, char *name, int cap, int *len);
int oblqf_curve_find(const void *handle, double gamma, double rel_tol, void **curve,
                     double *found_gamma);
void oblqf_curve_free(void *curve);
int oblqf_curve_p(const void *curve, double alpha, int clamp, double *p);
int oblqf_rebound_3d(const void *handle, double m1, double r1, double kappa1, double m2,
                     double r2, double kappa2, double gamma, double mu, const double v1[3],
                     const double w1[3], const double v2[3], const double w2[3],
                     const double normal[3], int clamp, double v1_out[3], double w1_out[3],
                     double v2_out[3], double w2_out[3], double *p, double *alpha, double *e_t,
                     double *energy_lost);
int oblqf_rebound_3d_e(const void *handle, double m1, double r1, double kappa1, double m2,
                       double r2, double kappa2, double gamma, double mu, double e_n,
                       const double v1[3], const double w1[3], const double v2[3],
                       const double w2[3], const double normal[3], int clamp, double v1_out[3],
                       double w1_out[3], double v2_out[3], double w2_out[3], double *p,
                       double *alpha, double *e_t, double *energy_lost);
int oblqf_rebound_3d_curve(const void *curve, double m1, double r1, double kappa1, double m2,
                           double r2, double kappa2, double mu, const double v1[3],
                           const double w1[3], const double v2[3], const double w2[3],
                           const double normal[3], int clamp, double v1_out[3],
                           double w1_out[3], double v2_out[3], double w2_out[3], double *p,
                           double *alpha, double *e_t, double *energy_lost);
int oblqf_gamma_of(double m1, double r1, double kappa1, double m2, double r2, double kappa2,
                   double e1, double nu1, double e2, double nu2, double *gamma);
int oblqf_message(int code, char *buf, int cap);

/* A table: the export (malloc'ed, so 8-byte aligned) and the checked view of it. */
typedef struct {
    oblq_table table;
    void *data;
} oblqf_table;

/* The whole file in a malloc'ed buffer; OBLQ_OK, OBLQF_E_IO, OBLQF_E_NOMEM or
   OBLQF_E_NOT_FILE. Only a regular file is opened (a FIFO would block, a device such as
   /dev/zero would be read until memory runs out), and no more bytes are read than the file
   had when it was opened (plus one, to see that it grew: then it is refused). */
static int oblqf__read(const char *path, void **data, size_t *size) {
    FILE *f;
    char *buf = NULL;
    size_t cap = 0, len = 0, n, limit = (size_t)-1;
#if defined(__unix__) || defined(__APPLE__)
    struct stat st;
    if (stat(path, &st) != 0) return OBLQF_E_IO;
    if (!S_ISREG(st.st_mode)) return OBLQF_E_NOT_FILE;
    if ((unsigned long long)st.st_size < (unsigned long long)((size_t)-1))
        limit = (size_t)st.st_size + 1;
#endif
    f = fopen(path, "rb");
    if (!f) return OBLQF_E_IO;
    for (;;) {
        if (len == cap) {
            char *bigger;
            cap = cap ? 2 * cap : (size_t)1 << 20;
            bigger = (char *)realloc(buf, cap);
            if (!bigger) {
                free(buf);
                fclose(f);
                return OBLQF_E_NOMEM;
            }
            buf = bigger;
        }
        n = fread(buf + len, 1, (cap - len < limit - len) ? cap - len : limit - len, f);
        len += n;
        if (n == 0 || len == limit) break;
    }
    if (limit != (size_t)-1 && len == limit) { /* it grew while being read */
        free(buf);
        fclose(f);
        return OBLQF_E_IO;
    }
    if (ferror(f)) { /* e.g. a directory */
        free(buf);
        fclose(f);
        return OBLQF_E_IO;
    }
    fclose(f);
    *data = buf;
    *size = len;
    return OBLQ_OK;
}

/* Read the export at `path` (a NUL-terminated file name) and check it; *handle: the table
   (free with oblqf_close), or NULL on an error. */
int oblqf_open(const char *path, void **handle) {
    oblqf_table *h;
    void *data = NULL;
    size_t size = 0;
    int rc;
    if (!path || !handle) return OBLQ_E_NULL;
    *handle = NULL;
    rc = oblqf__read(path, &data, &size);
    if (rc != OBLQ_OK) return rc;
    h = (oblqf_table *)malloc(sizeof *h);
    if (!h) {
        free(data);
        return OBLQF_E_NOMEM;
    }
    rc = oblq_open(&h->table, data, size);
    if (rc != OBLQ_OK) {
        free(data);
        free(h);
        return rc;
    }
    h->data = data;
    *handle = h;
    return OBLQ_OK;
}

/* Free a table made by oblqf_open (NULL: nothing). */
void oblqf_close(void *handle) {
    oblqf_table *h = (oblqf_table *)handle;
    if (!h) return;
    free(h->data);
    free(h);
}

static const oblq_table *oblqf__table(const void *handle) {
    return handle ? &((const oblqf_table *)handle)->table : NULL;
}

/* The table's domain, its absolute error bound on P, whether it holds the surface (1) or
   only curves (0), and its number of curves. Any output pointer may be NULL. */
int oblqf_info(const void *handle, double *gamma_min, double *gamma_max, double *alpha_max,
               double *error_bound, int *has_surface, int *n_curves) {
    const oblq_table *t = oblqf__table(handle);
    if (!t) return OBLQ_E_NULL;
    if (gamma_min) *gamma_min = t->gamma_min;
    if (gamma_max) *gamma_max = t->gamma_max;
    if (alpha_max) *alpha_max = t->alpha_max;
    if (error_bound) *error_bound = t->error_bound;
    if (has_surface) *has_surface = t->has_surface;
    if (n_curves) *n_curves = t->n_curves > 2147483647u ? 2147483647 : (int)t->n_curves;
    return OBLQ_OK;
}

/* P(gamma, alpha) by the table's rule (alpha = INFINITY: no slip). */
int oblqf_p(const void *handle, double gamma, double alpha, int clamp, double *p) {
    return oblq_p(oblqf__table(handle), gamma, alpha, clamp, p);
}

/* P(gamma, alpha, e_n) at normal restitution e_n, in the table's e_n range (never clamped;
   an elastic table answers e_n = 1 only). */
int oblqf_p_e(const void *handle, double gamma, double alpha, double e_n, int clamp, double *p) {
    return oblq_p_e(oblqf__table(handle), gamma, alpha, e_n, clamp, p);
}

/* P at the point x[0..n), one value per axis of the table (oblq_p_at). */
int oblqf_p_at(const void *handle, const double *x, int n, int clamp, double *p) {
    return oblq_p_at(oblqf__table(handle), x, n, clamp, p);
}

/* The number of axes of a point of the table (oblq_axis_count). */
int oblqf_axis_count(const void *handle, int *n) {
    return oblq_axis_count(oblqf__table(handle), n);
}

/* The name of axis i (0-based) into name[0..cap) blank-padded (Fortran's character), *len its
   length; OBLQ_E_AXES for another i. */
int oblqf_axis_name(const void *handle, int i, char *name, int cap, int *len) {
    const char *s = oblq_axis_name(oblqf__table(handle), i);
    int k = 0;
    if (!name || !len) return OBLQ_E_NULL;
    if (!s) return oblqf__table(handle) ? OBLQ_E_AXES : OBLQ_E_NULL;
    for (; s[k] && k < cap; k++) name[k] = s[k];
    *len = k;
    for (; k < cap; k++) name[k] = ' ';
    return OBLQ_OK;
}

/* The e_n range the table answers (1, 1 for an elastic table). */
int oblqf_e_n_range(const void *handle, double *e_n_min, double *e_n_max) {
    return oblq_e_n_range(oblqf__table(handle), e_n_min, e_n_max);
}

/* The curve of the export whose gamma is nearest to `gamma`, if within `rel_tol` relative
   (0: exactly the exported value); *curve: the curve (free with oblqf_curve_free) or NULL on
   an error; *found_gamma (may be NULL): the exported gamma of that curve. */
int oblqf_curve_find(const void *handle, double gamma, double rel_tol, void **curve,
                     double *found_gamma) {
    oblq_curve c, *out;
    int rc;
    if (!curve) return OBLQ_E_NULL;
    *curve = NULL;
    rc = oblq_curve_find(oblqf__table(handle), gamma, rel_tol, &c);
    if (rc != OBLQ_OK) return rc;
    out = (oblq_curve *)malloc(sizeof *out);
    if (!out) return OBLQF_E_NOMEM;
    *out = c;
    *curve = out;
    if (found_gamma) *found_gamma = c.gamma;
    return OBLQ_OK;
}

/* Free a curve made by oblqf_curve_find (NULL: nothing). */
void oblqf_curve_free(void *curve) { free(curve); }

/* P(alpha) at the curve's gamma. */
int oblqf_curve_p(const void *curve, double alpha, int clamp, double *p) {
    return oblq_curve_p((const oblq_curve *)curve, alpha, clamp, p);
}

static oblq_body oblqf__body(double mass, double radius, double kappa) {
    oblq_body b;
    b.mass = mass;
    b.radius = radius;
    b.kappa = kappa;
    return b;
}

/* The pair of bodies: sphere 1 on a wall (m2 == 0) or on sphere 2. */
static int oblqf__pair(oblq_pair *k, double m1, double r1, double kappa1, double m2, double r2,
                       double kappa2, double gamma, double mu, double e_n) {
    oblq_body b1 = oblqf__body(m1, r1, kappa1), b2 = oblqf__body(m2, r2, kappa2);
    return oblq_pair_init_e(k, &b1, m2 == 0.0 ? NULL : &b2, gamma, mu, e_n);
}

static int oblqf__rebound(const oblq_table *t, const oblq_curve *c, double m1, double r1,
                          double kappa1, double m2, double r2, double kappa2, double gamma,
                          double mu, double e_n, const double v1[3], const double w1[3], const double v2[3],
                          const double w2[3], const double normal[3], int clamp, double v1_out[3],
                          double w1_out[3], double v2_out[3], double w2_out[3], double *p,
                          double *alpha, double *e_t, double *energy_lost) {
    oblq_pair k;
    oblq_incident3 s;
    oblq_rebound3 r;
    int i, rc;
    if (!v1 || !w1 || !v2 || !w2 || !normal || !v1_out || !w1_out || !v2_out || !w2_out || !p ||
        !alpha || !e_t || !energy_lost)
        return OBLQ_E_NULL;
    rc = oblqf__pair(&k, m1, r1, kappa1, m2, r2, kappa2, gamma, mu, e_n);
    if (rc != OBLQ_OK) return rc;
    for (i = 0; i < 3; i++) {
        s.sphere.v[i] = v1[i];
        s.sphere.w[i] = w1[i];
        s.other.v[i] = v2[i];
        s.other.w[i] = w2[i];
        s.normal[i] = normal[i];
    }
    rc = c ? oblq_rebound_3d_curve(c, &k, &s, clamp, &r) : oblq_rebound_3d(t, &k, &s, clamp, &r);
    if (rc != OBLQ_OK) return rc;
    for (i = 0; i < 3; i++) {
        v1_out[i] = r.sphere.v[i];
        w1_out[i] = r.sphere.w[i];
        v2_out[i] = r.other.v[i];
        w2_out[i] = r.other.w[i];
    }
    *p = r.p;
    *alpha = r.alpha;
    *e_t = r.e_t;
    *energy_lost = r.energy_lost;
    return OBLQ_OK;
}

/* The 3-D rebound of sphere 1 (m1, r1, kappa1) on a wall (m2 == 0) or on sphere 2 (m2, r2,
   kappa2), with material group gamma (oblqf_gamma_of) and friction mu >= 0 (INFINITY: no
   slip), P from the table. Before: velocities v1, v2 (m/s), spins w1, w2 (rad/s), normal.
   After: v1_out, w1_out, v2_out, w2_out (a wall's stay zero); P (NaN when the contact point
   does not slip), alpha (INFINITY then), e_t (the tangential restitution of the centres; NaN
   when they have no tangential motion) and the kinetic energy lost to friction (J). */
int oblqf_rebound_3d(const void *handle, double m1, double r1, double kappa1, double m2,
                     double r2, double kappa2, double gamma, double mu, const double v1[3],
                     const double w1[3], const double v2[3], const double w2[3],
                     const double normal[3], int clamp, double v1_out[3], double w1_out[3],
                     double v2_out[3], double w2_out[3], double *p, double *alpha, double *e_t,
                     double *energy_lost) {
    const oblq_table *t = oblqf__table(handle);
    if (!t) return OBLQ_E_NULL;
    return oblqf__rebound(t, NULL, m1, r1, kappa1, m2, r2, kappa2, gamma, mu, 1.0, v1, w1, v2,
                          w2, normal, clamp, v1_out, w1_out, v2_out, w2_out, p, alpha, e_t,
                          energy_lost);
}

/* oblqf_rebound_3d at normal restitution 0 <= e_n <= 1 (oblq_pair_init_e): the normal relative
   velocity reverses to e_n times its value, P is the table's P(gamma, alpha, e_n) (e_n in its
   e_n range, else OBLQ_E_E_N; an elastic table: e_n = 1 only), and energy_lost adds
   (m* / 2) v_z0^2 (1 - e_n^2). e_n = 1: the bits of oblqf_rebound_3d. */
int oblqf_rebound_3d_e(const void *handle, double m1, double r1, double kappa1, double m2,
                       double r2, double kappa2, double gamma, double mu, double e_n,
                       const double v1[3], const double w1[3], const double v2[3],
                       const double w2[3], const double normal[3], int clamp, double v1_out[3],
                       double w1_out[3], double v2_out[3], double w2_out[3], double *p,
                       double *alpha, double *e_t, double *energy_lost) {
    const oblq_table *t = oblqf__table(handle);
    if (!t) return OBLQ_E_NULL;
    return oblqf__rebound(t, NULL, m1, r1, kappa1, m2, r2, kappa2, gamma, mu, e_n, v1, w1, v2,
                          w2, normal, clamp, v1_out, w1_out, v2_out, w2_out, p, alpha, e_t,
                          energy_lost);
}

/* oblqf_rebound_3d with P from a curve (its gamma is the pair's: no gamma argument). */
int oblqf_rebound_3d_curve(const void *curve, double m1, double r1, double kappa1, double m2,
                           double r2, double kappa2, double mu, const double v1[3],
                           const double w1[3], const double v2[3], const double w2[3],
                           const double normal[3], int clamp, double v1_out[3],
                           double w1_out[3], double v2_out[3], double w2_out[3], double *p,
                           double *alpha, double *e_t, double *energy_lost) {
    const oblq_curve *c = (const oblq_curve *)curve;
    if (!c) return OBLQ_E_NULL;
    return oblqf__rebound(NULL, c, m1, r1, kappa1, m2, r2, kappa2, c->gamma, mu, 1.0, v1, w1, v2,
                          w2, normal, clamp, v1_out, w1_out, v2_out, w2_out, p, alpha, e_t,
                          energy_lost);
}

/* gamma = sqrt((m* / m_t) G* / E*) of sphere 1 (m1, r1, kappa1; Young's modulus e1 in Pa,
   Poisson's ratio nu1) on a wall (m2 == 0; e2, nu2 the wall's) or on sphere 2. A rigid body:
   e = INFINITY. */
int oblqf_gamma_of(double m1, double r1, double kappa1, double m2, double r2, double kappa2,
                   double e1, double nu1, double e2, double nu2, double *gamma) {
    oblq_body b1 = oblqf__body(m1, r1, kappa1), b2 = oblqf__body(m2, r2, kappa2);
    oblq_material a, b;
    a.youngs_modulus = e1;
    a.poisson_ratio = nu1;
    b.youngs_modulus = e2;
    b.poisson_ratio = nu2;
    return oblq_gamma_of(&b1, m2 == 0.0 ? NULL : &b2, &a, &b, gamma);
}

/* The text of a status code: copies min(length, cap) bytes into buf (and a terminating NUL
   when there is room), returns the length of the whole text (without NUL). buf may be NULL
   when cap is 0: the length alone. */
int oblqf_message(int code, char *buf, int cap) {
    const char *text;
    size_t len;
    switch (code) {
    case OBLQF_E_IO:
        text = "cannot read the export file: it does not exist, is not readable, or is a "
               "directory";
        break;
    case OBLQF_E_NOMEM: text = "out of memory reading the export"; break;
    case OBLQF_E_NOT_FILE:
        text = "the export path is not a regular file (a directory, FIFO, device or socket)";
        break;
    default: text = oblq_error_message(code); break;
    }
    len = strlen(text);
    if (buf && cap > 0) {
        size_t n = len < (size_t)cap ? len : (size_t)cap;
        memcpy(buf, text, n);
        if (n < (size_t)cap) buf[n] = '\0';
    }
    return (int)len;
}
