/*
 * oblique_eval.h: the tangential restitution P(gamma, alpha) of oblique elastic impacts with
 * friction (and P(gamma, alpha, e_n) of dissipative ones, from a table with a normal-restitution
 * axis of the Kelvin-Voigt or Thornton's elastic-plastic law, or from the table of one pair:
 * P(alpha, e_n) at its single gamma), and the rebounds of
 * spheres on walls and on spheres, evaluated from an export of a table
 * (`sweep export TABLE -o FILE`) held in memory. One header, no library but libm, no
 * allocation (but in the optional file loader oblq_load_file): C99 and later, C++11 and later.
 * Little-endian machines only (x86-64, AArch64).
 *
 *   #include "oblique_eval.h"
 *   oblq_table t;
 *   int rc = oblq_open(&t, bytes, size);          // checks the export once (layout, checksum)
 *   rc = oblq_load_file(&t, "full.oblq");         // or: read the file, then oblq_open (host)
 *   double p;
 *   rc = oblq_p(&t, 1.754, 0.3, 0, &p);           // P(gamma, alpha); rc = OBLQ_OK or an error
 *   rc = oblq_p_e(&t, 1.45, 0.3, 0.8, 0, &p);     // P(gamma, alpha, e_n): a table with the axis
 *   double x[3] = {1.45, 0.3, 0.8};               // or a point, one value per axis:
 *   rc = oblq_p_at(&t, x, 3, 0, &p);              // oblq_axis_count, oblq_axis_name list them
 *
 * Symbols and units (SI) as in the project's physics.md: gamma = sqrt((m* / m_t) G* / E*),
 * alpha = (2/7)(m* / m_t) mu v_z0/|u0|, P = u_after/u_before (the tangential restitution of the
 * contact point), -1 <= P <= 1. The rule is the one of docs/table-format.md; the layout of an
 * export is docs/export-format.md.
 *
 * Every function returns an int status: OBLQ_OK (0) or a positive OBLQ_E_* code, never reads
 * outside the export it was given, and writes its outputs only on OBLQ_OK.
 * oblq_error_message(code) names the argument and the allowed range. The data an oblq_table
 * points to must stay alive and unchanged while it is used; an oblq_table, oblq_curve and
 * oblq_pair are read-only after they are made and may be shared by threads.
 *
 * Answers agree with the Rust library (oblique-lookup) to the last bit when compiled without
 * value-changing optimisations (no -ffast-math; on machines with fused multiply-add, also
 * -ffp-contract=off, which ISO modes such as -std=c99 select in GCC): the same operations in
 * the same order. Otherwise they differ by rounding only (a few units in the last place).
 *
 * GPU codes (CUDA): `#define OBLQ_FN __host__ __device__ static inline` before including marks
 * every function for host and device code alike (none calls a host-only function). Open the
 * export on the host, copy its bytes to the device, and move a copy of the table there:
 *
 *   oblq_table host, dev;                          // host: checks the bytes at `bytes`
 *   oblq_open(&host, bytes, size);
 *   cudaMalloc(&d_bytes, size); cudaMemcpy(d_bytes, bytes, size, cudaMemcpyHostToDevice);
 *   dev = host;
 *   oblq_rebase(&dev, d_bytes);                    // dev's pointers now point into d_bytes
 *   kernel<<<blocks, threads>>>(dev, ...);         // by value; oblq_p(&dev, ...) in the kernel
 *
 * (oblq_curve_rebase moves a curve the same way; oblq_open also runs in a kernel, on one
 * thread, but reads the whole export serially.) Compiled with nvcc -fmad=false (no fused
 * multiply-add, as -ffp-contract=off on the host; without it oblq_open and oblq_curve_get,
 * which check stored values against the rule's to the bit, may refuse a sound export), device
 * answers are the host's bit for bit except where CUDA's double log, within 1 ulp of the exact
 * logarithm but not always rounded as the host's libm, differs: in partial slip, where P then
 * differs in the last bits only, by at most 2e-15 (on an NVIDIA H200 over 2^24 random points:
 * 1.2e-15, about 1 answer in 4000 not the host's bits; a curve's P 3.3e-16; on the host with
 * half of the logs off by an ulp: 2e-15; oblq_p_e of a table with an e_n axis likewise: log is
 * its only call that CUDA may round otherwise, the square roots of an e_n axis over
 * (1 - e_n)^(1/4) (layout version 8) being correctly rounded there too; on the table of one pair,
 * tables/dissipative-pair.h5, over 2^24 random points on an NVIDIA H100: every status the
 * host's, 3840 answers not the host's bits, by at most 4.4e-16).
 * A 3-D rebound carries that difference into the fields computed from P: over 2^24 random
 * sphere-sphere impacts (H200) every field was within 4.3e-14 of the host's, relative to the
 * field's size where that exceeds 1 and absolute below, i.e. |device - host| <= 4.3e-14
 * max(1, |host|): relative for the spins (rad/s, nearly all above 1), absolute for most
 * velocity components (m/s, mostly below 1) and for the impulses and energy lost (below
 * 1e-3 N s and 1e-4 J there, so the bound says little about them). At random e_n
 * (oblq_pair_init_e; 2^24 wall and sphere impacts on the export of tables/dissipative-demo.h5,
 * H200): 5483 answers not the host's bits, every field (with e_t) within 1.14e-13 max(1, |host|).
 * examples/cuda/oblique_gpu.cu does all of this (elastic tables, and tables with an e_n axis:
 * oblq_p_e and rebounds at each pair's e_n) and compares the device with the host.
 */
#ifndef OBLIQUE_EVAL_H
#define OBLIQUE_EVAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#ifndef OBLQ_NO_STDIO
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#if defined(__unix__) || defined(__APPLE__)
#include <sys/stat.h>
#endif
#endif

#ifndef OBLQ_FN
#define OBLQ_FN static inline
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Newest layout version this header reads: 1 (an elastic table, and curves), 2 (a table
   with a normal-restitution axis e_n), 3 (the table of one pair: P(alpha, e_n) at a single
   gamma), 4 (a table of Thornton's law: version 2 without a closed-form full-slip line), 5
   (version 2 or 4 whose partial-slip coordinate has knots), 6 (an elastic table whose
   split cells halve only the axes their masks name), 7 (version 5 whose stick patch
   stick_high has knots too) and 8 (version 2, 4, 5 or 7 whose e_n axis is mapped: its trees
   over x_e = (t(e_n_min) - t(e_n))/(t(e_n_min) - t(e_n_max)), t(e) = (1 - e)^(1/4)). */
#define OBLQ_EXPORT_VERSION 8u

/* Most knots of a patch's coordinate (layout versions 5, 7 and 8). */
#define OBLQ_MAX_KNOTS 8

/* Status codes of the file loader oblq_load_file (host only; the others follow). */
enum {
    OBLQ_E_FILE = 25,      /* the file cannot be opened or read (errno says why) */
    OBLQ_E_NOT_FILE = 26,  /* the path is a directory, FIFO, device or socket, not a file */
    OBLQ_E_NO_MEMORY = 27  /* no memory for the file's contents */
};

/* Status codes. */
enum {
    OBLQ_OK = 0,
    OBLQ_E_NULL = 1,          /* a pointer argument is NULL */
    OBLQ_E_TRUNCATED = 2,     /* the data is shorter than its header says (truncated) */
    OBLQ_E_FORMAT = 3,        /* not an export: wrong magic bytes */
    OBLQ_E_VERSION = 4,       /* an export of another layout version */
    OBLQ_E_CHECKSUM = 5,      /* damaged: the checksum does not match the contents */
    OBLQ_E_CORRUPT = 6,       /* inconsistent contents (offsets, sizes, values) */
    OBLQ_E_GAMMA = 7,         /* gamma not finite or <= 0 */
    OBLQ_E_ALPHA = 8,         /* alpha NaN or < 0 */
    OBLQ_E_GAMMA_DOMAIN = 9,  /* gamma outside the table's domain (and not on the line) */
    OBLQ_E_ALPHA_DOMAIN = 10, /* alpha above the table's alpha_max */
    OBLQ_E_NO_SURFACE = 11,   /* a curves-only export asked for P at any gamma */
    OBLQ_E_NO_CURVE = 12,     /* no curve of that gamma (or index) in the export */
    OBLQ_E_MASS = 13,         /* a mass not finite or <= 0 */
    OBLQ_E_RADIUS = 14,       /* a radius not finite or <= 0 */
    OBLQ_E_KAPPA = 15,        /* an inertia factor not finite or <= 0 */
    OBLQ_E_FRICTION = 16,     /* friction NaN or < 0 */
    OBLQ_E_MODULUS = 17,      /* Young's modulus NaN or <= 0, or both bodies rigid */
    OBLQ_E_POISSON = 18,      /* Poisson's ratio outside (-1, 0.5] */
    OBLQ_E_MOTION = 19,       /* a velocity, spin or normal component not finite */
    OBLQ_E_NORMAL = 20,       /* a zero (or overflowing) normal */
    OBLQ_E_APPROACH = 21,     /* the bodies do not approach along the normal (v_z0 <= 0) */
    OBLQ_E_WALL_MOTION = 22,  /* a wall (other = NULL) given a non-zero motion */
    OBLQ_E_P_RANGE = 23,      /* P outside [-1, 1] given to oblq_e_t */
    OBLQ_E_E_N = 24,          /* e_n outside the table's e_n range (elastic: e_n != 1) */
    OBLQ_E_AXES = 28          /* a point of another number of values than the table's axes */
};

/* Deprecated: the old name of OBLQ_E_P_RANGE (kept for source compatibility). */
#define OBLQ_E_KAPPA_P OBLQ_E_P_RANGE

/* One patch of the surface (pointers into the export). */
typedef struct {
    int present;
    int partial;                /* 1: the partial-slip patch, 0: a stick patch */
    double gamma_lo, gamma_hi;
    size_t blocks_gamma, blocks_coord, m, cells, leaves;
    const unsigned char *tree; /* int32 little-endian [cells] */
    const double *p;           /* [leaves][m+1][m+1] */
    int warp;
    double w_start, w_gamma_0, w_gamma_step, w_c_star;
    size_t w_n;
    const double *knot;
    /* The fine index (NULL: descend from the roots): rows x cols cell numbers at depth
       log2(fine), and every cell's 2^depth and origin. */
    const unsigned char *index; /* uint32 little-endian [rows][cols] */
    const double *origin;       /* [cells][3]: scale, og, oc */
    size_t rows, cols;
    double fine;
    /* Root cells along e_n (1 without the axis); with the axis the tree is an octree and p
       is [leaves][m+1][m+1][m+1]; in the patch of one pair (gamma_lo == gamma_hi,
       blocks_gamma 1) a quadtree over (c, e_n) and p is [leaves][m+1][m+1]. */
    size_t blocks_e_n;
    /* Optionally: which axes each split cell halves, uint8 [cells]; NULL: every split halves
       every axis. With the axis bit 4: gamma, 2: c, 1: e_n (1 to 3 in the patch of one pair:
       c, e_n); without it (layout version 6) bit 2: gamma, 1: c; 0 for a leaf. */
    const unsigned char *split;
    /* The knots of the patch's coordinate (layout version 5: partial_high; 7 and 8:
       partial_high and stick_high; k_n = 0: none): k_n kink
       surfaces K_j tabulated at (k_gamma_0 + i k_gamma_step, k_e_n_0 + l k_e_n_step),
       k_knot [k_n][k_ng][k_ne], sent to k_c_star[j] inside k_region (root cells: gamma from,
       gamma to, e_n from, e_n to); k_grade[j]: 0 linear, 1 the segment below graded, 2 the
       segment above. */
    size_t k_n, k_ng, k_ne;
    double k_gamma_0, k_gamma_step, k_e_n_0, k_e_n_step, k_region[4];
    unsigned char k_grade[OBLQ_MAX_KNOTS];
    const double *k_c_star, *k_knot;
} oblq_patch;

/* A checked export: the table's domain and stated error bound, its patches, its curves. */
typedef struct {
    double gamma_min, gamma_max, alpha_max;
    double error_bound; /* absolute error bound of every P the table answers */
    int has_surface;    /* 0 for a curves-only export */
    oblq_patch patch[3]; /* stick_low, partial_high, stick_high */
    size_t n_curves;
    const unsigned char *data; /* the export */
    uint64_t size;
    uint64_t curves; /* offset of the curve records */
    int has_e_n; /* 1: a table with a normal-restitution axis (layout versions 2 to 5, 7, 8) */
    double e_n_min, e_n_max;  /* the e_n range it answers: 1, 1 for an elastic table */
    /* The map of the e_n axis: 0 linear, x_e = (e_n - e_n_min)/(e_n_max - e_n_min); 1 (layout
       version 8) over t = (1 - e_n)^(1/4), x_e = (m(e_n) - e_n_lo)/e_n_width with
       m(e) = -sqrt(sqrt(1 - e)), e_n_lo = m(e_n_min), e_n_width = m(e_n_max) - e_n_lo, i.e.
       (t_min - t)/(t_min - t_max) (0 and 1 for a linear axis: unused). */
    int e_n_map;
    double e_n_lo, e_n_width;
    int pair; /* 1: the table of one pair (layout version 3): gamma_min == gamma_max, its gamma */
    /* 1: a table without a closed-form full-slip line (layout version 4, or 5, 7 and 8 with the
       flag, Thornton's law): its partial-slip patch answers every alpha < alpha_c2 for gamma >= 1
       (gamma_min >= 1). */
    int no_line;
} oblq_table;

/* One patch of a curve. */
typedef struct {
    int present;
    size_t n;             /* intervals */
    const double *coef;   /* [n][4] */
    int warp;
    double k, c_star;
} oblq_piece;

/* P(alpha) at one gamma, precomputed (a curve of the export). */
typedef struct {
    double gamma, alpha_lin, alpha_c2, g2, ratio, ln_ratio, stick_c2, rho_c2, s_max, alpha_max;
    int high;
    oblq_piece partial, stick;
} oblq_curve;

/* ---------------------------------------------------------------------------------------- */
/* Reading the export                                                                         */

OBLQ_FN uint32_t oblq__u32(const unsigned char *b) {
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) |
           ((uint32_t)b[3] << 24);
}

OBLQ_FN uint64_t oblq__u64(const unsigned char *b) {
    return (uint64_t)oblq__u32(b) | ((uint64_t)oblq__u32(b + 4) << 32);
}

OBLQ_FN double oblq__f64(const unsigned char *b) {
    double d;
    uint64_t u = oblq__u64(b);
    memcpy(&d, &u, sizeof d);
    return d;
}

OBLQ_FN int32_t oblq__i32(const unsigned char *b) {
    uint32_t u = oblq__u32(b);
    int32_t i;
    memcpy(&i, &u, sizeof i);
    return i;
}

/* Whether [off, off + count*size) lies inside [0, len), 8-byte aligned (no overflow). */
OBLQ_FN int oblq__span(uint64_t off, uint64_t count, uint64_t size, uint64_t len) {
    if (off % 8 != 0 || off > len) return 0;
    if (size != 0 && count > (len - off) / size) return 0;
    return 1;
}

OBLQ_FN int oblq__finite_array(const double *v, size_t n) {
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* The mapped value m(e) = -(1 - e)^(1/4) of an e_n axis over (1 - e_n)^(1/4) (layout version
   8), as -sqrt(sqrt(1 - e)): two correctly rounded square roots (host and CUDA alike), the
   Rust library's operations. */
OBLQ_FN double oblq__quarter_root(double e) { return -sqrt(sqrt(1.0 - e)); }

/* The coordinate x_e of e_n along the table's e_n axis (steps 6 and 7, and where the knots
   apply): (e_n - e_n_min)/(e_n_max - e_n_min) on a linear axis, (m(e_n) - e_n_lo)/e_n_width
   on an axis over (1 - e_n)^(1/4) (layout version 8): the same bits as the Rust library. */
OBLQ_FN double oblq__x_e(const oblq_table *t, double e_n) {
    if (t->e_n_map) return (oblq__quarter_root(e_n) - t->e_n_lo) / t->e_n_width;
    return (e_n - t->e_n_min) / (t->e_n_max - t->e_n_min);
}

/* The e_n at root-cell position v of an e_n axis of `blocks` root cells (the knots' check):
   e_n_min + (e_n_max - e_n_min) v/blocks on a linear axis; over (1 - e_n)^(1/4) the inverse
   of the map at x = v/blocks, e_n_min at x <= 0, e_n_max at x >= 1, else 1 - w^4 of
   w = e_n_lo + e_n_width x, clamped to [e_n_min, e_n_max]. */
OBLQ_FN double oblq__e_n_at(const oblq_table *t, double v, double blocks) {
    double x, w;
    if (!t->e_n_map) return t->e_n_min + (t->e_n_max - t->e_n_min) * v / blocks;
    x = v / blocks;
    if (x >= 1.0) return t->e_n_max;
    if (x <= 0.0) return t->e_n_min;
    w = t->e_n_lo + t->e_n_width * x;
    w = w * w;
    w = 1.0 - w * w;
    return w < t->e_n_min ? t->e_n_min : w > t->e_n_max ? t->e_n_max : w;
}

/* A patch record; `axes`: 2 of an elastic table (versions 1 and 6), 3 of a table with an e_n
   axis (version 2: an octree over gamma, c, e_n), 1 of the table of one pair (version 3: a
   single gamma, a quadtree over c, e_n). `masked`: an elastic table whose records may name
   split masks (version 6); a patch with masks has no fine index. */
OBLQ_FN int oblq__patch(oblq_patch *p, const unsigned char *d, uint64_t len,
                        const unsigned char *r, int axes, int masked) {
    uint64_t cells, leaves, m, bg, bc, be, fan, roots, i, nodes, off, masks;
    int octree = axes != 2, pair = axes == 1;
    memset(p, 0, sizeof *p);
    if (oblq__u32(r) == 0) return OBLQ_OK;
    if (oblq__u32(r) != 1 || oblq__u32(r + 4) > 1) return OBLQ_E_CORRUPT;
    p->present = 1;
    p->partial = (int)oblq__u32(r + 4);
    p->gamma_lo = oblq__f64(r + 8);
    p->gamma_hi = oblq__f64(r + 16);
    bg = oblq__u32(r + 24);
    bc = oblq__u32(r + 28);
    m = oblq__u32(r + 32);
    cells = oblq__u32(r + 36);
    leaves = oblq__u32(r + 40);
    /* gamma_lo < gamma_hi; equal (and one root along gamma) in the patch of one pair only. */
    if (!(isfinite(p->gamma_lo) && isfinite(p->gamma_hi) && p->gamma_lo > 0.0 &&
          (pair ? p->gamma_lo == p->gamma_hi && bg == 1 : p->gamma_lo < p->gamma_hi)))
        return OBLQ_E_CORRUPT;
    if (bg < 1 || bc < 1 || m < 3 || m > 64 || leaves < 1) return OBLQ_E_CORRUPT;
    be = 1;
    fan = 4;
    masks = 3; /* the masks a split cell may have: 1 to 3 over (gamma, c) */
    if (octree) {
        /* The e_n axis: an octree (a quadtree over c, e_n in the patch of one pair), without a
           warp or a fine index. */
        be = oblq__u32(r + 136);
        fan = pair ? 4 : 8;
        masks = pair ? 3 : 7;
        if (be < 1 || be > 65536 || oblq__u32(r + 44) != 0 || oblq__u64(r + 120) != 0)
            return OBLQ_E_CORRUPT;
    }
    roots = bg * bc; /* < 2^64; then at most cells (< 2^32) times be (<= 2^16) */
    if (cells < roots) return OBLQ_E_CORRUPT;
    roots *= be;
    if (cells < roots) return OBLQ_E_CORRUPT;
    off = oblq__u64(r + 48);
    if (!oblq__span(off, cells, 4, len)) return OBLQ_E_CORRUPT;
    p->tree = d + off;
    p->split = NULL;
    if (octree || masked) {
        /* The split masks (offset 0: none). Their offset need not be 8-byte aligned. In an
           elastic table (version 6) a patch with masks is descended from its roots: no fine
           index. */
        off = oblq__u64(r + 144);
        if (off != 0) {
            if (off > len || cells > len - off) return OBLQ_E_CORRUPT;
            if (!octree && (oblq__u64(r + 120) != 0 || oblq__u64(r + 128) != 0 ||
                            oblq__u32(r + 112) != 0))
                return OBLQ_E_CORRUPT;
            p->split = d + off;
        }
    } else if (oblq__u64(r + 144) != 0) {
        return OBLQ_E_CORRUPT;
    }
    /* Safe descent: a split cell's children exist and come after it (so every descent ends),
       a leaf number is in range; a mask is 1 to 7 for a split cell of an octree (1 to 3 in the
       patch of one pair: never gamma; 1 to 3 in an elastic table: gamma, c), 0 for a leaf; the
       children of all split cells are exactly the cells after the roots. */
    {
        uint64_t children = 0;
        for (i = 0; i < cells; i++) {
            int32_t t = oblq__i32(p->tree + 4 * i);
            uint64_t s = p->split ? p->split[i] : (t >= 0 ? masks : 0), f;
            if (t >= 0) {
                if (s < 1 || s > masks) return OBLQ_E_CORRUPT;
                f = p->split ? (uint64_t)1 << ((s & 1) + ((s >> 1) & 1) + (s >> 2)) : fan;
                if ((uint64_t)t <= i || (uint64_t)t + f - 1 >= cells) return OBLQ_E_CORRUPT;
                children += f;
            } else if (s != 0 || (uint64_t)(-(int64_t)t - 1) >= leaves) {
                return OBLQ_E_CORRUPT;
            }
        }
        if (cells - roots != children) return OBLQ_E_CORRUPT;
    }
    nodes = leaves * (m + 1) * (m + 1) * (octree && !pair ? m + 1 : 1); /* < 2^51 */
    off = oblq__u64(r + 56);
    if (!oblq__span(off, nodes, 8, len)) return OBLQ_E_CORRUPT;
    p->p = (const double *)(const void *)(d + off);
    if (!oblq__finite_array(p->p, (size_t)nodes)) return OBLQ_E_CORRUPT;
    p->blocks_gamma = (size_t)bg;
    p->blocks_coord = (size_t)bc;
    p->m = (size_t)m;
    p->cells = (size_t)cells;
    p->leaves = (size_t)leaves;
    p->blocks_e_n = (size_t)be;
    if (oblq__u32(r + 44) > 1) return OBLQ_E_CORRUPT;
    p->warp = (int)oblq__u32(r + 44);
    if (p->warp) {
        p->w_start = oblq__f64(r + 64);
        p->w_gamma_0 = oblq__f64(r + 72);
        p->w_gamma_step = oblq__f64(r + 80);
        p->w_c_star = oblq__f64(r + 88);
        p->w_n = oblq__u32(r + 96);
        off = oblq__u64(r + 104);
        if (!p->partial || p->w_n < 4 || !oblq__span(off, p->w_n, 8, len)) return OBLQ_E_CORRUPT;
        p->knot = (const double *)(const void *)(d + off);
        if (!(isfinite(p->w_start) && isfinite(p->w_gamma_0) && p->w_gamma_step > 0.0 &&
              isfinite(p->w_gamma_step) && p->w_c_star > 0.0 && p->w_c_star < 1.0))
            return OBLQ_E_CORRUPT;
        for (i = 0; i < p->w_n; i++)
            if (!(p->knot[i] > 0.0 && p->knot[i] < 1.0)) return OBLQ_E_CORRUPT;
    }
    off = oblq__u64(r + 120);
    if (off != 0) {
        uint64_t depth = oblq__u32(r + 112), coff = oblq__u64(r + 128), rows, cols, e;
        double fine;
        if (depth > 30) return OBLQ_E_CORRUPT;
        rows = bg << depth;
        cols = bc << depth;
        if (rows > (uint64_t)1 << 40 || cols > ((uint64_t)1 << 40) / rows) return OBLQ_E_CORRUPT;
        if (!oblq__span(off, rows * cols, 4, len) || !oblq__span(coff, cells, 24, len))
            return OBLQ_E_CORRUPT;
        p->index = d + off;
        p->origin = (const double *)(const void *)(d + coff);
        p->rows = (size_t)rows;
        p->cols = (size_t)cols;
        fine = (double)((uint64_t)1 << depth);
        p->fine = fine;
        /* Every cell's depth and origin follow from its parent's (roots: 1, a, b). */
        for (i = 0; i < roots; i++) {
            const double *c = p->origin + 3 * i;
            if (c[0] != 1.0 || c[1] != (double)(i / bc) || c[2] != (double)(i % bc))
                return OBLQ_E_CORRUPT;
        }
        for (i = 0; i < cells; i++) {
            int32_t t = oblq__i32(p->tree + 4 * i);
            const double *c = p->origin + 3 * i;
            uint64_t q;
            if (!(c[0] >= 1.0 && c[0] <= 1073741824.0)) return OBLQ_E_CORRUPT;
            if (t < 0) continue;
            for (q = 0; q < 4; q++) {
                const double *k = p->origin + 3 * ((uint64_t)t + q);
                if (k[0] != 2.0 * c[0] || k[1] != 2.0 * c[1] + (double)(q / 2) ||
                    k[2] != 2.0 * c[2] + (double)(q % 2))
                    return OBLQ_E_CORRUPT;
            }
        }
        /* Every entry names a cell that contains it and is a leaf or at the index's depth:
           the leaf of the descent from the roots. */
        for (e = 0; e < rows * cols; e++) {
            uint64_t cell = oblq__u32(p->index + 4 * e);
            const double *c;
            double k;
            if (cell >= cells) return OBLQ_E_CORRUPT;
            c = p->origin + 3 * cell;
            if (c[0] > fine) return OBLQ_E_CORRUPT;
            k = fine / c[0];
            if (c[1] != floor((double)(e / cols) / k) || c[2] != floor((double)(e % cols) / k))
                return OBLQ_E_CORRUPT;
            if (oblq__i32(p->tree + 4 * cell) >= 0 && c[0] != fine) return OBLQ_E_CORRUPT;
        }
    }
    return OBLQ_OK;
}

/* Whether root-cell positions [a/2^d, (a+1)/2^d] of a cell (d < 21; deeper cells straddle no
   multiple of 2^-20) hold the region edge E (in units of 2^-20) strictly inside. */
OBLQ_FN int oblq__straddles(uint64_t a, unsigned d, uint64_t e) {
    uint64_t w;
    if (d > 20) return 0;
    w = (uint64_t)1 << (20 - d);
    return a * w < e && e < (a + 1) * w;
}

/* The knots block of a patch at offset `off` (layout versions 5, 7 and 8), checked as the
   other blocks are: inside the export, the counts and values in their ranges (c_star strictly
   increasing in (0, 1), grades 0 to 2 with no segment graded at both ends, the knot values
   strictly increasing in (0, 1) at every grid point), the region finite multiples of 2^-20
   with 0 <= from < to <= blocks per axis, the grid covering it (within 1e-12 of the value),
   and no leaf across an edge of the region along gamma or e_n (a walk down the cells that
   straddle one, on a path of at most 64 of them, whose splits would halve one axis 21 times).
   `t`: the table's e_n range and map. */
OBLQ_FN int oblq__knots(oblq_patch *p, const unsigned char *d, uint64_t len, uint64_t off,
                        const oblq_table *t) {
    const unsigned char *b;
    uint64_t n, ng, ne, i, j, l, edge[4];
    double g[4], v, blocks[2];
    struct { uint64_t cell, ag, ae; unsigned dg, de, q; } st[64];
    unsigned sp;
    if (off == 0 || !oblq__span(off, 1, 88, len)) return OBLQ_E_CORRUPT;
    b = d + off;
    n = oblq__u32(b);
    ng = oblq__u32(b + 4);
    ne = oblq__u32(b + 8);
    if (n < 1 || n > OBLQ_MAX_KNOTS || ng < 4 || ne < 4 || oblq__u32(b + 12) != 0)
        return OBLQ_E_CORRUPT;
    if (!oblq__span(off + 88, n, 8, len) || !oblq__span(off + 88 + 8 * n, ng, 8 * n * ne, len))
        return OBLQ_E_CORRUPT;
    p->k_n = (size_t)n;
    p->k_ng = (size_t)ng;
    p->k_ne = (size_t)ne;
    for (i = 0; i < 4; i++) g[i] = oblq__f64(b + 16 + 8 * i);
    p->k_gamma_0 = g[0];
    p->k_gamma_step = g[1];
    p->k_e_n_0 = g[2];
    p->k_e_n_step = g[3];
    if (!(isfinite(g[0]) && isfinite(g[1]) && g[1] > 0.0 && isfinite(g[2]) && isfinite(g[3]) &&
          g[3] > 0.0))
        return OBLQ_E_CORRUPT;
    blocks[0] = (double)p->blocks_gamma;
    blocks[1] = (double)p->blocks_e_n;
    for (i = 0; i < 4; i++) {
        v = oblq__f64(b + 48 + 8 * i);
        p->k_region[i] = v;
        /* finite, inside [0, blocks], a multiple of 2^-20 */
        if (!(v >= 0.0 && v <= blocks[i / 2]) || v * 1048576.0 != floor(v * 1048576.0))
            return OBLQ_E_CORRUPT;
        edge[i] = (uint64_t)(v * 1048576.0);
    }
    if (!(p->k_region[0] < p->k_region[1] && p->k_region[2] < p->k_region[3]))
        return OBLQ_E_CORRUPT;
    for (j = 0; j < OBLQ_MAX_KNOTS; j++) {
        p->k_grade[j] = b[80 + j];
        if (j >= n ? p->k_grade[j] != 0 : p->k_grade[j] > 2) return OBLQ_E_CORRUPT;
        if (j >= 1 && j < n && p->k_grade[j - 1] == 2 && p->k_grade[j] == 1) return OBLQ_E_CORRUPT;
    }
    p->k_c_star = (const double *)(const void *)(b + 88);
    p->k_knot = p->k_c_star + n;
    for (j = 0; j < n; j++)
        if (!(p->k_c_star[j] > (j ? p->k_c_star[j - 1] : 0.0) && p->k_c_star[j] < 1.0))
            return OBLQ_E_CORRUPT;
    for (i = 0; i < ng; i++)
        for (l = 0; l < ne; l++)
            for (j = 0; j < n; j++) {
                v = p->k_knot[(j * ng + i) * ne + l];
                if (!(v > (j ? p->k_knot[((j - 1) * ng + i) * ne + l] : 0.0) && v < 1.0))
                    return OBLQ_E_CORRUPT;
            }
    /* The grid covers the region: gamma_0 <= its lowest value, the last grid point >= its
       highest (within 1e-12 of the value), along gamma and along e_n (through the axis's
       map). */
    for (i = 0; i < 2; i++) {
        double from = i ? oblq__e_n_at(t, p->k_region[2], blocks[1])
                        : p->gamma_lo + (p->gamma_hi - p->gamma_lo) * p->k_region[0] / blocks[0];
        double to = i ? oblq__e_n_at(t, p->k_region[3], blocks[1])
                      : p->gamma_lo + (p->gamma_hi - p->gamma_lo) * p->k_region[1] / blocks[0];
        double first = g[2 * i], end = first + (double)((i ? ne : ng) - 1) * g[2 * i + 1];
        double slack = 1e-12 * (fabs(to) > 1.0 ? fabs(to) : 1.0);
        if (!(first <= from + slack && end >= to - slack)) return OBLQ_E_CORRUPT;
    }
    /* No leaf straddles an edge of the region: from each root that straddles one, depth first
       through the children that straddle one; every cell reached must be split. */
    for (i = 0; i < p->blocks_gamma * p->blocks_coord * p->blocks_e_n; i++) {
        sp = 0;
        st[0].cell = i;
        st[0].ag = i / (p->blocks_coord * p->blocks_e_n);
        st[0].ae = i % p->blocks_e_n;
        st[0].dg = st[0].de = st[0].q = 0;
        for (;;) {
            uint64_t cell = st[sp].cell;
            int32_t t = oblq__i32(p->tree + 4 * cell);
            unsigned mask, k, fan, q;
            int across = 0;
            for (k = 0; k < 2; k++)
                across |= oblq__straddles(st[sp].ag, st[sp].dg, edge[k]) |
                          oblq__straddles(st[sp].ae, st[sp].de, edge[2 + k]);
            if (across && t < 0) return OBLQ_E_CORRUPT; /* a leaf across an edge */
            mask = t < 0 ? 0u : (p->split ? p->split[cell] : 7u);
            fan = 1u << ((mask & 1u) + ((mask >> 1) & 1u) + (mask >> 2));
            if (!across || t < 0 || st[sp].q == fan) {
                if (sp == 0) break;
                sp--;
                continue;
            }
            if (sp + 1 >= 64) return OBLQ_E_CORRUPT; /* a path deeper than the walk holds */
            /* Child q: its bits over the halved axes in the order gamma, c, e_n. */
            q = st[sp].q++;
            st[sp + 1].cell = (uint64_t)t + q;
            st[sp + 1].ag = st[sp].ag;
            st[sp + 1].dg = st[sp].dg;
            st[sp + 1].ae = st[sp].ae;
            st[sp + 1].de = st[sp].de;
            st[sp + 1].q = 0;
            if (mask & 1u) {
                st[sp + 1].ae = 2 * st[sp].ae + (q & 1u);
                st[sp + 1].de++;
            }
            if (mask & 4u) {
                unsigned shift = (mask & 1u) + ((mask >> 1) & 1u);
                st[sp + 1].ag = 2 * st[sp].ag + ((q >> shift) & 1u);
                st[sp + 1].dg++;
            }
            sp++;
        }
    }
    return OBLQ_OK;
}

OBLQ_FN int oblq__piece(oblq_piece *c, const unsigned char *d, uint64_t len, const unsigned char *r) {
    uint64_t off;
    memset(c, 0, sizeof *c);
    if (oblq__u32(r) == 0) return OBLQ_OK;
    if (oblq__u32(r) != 1 || oblq__u32(r + 16) > 1) return OBLQ_E_CORRUPT;
    c->present = 1;
    c->n = oblq__u32(r + 4);
    off = oblq__u64(r + 8);
    if (c->n < 1 || !oblq__span(off, (uint64_t)c->n, 32, len)) return OBLQ_E_CORRUPT;
    c->coef = (const double *)(const void *)(d + off);
    if (!oblq__finite_array(c->coef, 4 * c->n)) return OBLQ_E_CORRUPT;
    c->warp = (int)oblq__u32(r + 16);
    if (c->warp) {
        c->k = oblq__f64(r + 24);
        c->c_star = oblq__f64(r + 32);
        if (!(c->k > 0.0 && c->k < 1.0 && c->c_star > 0.0 && c->c_star < 1.0))
            return OBLQ_E_CORRUPT;
    }
    return OBLQ_OK;
}

OBLQ_FN double oblq_linear_limit(double gamma);
OBLQ_FN double oblq_alpha_c2(double gamma);
OBLQ_FN double oblq__stick_scale(double gamma);

/* Whether a stored logarithm is the one computed here: to the bit on the host; within 2^-51
   relative in CUDA device code, whose log is within 1 ulp but not always rounded as the host
   libm's that wrote the export. */
OBLQ_FN int oblq__same_log(double stored, double computed) {
#ifdef __CUDA_ARCH__
    return fabs(stored - computed) <= 4.440892098500626e-16 * fabs(computed);
#else
    return stored == computed;
#endif
}

OBLQ_FN int oblq__curve_at(const oblq_table *t, size_t i, oblq_curve *c) {
    const unsigned char *r = t->data + t->curves + 168 * i;
    double v[10];
    size_t k;
    int rc;
    for (k = 0; k < 10; k++) v[k] = oblq__f64(r + 8 * k);
    c->gamma = v[0];
    c->alpha_lin = v[1];
    c->alpha_c2 = v[2];
    c->g2 = v[3];
    c->ratio = v[4];
    c->ln_ratio = v[5];
    c->stick_c2 = v[6];
    c->rho_c2 = v[7];
    c->s_max = v[8];
    c->alpha_max = v[9];
    if (oblq__u32(r + 80) > 1) return OBLQ_E_CORRUPT;
    c->high = (int)oblq__u32(r + 80);
    for (k = 0; k < 8; k++) /* ln(2 gamma^2 - 1) is NaN below gamma = 1/sqrt(2): unused there */
        if (!isfinite(v[k]) && k != 5) return OBLQ_E_CORRUPT;
    if (!(c->gamma >= t->gamma_min && c->gamma <= t->gamma_max) || c->alpha_max != t->alpha_max)
        return OBLQ_E_CORRUPT;
    if (c->high != (c->gamma > 1.0)) return OBLQ_E_CORRUPT;
    /* Everything but the cubics follows from gamma and alpha_max: it must be what the rule
       computes (so that a damaged but resealed record cannot move the full-slip line). */
    {
        double g2 = 2.0 * c->gamma * c->gamma, sc2 = c->gamma * c->gamma * (2.0 / 7.0);
        double rc2 = oblq__stick_scale(c->gamma) * sc2, dm = c->alpha_max - sc2;
        if (c->alpha_lin != oblq_linear_limit(c->gamma) || c->alpha_c2 != oblq_alpha_c2(c->gamma) ||
            c->g2 != g2 || c->ratio != g2 - 1.0 || c->stick_c2 != sc2 || c->rho_c2 != rc2)
            return OBLQ_E_CORRUPT;
        if (c->high && !oblq__same_log(c->ln_ratio, log(g2 - 1.0))) return OBLQ_E_CORRUPT;
        if (isinf(c->alpha_max) ? !isnan(c->s_max) : c->s_max != dm / (dm + rc2))
            return OBLQ_E_CORRUPT;
    }
    rc = oblq__piece(&c->partial, t->data, t->size, r + 88);
    if (rc != OBLQ_OK) return rc;
    return oblq__piece(&c->stick, t->data, t->size, r + 128);
}

/* Check an export of `size` bytes at `data` (8-byte aligned: a malloc'ed or mmap'ed buffer,
   or the array of a generated C source) and make `t` refer to it. Reads every byte once (the
   checksum); no allocation. */
OBLQ_FN int oblq_open(oblq_table *t, const void *data, size_t size) {
    const unsigned char *d = (const unsigned char *)data;
    uint64_t len, sum, off, i, header;
    uint32_t version;
    size_t k;
    int rc;
    oblq_table out;
    oblq_curve c;
    if (!t || !data) return OBLQ_E_NULL;
    if (size < 8) return OBLQ_E_TRUNCATED;
    for (k = 0; k < 8; k++) /* a byte loop, not memcmp: device code has no memcmp */
        if (d[k] != (unsigned char)"OBLQEVAL"[k]) return OBLQ_E_FORMAT;
    if (size < 96) return OBLQ_E_TRUNCATED;
    version = oblq__u32(d + 8);
    if (version < 1 || version > OBLQ_EXPORT_VERSION) return OBLQ_E_VERSION;
    /* Versions 2 to 5, 7 and 8 add the e_n range; version 6 is version 1 with split masks. */
    header = version == 1 || version == 6 ? 96 : 112;
    if (oblq__u32(d + 12) != header) return OBLQ_E_CORRUPT;
    if (((uintptr_t)data) % 8 != 0) return OBLQ_E_CORRUPT;
    len = oblq__u64(d + 16);
    if (len > (uint64_t)size) return OBLQ_E_TRUNCATED;
    if (len < header || len % 8 != 0) return OBLQ_E_CORRUPT;
    sum = 0xcbf29ce484222325ULL;
    for (i = 32; i < len; i++) sum = (sum ^ d[i]) * 0x100000001b3ULL;
    if (sum != oblq__u64(d + 24)) return OBLQ_E_CHECKSUM;
    memset(&out, 0, sizeof out);
    out.data = d;
    out.size = len;
    out.gamma_min = oblq__f64(d + 32);
    out.gamma_max = oblq__f64(d + 40);
    out.alpha_max = oblq__f64(d + 48);
    out.error_bound = oblq__f64(d + 56);
    /* Every header value as the data implies it (a value changed and resealed must not reach
       a query: alpha_max at alpha_c2 made the stick coordinate 0/0): the domain
       0 < gamma_min < gamma_max <= 1e100 (tables are built to gamma <= 64; below 1e100 no
       product of the rule overflows; gamma_min == gamma_max in version 3 only, the table of
       one pair), the bound finite and >= 0, alpha_max inf or above alpha_c2(gamma_max) in both
       of the rule's forms (then S(alpha_max) > 0 at every gamma of the domain), and below the
       patches and curves. */
    out.pair = version == 3;
    /* The flag of a table without a full-slip line: 1 in version 4, 0 (reserved) before, 0 or
       1 in versions 5, 7 and 8 (the knots, or the e_n map, of a table of either kind). */
    out.no_line = version == 4 ||
                  ((version == 5 || version == 7 || version == 8) && oblq__u32(d + 68) == 1);
    if (oblq__u32(d + 68) != (uint32_t)out.no_line) return OBLQ_E_CORRUPT;
    /* The map of the e_n axis: 1, over (1 - e_n)^(1/4), in version 8 (the only map it knows);
       0 (reserved) in every other version, an elastic table's included. */
    out.e_n_map = version == 8;
    if (oblq__u32(d + 84) != (uint32_t)out.e_n_map) return OBLQ_E_CORRUPT;
    /* A table without the line starts at gamma = 1 or above (no stick_low). */
    if (out.no_line && !(out.gamma_min >= 1.0)) return OBLQ_E_CORRUPT;
    if (!(isfinite(out.gamma_min) && out.gamma_min > 0.0 &&
          (out.pair ? out.gamma_min == out.gamma_max : out.gamma_min < out.gamma_max) &&
          out.gamma_max <= 1e100))
        return OBLQ_E_CORRUPT;
    if (!(out.error_bound >= 0.0 && out.error_bound < INFINITY)) return OBLQ_E_CORRUPT;
    if (!(out.alpha_max == INFINITY ||
          (out.alpha_max > oblq_alpha_c2(out.gamma_max) &&
           out.alpha_max > out.gamma_max * out.gamma_max * (2.0 / 7.0))))
        return OBLQ_E_CORRUPT;
    if (oblq__u32(d + 64) != 4) return OBLQ_E_CORRUPT; /* the cubic stencil */
    out.e_n_min = 1.0;
    out.e_n_max = 1.0;
    out.e_n_lo = 0.0;
    out.e_n_width = 1.0;
    if ((version >= 2 && version <= 5) || version == 7 || version == 8) {
        /* A table with an e_n axis (of one pair in version 3): its range, its surface, no
           curves. */
        out.has_e_n = 1;
        out.e_n_min = oblq__f64(d + 96);
        out.e_n_max = oblq__f64(d + 104);
        if (!(out.e_n_min > 0.0 && out.e_n_max > out.e_n_min && out.e_n_max <= 1.0))
            return OBLQ_E_CORRUPT;
        if (out.e_n_map) {
            /* The mapped ends, once: x_e = (m(e_n) - e_n_lo)/e_n_width. */
            out.e_n_lo = oblq__quarter_root(out.e_n_min);
            out.e_n_width = oblq__quarter_root(out.e_n_max) - out.e_n_lo;
            if (!(out.e_n_width > 0.0)) return OBLQ_E_CORRUPT;
        }
        if (oblq__u64(d + 72) == 0 || oblq__u32(d + 80) != 0 || oblq__u64(d + 88) != 0)
            return OBLQ_E_CORRUPT;
    }
    off = oblq__u64(d + 72);
    if (off != 0) {
        if (!oblq__span(off, 3, 160, len) || off < header) return OBLQ_E_CORRUPT;
        out.has_surface = 1;
        for (k = 0; k < 3; k++) {
            const unsigned char *r = d + off + 160 * k;
            rc = oblq__patch(&out.patch[k], d, len, r, out.pair ? 1 : (out.has_e_n ? 3 : 2),
                             version == 6);
            if (rc != OBLQ_OK) return rc;
            /* The knots blocks: in the record of partial_high of version 5 (and there), of
               stick_high of version 7 (and there), of partial_high of version 7 where named,
               of partial_high and stick_high of version 8 where named. */
            if ((version == 5 && k == 1) || (version == 7 && k == 2) ||
                ((version == 7 || version == 8) && k == 1 && oblq__u64(r + 152) != 0) ||
                (version == 8 && k == 2 && oblq__u64(r + 152) != 0)) {
                if (!out.patch[k].present) return OBLQ_E_CORRUPT;
                rc = oblq__knots(&out.patch[k], d, len, oblq__u64(r + 152), &out);
                if (rc != OBLQ_OK) return rc;
            } else if (oblq__u64(r + 152) != 0) {
                return OBLQ_E_CORRUPT;
            }
        }
        if (out.patch[1].present && !out.patch[1].partial) return OBLQ_E_CORRUPT;
        /* Without the line alpha_c1 is the root-cell edge c = 1/2: blocks_coord is even. */
        if (out.no_line && out.patch[1].present && out.patch[1].blocks_coord % 2 != 0)
            return OBLQ_E_CORRUPT;
        if ((out.patch[0].present && out.patch[0].partial) ||
            (out.patch[2].present && out.patch[2].partial))
            return OBLQ_E_CORRUPT;
        /* The patches the domain needs, over the gamma ranges they are built on: stick_low
           over [gamma_min, min(gamma_max, 1)] when gamma_min < 1, the other two over
           [max(gamma_min, 1), gamma_max] when gamma_max > 1; no other. (The table of one pair:
           its patches at its gamma, gamma_lo == gamma_hi == gamma_min.) */
        for (k = 0; k < 3; k++) {
            const oblq_patch *p = &out.patch[k];
            int low = k == 0;
            int needed = low ? out.gamma_min < 1.0 : out.gamma_max > 1.0;
            double lo = low || out.gamma_min > 1.0 ? out.gamma_min : 1.0;
            double hi = !low || out.gamma_max < 1.0 ? out.gamma_max : 1.0;
            if (p->present != needed || (needed && !(p->gamma_lo == lo && p->gamma_hi == hi)))
                return OBLQ_E_CORRUPT;
        }
    }
    out.n_curves = oblq__u32(d + 80);
    off = oblq__u64(d + 88);
    if (out.n_curves > 0) {
        if (!oblq__span(off, out.n_curves, 168, len) || off < header) return OBLQ_E_CORRUPT;
        out.curves = off;
        for (k = 0; k < out.n_curves; k++) {
            rc = oblq__curve_at(&out, k, &c);
            if (rc != OBLQ_OK) return rc;
        }
    } else if (off != 0) {
        return OBLQ_E_CORRUPT;
    }
    if (!out.has_surface && out.n_curves == 0) return OBLQ_E_CORRUPT;
    *t = out;
    return OBLQ_OK;
}

/* The pointer at `p` into the copy at `from`, moved to the same offset in the copy at `to`
   (NULL stays NULL). Integer arithmetic: `to` may be an address the caller cannot read. */
OBLQ_FN const void *oblq__moved(const void *p, const void *from, const void *to) {
    if (!p) return NULL;
    return (const void *)((uintptr_t)to + ((uintptr_t)p - (uintptr_t)from));
}

/* Make `t` (checked by oblq_open) refer to another copy of the same bytes at `data`: a GPU
   code opens the export on the host, copies its bytes to the device (cudaMalloc, cudaMemcpy)
   and rebases a copy of the table to that address, then passes the table to kernels by value.
   Only the table's pointers change; `data` is not read (it may be device memory), so it must
   hold the bytes oblq_open checked, unchanged, 8-byte aligned (cudaMalloc's are). */
OBLQ_FN int oblq_rebase(oblq_table *t, const void *data) {
    oblq_table out;
    size_t k;
    if (!t || !data || !t->data) return OBLQ_E_NULL;
    if (((uintptr_t)data) % 8 != 0) return OBLQ_E_CORRUPT;
    out = *t;
    for (k = 0; k < 3; k++) {
        oblq_patch *p = &out.patch[k];
        p->tree = (const unsigned char *)oblq__moved(p->tree, t->data, data);
        p->p = (const double *)oblq__moved(p->p, t->data, data);
        p->knot = (const double *)oblq__moved(p->knot, t->data, data);
        p->index = (const unsigned char *)oblq__moved(p->index, t->data, data);
        p->origin = (const double *)oblq__moved(p->origin, t->data, data);
        p->split = (const unsigned char *)oblq__moved(p->split, t->data, data);
        p->k_c_star = (const double *)oblq__moved(p->k_c_star, t->data, data);
        p->k_knot = (const double *)oblq__moved(p->k_knot, t->data, data);
    }
    out.data = (const unsigned char *)data;
    *t = out;
    return OBLQ_OK;
}

/* What a status code means: the argument and the allowed range. */
OBLQ_FN const char *oblq_error_message(int code) {
    switch (code) {
    case OBLQ_OK: return "ok";
    case OBLQ_E_FILE: return "cannot open or read the export file (errno says why: missing, unreadable, changed while read)";
    case OBLQ_E_NOT_FILE: return "the export path is not a regular file (a directory, FIFO, device or socket)";
    case OBLQ_E_NO_MEMORY: return "out of memory reading the export file";
    case OBLQ_E_NULL: return "a pointer argument is NULL";
    case OBLQ_E_TRUNCATED: return "the export is truncated: shorter than its header says";
    case OBLQ_E_FORMAT: return "not an export of oblique (`sweep export`): wrong magic bytes";
    case OBLQ_E_VERSION: return "an export of another layout version: re-export with the sweep matching this header";
    case OBLQ_E_CHECKSUM: return "the export is damaged: its checksum does not match its contents";
    case OBLQ_E_CORRUPT: return "the export is inconsistent (offsets, sizes or values out of range) or not 8-byte aligned in memory";
    case OBLQ_E_GAMMA: return "invalid gamma: must be a finite number > 0";
    case OBLQ_E_ALPHA: return "invalid alpha: must be >= 0 (or inf for no slip)";
    case OBLQ_E_GAMMA_DOMAIN: return "gamma outside the table's domain [gamma_min, gamma_max] (and alpha above the full-slip line; a table of one pair: its gamma within 1e-9 relative); or opt into clamping";
    case OBLQ_E_ALPHA_DOMAIN: return "alpha above the table's alpha_max; or opt into clamping";
    case OBLQ_E_NO_SURFACE: return "this export holds only curves: query a curve, or export the whole table";
    case OBLQ_E_NO_CURVE: return "no curve of that gamma (or index) in the export: export it with sweep export --gamma";
    case OBLQ_E_MASS: return "invalid mass: must be a finite number > 0 (kg)";
    case OBLQ_E_RADIUS: return "invalid radius: must be a finite number > 0 (m)";
    case OBLQ_E_KAPPA: return "invalid kappa (I = kappa m R^2): must be a finite number > 0";
    case OBLQ_E_FRICTION: return "invalid friction: must be >= 0 (or inf for no slip)";
    case OBLQ_E_MODULUS: return "invalid youngs_modulus: must be > 0 Pa (inf for a rigid body), finite for at least one body";
    case OBLQ_E_POISSON: return "invalid poisson_ratio: must be in (-1, 0.5]";
    case OBLQ_E_MOTION: return "invalid velocity, spin or normal: components must be finite";
    case OBLQ_E_NORMAL: return "invalid normal: must be a vector of non-zero, finite length";
    case OBLQ_E_APPROACH: return "invalid v_z: the approach speed v_z0 along the normal must be finite and > 0 (the bodies must move towards each other)";
    case OBLQ_E_WALL_MOTION: return "invalid other motion: must be zero for a fixed wall";
    case OBLQ_E_P_RANGE: return "invalid P: must be in [-1, 1]";
    case OBLQ_E_E_N: return "invalid e_n: must be in the table's e_n range [e_n_min, e_n_max] (never clamped); an elastic table answers e_n = 1 only";
    case OBLQ_E_AXES: return "invalid point: must have one value per axis of the table (oblq_axis_count, oblq_axis_name): gamma, alpha, and e_n for a table with that axis";
    default: return "unknown status code";
    }
}

/* ---------------------------------------------------------------------------------------- */
/* The rule (docs/table-format.md, steps 1-10)                                               */

/* alpha_c1 = 2 gamma^2/(7(2 gamma^2 - 1)): the end of full slip for gamma > 1. Where the
   denominator overflows (gamma > 3.58e153), the same value as 1/(7(1 - 1/(2 gamma^2))) (1/7, the
   limit); elsewhere exactly these operations, the Rust library's. */
OBLQ_FN double oblq_alpha_c1(double gamma) {
    double g2 = gamma * gamma;
    double d = 7.0 * (2.0 * g2 - 1.0);
    if (d == INFINITY) return 1.0 / (7.0 * (1.0 - 1.0 / (2.0 * g2)));
    return 2.0 * g2 / d;
}

/* alpha_c2 = 2 gamma^2/7: the start of stick. */
OBLQ_FN double oblq_alpha_c2(double gamma) { return 2.0 * gamma * gamma / 7.0; }

/* End of the exact full-slip line P = 1 - 7 alpha: alpha_c1 for gamma > 1, else alpha_c2. */
OBLQ_FN double oblq_linear_limit(double gamma) {
    return gamma > 1.0 ? oblq_alpha_c1(gamma) : oblq_alpha_c2(gamma);
}

OBLQ_FN double oblq__clamp(double x, double lo, double hi) {
    return x < lo ? lo : (x > hi ? hi : x);
}

/* min(floor(u), max) for u >= 0; 0 for u < 0 or NaN (no undefined conversion). */
OBLQ_FN size_t oblq__floor_index(double u, size_t max) {
    if (!(u >= 0.0)) return 0;
    if (u >= (double)max) return max;
    return (size_t)u;
}

OBLQ_FN void oblq__cubic_weights(double a, double w[4]) {
    double b = a - 1.0, c = a - 2.0, d = a - 3.0;
    double ab = a * b, cd = c * d;
    w[0] = -(b * cd) * (1.0 / 6.0);
    w[1] = a * cd * 0.5;
    w[2] = -(ab * d) * 0.5;
    w[3] = ab * c * (1.0 / 6.0);
}

/* The 4-point stencil at grid position u on n >= 4 nodes: start index and weights. */
OBLQ_FN size_t oblq__stencil4(double u, size_t n, double w[4]) {
    size_t cell = oblq__floor_index(u, n - 2);
    size_t start = cell >= 1 ? cell - 1 : 0;
    if (start > n - 4) start = n - 4;
    oblq__cubic_weights(u - (double)start, w);
    return start;
}

OBLQ_FN size_t oblq__locate(double x, size_t blocks, double *f) {
    double u = oblq__clamp(x * (double)blocks, 0.0, (double)blocks);
    size_t a = oblq__floor_index(u, blocks - 1);
    *f = u - (double)a;
    return a;
}

OBLQ_FN double oblq__stick_scale(double gamma) {
    return gamma < 1.0 ? 2.0 * (1.0 - gamma * gamma) : 1.0;
}

OBLQ_FN double oblq__max0(double x) { return x > 0.0 ? x : 0.0; }

OBLQ_FN double oblq__partial_coord(double gamma, double alpha) {
    double g2 = 2.0 * gamma * gamma;
    double ratio = g2 - 1.0;
    double l = log(7.0 * alpha * ratio / g2) / log(ratio);
    return 1.0 - sqrt(oblq__max0(1.0 - l));
}

OBLQ_FN double oblq__stick_coord(double gamma, double alpha, double alpha_max) {
    double c2, rho, d, s, dm;
    if (isinf(alpha)) return 1.0;
    c2 = gamma * gamma * (2.0 / 7.0);
    rho = oblq__stick_scale(gamma);
    d = alpha - c2;
    s = d / (d + rho * c2);
    if (isinf(alpha_max)) return s;
    dm = alpha_max - c2;
    return s / (dm / (dm + rho * c2));
}

OBLQ_FN double oblq__warp_apply(double k, double c_star, double c) {
    if (c <= k) return c_star * (1.0 - sqrt(oblq__max0(1.0 - c / k)));
    return c_star + (1.0 - c_star) * (c - k) / (1.0 - k);
}

OBLQ_FN double oblq__knot_at(const oblq_patch *p, double gamma) {
    double w[4];
    double u = oblq__clamp((gamma - p->w_gamma_0) / p->w_gamma_step, 0.0, (double)(p->w_n - 1));
    size_t s = oblq__stencil4(u, p->w_n, w);
    const double *k = p->knot + s;
    return w[0] * k[0] + w[1] * k[1] + w[2] * k[2] + w[3] * k[3];
}

OBLQ_FN size_t oblq__descend(const oblq_patch *p, size_t cell, double *f, unsigned n);

/* Steps 6-9 on a patch of an elastic table at (gamma, c): the quadtree's leaf (from the fine
   index, or from the roots; through the split masks of layout version 6), then the tensor
   product of the two cubic stencils, summed c innermost. */
OBLQ_FN double oblq__tensor(const oblq_patch *p, double gamma, double c) {
    double fg, fc, wg[4], wc[4], r[4];
    double xg = (gamma - p->gamma_lo) / (p->gamma_hi - p->gamma_lo);
    size_t cell, leaf, n1, sg, sc, i;
    const double *v;
    if (p->split) {
        /* Cells that halve only the axes of their masks (bit 2: gamma, 1: c): the generic
           descent from the root cell, the doublings below on the halved axes only. */
        double f[2];
        size_t a = oblq__locate(xg, p->blocks_gamma, &f[0]);
        size_t b = oblq__locate(c, p->blocks_coord, &f[1]);
        leaf = oblq__descend(p, a * p->blocks_coord + b, f, 2);
        fg = f[0];
        fc = f[1];
    } else {
        if (p->index) {
            /* The fine index: the entry's cell, the position inside it (v 2^d - origin, the
               rule's repeated f <- 2f - q bit for bit), then the descent only below the
               index's depth. */
            double bg = (double)p->blocks_gamma, bc = (double)p->blocks_coord;
            double vg = oblq__clamp(xg * bg, 0.0, bg), vc = oblq__clamp(c * bc, 0.0, bc);
            size_t ig = oblq__floor_index(vg * p->fine, p->rows - 1);
            size_t ic = oblq__floor_index(vc * p->fine, p->cols - 1);
            const double *co;
            cell = oblq__u32(p->index + 4 * (ig * p->cols + ic));
            co = p->origin + 3 * cell;
            fg = vg * co[0] - co[1];
            fc = vc * co[0] - co[2];
        } else {
            size_t a = oblq__locate(xg, p->blocks_gamma, &fg);
            size_t b = oblq__locate(c, p->blocks_coord, &fc);
            cell = a * p->blocks_coord + b;
        }
        for (;;) {
            int32_t t = oblq__i32(p->tree + 4 * cell);
            size_t qg, qc;
            if (t < 0) {
                leaf = (size_t)(-(int64_t)t - 1);
                break;
            }
            fg *= 2.0;
            fc *= 2.0;
            qg = fg >= 1.0;
            qc = fc >= 1.0;
            fg -= (double)qg;
            fc -= (double)qc;
            cell = (size_t)t + 2 * qg + qc;
        }
    }
    n1 = p->m + 1;
    sg = oblq__stencil4(fg * (double)p->m, n1, wg);
    sc = oblq__stencil4(fc * (double)p->m, n1, wc);
    v = p->p + leaf * n1 * n1 + sg * n1 + sc;
    for (i = 0; i < 4; i++) {
        const double *row = v + i * n1;
        r[i] = row[0] * wc[0] + row[1] * wc[1] + row[2] * wc[2] + row[3] * wc[3];
    }
    return wg[0] * r[0] + wg[1] * r[1] + wg[2] * r[2] + wg[3] * r[3];
}

/* The rule in a region above the line (patch index 0, 1, 2), inside the domain. */
OBLQ_FN double oblq__eval_in(const oblq_table *t, int region, double gamma, double alpha) {
    const oblq_patch *p = &t->patch[region];
    double c, bg;
    if (!p->present) return -1.0; /* a domain that touches gamma = 1 from one side only */
    c = p->partial ? oblq__partial_coord(gamma, alpha)
                   : oblq__stick_coord(gamma, alpha, t->alpha_max);
    c = oblq__clamp(c, 0.0, 1.0);
    if (p->warp) {
        double xg = (gamma - p->gamma_lo) / (p->gamma_hi - p->gamma_lo);
        bg = (double)p->blocks_gamma;
        if (oblq__clamp(xg * bg, 0.0, bg) >= p->w_start)
            c = oblq__warp_apply(oblq__knot_at(p, gamma), p->w_c_star, c);
    }
    return oblq__clamp(oblq__tensor(p, gamma, c), -1.0, 1.0);
}

OBLQ_FN int oblq__region(double gamma, double alpha) {
    if (alpha <= oblq_linear_limit(gamma)) return -1;
    if (gamma <= 1.0) return 0;
    if (alpha < oblq_alpha_c2(gamma)) return 1;
    return 2;
}

/* oblq_p of an elastic table (or a curves-only export). */
OBLQ_FN int oblq__p_elastic(const oblq_table *t, double gamma, double alpha, int clamp,
                            double *p) {
    int region, inside;
    if (!t || !p) return OBLQ_E_NULL;
    if (!(gamma > 0.0 && gamma < INFINITY)) return OBLQ_E_GAMMA;
    if (!(alpha >= 0.0)) return OBLQ_E_ALPHA; /* NaN or negative */
    region = oblq__region(gamma, alpha);
    if (region < 0) {
        *p = 1.0 - 7.0 * alpha;
        return OBLQ_OK;
    }
    if (!t->has_surface) return OBLQ_E_NO_SURFACE;
    inside = gamma >= t->gamma_min && gamma <= t->gamma_max;
    if (!(inside && alpha <= t->alpha_max)) {
        if (!clamp) return inside ? OBLQ_E_ALPHA_DOMAIN : OBLQ_E_GAMMA_DOMAIN;
        gamma = oblq__clamp(gamma, t->gamma_min, t->gamma_max);
        alpha = alpha < t->alpha_max ? alpha : t->alpha_max;
        region = oblq__region(gamma, alpha);
        if (region < 0) {
            *p = 1.0 - 7.0 * alpha;
            return OBLQ_OK;
        }
    }
    *p = oblq__eval_in(t, region, gamma, alpha);
    return OBLQ_OK;
}

/* alpha_c1(gamma, e_n) = 2 gamma^2/(7(gamma^2(1 + e_n) - e_n)): the end of full slip of an
   impact with normal restitution e_n for gamma > 1 (alpha_c2, where stick starts, does not move
   with e_n). */
OBLQ_FN double oblq__alpha_c1_e(double gamma, double e_n) {
    double g2 = gamma * gamma;
    double d = 7.0 * (g2 * (1.0 + e_n) - e_n);
    if (d == INFINITY) return 2.0 / (7.0 * ((1.0 + e_n) - e_n / g2)); /* overflow: the same */
    return 2.0 * g2 / d;
}

OBLQ_FN int oblq__region_e(double gamma, double alpha, double e_n) {
    if (alpha <= (gamma > 1.0 ? oblq__alpha_c1_e(gamma, e_n) : oblq_alpha_c2(gamma))) return -1;
    if (gamma <= 1.0) return 0;
    if (alpha < oblq_alpha_c2(gamma)) return 1;
    return 2;
}

/* The region of a table without a full-slip line (layout version 4): 0 (stick_low) for
   gamma < 1, outside such a table's domain; 1 (partial_high) for alpha < alpha_c2, else 2;
   never the line. */
OBLQ_FN int oblq__region_no_line(double gamma, double alpha) {
    if (gamma < 1.0) return 0;
    if (alpha < oblq_alpha_c2(gamma)) return 1;
    return 2;
}

/* The region of a query at e_n in table t (-1: the full-slip line). */
OBLQ_FN int oblq__region_t(const oblq_table *t, double gamma, double alpha, double e_n) {
    return t->no_line ? oblq__region_no_line(gamma, alpha) : oblq__region_e(gamma, alpha, e_n);
}

/* The full-slip line at e_n: P = 1 - (7/2)(1 + e_n) alpha. */
OBLQ_FN double oblq__line_e(double alpha, double e_n) { return 1.0 - 3.5 * (1.0 + e_n) * alpha; }

/* The partial-slip coordinate of a table with an e_n axis: c = 1 - sqrt(1 - sqrt(l)),
   l = ln(alpha/alpha_c1)/ln(alpha_c2/alpha_c1) clamped to [0, 1], with
   alpha/alpha_c1 = 7 alpha h/(2 gamma^2) and alpha_c2/alpha_c1 = h = gamma^2(1 + e_n) - e_n. */
OBLQ_FN double oblq__partial_coord_e(double gamma, double alpha, double e_n) {
    double g2 = gamma * gamma;
    double ratio = g2 * (1.0 + e_n) - e_n;
    double l = log(7.0 * alpha * ratio / (2.0 * g2)) / log(ratio);
    return 1.0 - sqrt(1.0 - sqrt(oblq__clamp(l, 0.0, 1.0)));
}

/* The partial-slip coordinate of a table without a full-slip line (Thornton's law, layout
   version 4), over 0 <= alpha <= alpha_c2: with q = alpha/alpha_c1 = 7 alpha h/(2 gamma^2),
   c = q/2 for q <= 1 (no logarithm: at gamma = 1 every alpha < alpha_c2 is there), else
   c = 1/2 + (1 - sqrt(1 - sqrt(l)))/2, l = ln(q)/ln(h) clamped to [0, 1]. */
OBLQ_FN double oblq__partial_coord_slip(double gamma, double alpha, double e_n) {
    double g2 = gamma * gamma;
    double ratio = g2 * (1.0 + e_n) - e_n;
    double q = 7.0 * alpha * ratio / (2.0 * g2);
    double l;
    if (q <= 1.0) return 0.5 * q;
    l = log(q) / log(ratio);
    return 0.5 + 0.5 * (1.0 - sqrt(1.0 - sqrt(oblq__clamp(l, 0.0, 1.0))));
}

/* Step 7 in a tree whose cells halve the axes of their mask: the leaf that holds the positions
   f[0..n) (changed to the positions inside it) from root cell `cell`. A split cell's mask has
   bit n - 1 - k for each axis k it halves (every axis without a `split` dataset); each of them
   is doubled, q_k = 1 where it reaches 1 (then 1 subtracted), and the child is
   tree[cell] + q, q the q_k of the halved axes read as binary digits in axis order. */
OBLQ_FN size_t oblq__descend(const oblq_patch *p, size_t cell, double *f, unsigned n) {
    unsigned every = (1u << n) - 1u, k;
    for (;;) {
        int32_t t = oblq__i32(p->tree + 4 * cell);
        unsigned mask;
        size_t q = 0, b;
        if (t < 0) return (size_t)(-(int64_t)t - 1);
        mask = p->split ? p->split[cell] : every;
        for (k = 0; k < n; k++) {
            if ((mask >> (n - 1u - k)) & 1u) {
                f[k] *= 2.0;
                b = f[k] >= 1.0;
                f[k] -= (double)b;
                q = 2 * q + b;
            }
        }
        cell = (size_t)t + q;
    }
}

/* Steps 6-9 on a patch with an e_n axis at (gamma, c, x_e): the octree's leaf, then the tensor
   product of the three cubic stencils, summed e_n innermost, gamma outermost. */
OBLQ_FN double oblq__tensor3(const oblq_patch *p, double gamma, double c, double xe) {
    double f[3], wg[4], wc[4], we[4], r[4], plane[4];
    double xg = (gamma - p->gamma_lo) / (p->gamma_hi - p->gamma_lo);
    size_t a = oblq__locate(xg, p->blocks_gamma, &f[0]);
    size_t b = oblq__locate(c, p->blocks_coord, &f[1]);
    size_t e = oblq__locate(xe, p->blocks_e_n, &f[2]);
    size_t leaf, n1, sg, sc, se, i, j;
    const double *v;
    leaf = oblq__descend(p, (a * p->blocks_coord + b) * p->blocks_e_n + e, f, 3);
    n1 = p->m + 1;
    sg = oblq__stencil4(f[0] * (double)p->m, n1, wg);
    sc = oblq__stencil4(f[1] * (double)p->m, n1, wc);
    se = oblq__stencil4(f[2] * (double)p->m, n1, we);
    v = p->p + leaf * n1 * n1 * n1;
    for (i = 0; i < 4; i++) {
        for (j = 0; j < 4; j++) {
            const double *row = v + ((sg + i) * n1 + sc + j) * n1 + se;
            r[j] = row[0] * we[0] + row[1] * we[1] + row[2] * we[2] + row[3] * we[3];
        }
        plane[i] = wc[0] * r[0] + wc[1] * r[1] + wc[2] * r[2] + wc[3] * r[3];
    }
    return wg[0] * plane[0] + wg[1] * plane[1] + wg[2] * plane[2] + wg[3] * plane[3];
}

/* Steps 6-9 on the patch of one pair at (c, x_e): the quadtree's leaf (masks: bit 2 c, bit 1
   e_n), then the tensor product of the two cubic stencils, summed e_n innermost. */
OBLQ_FN double oblq__tensor_pair(const oblq_patch *p, double c, double xe) {
    double f[2], wc[4], we[4], r[4];
    size_t b = oblq__locate(c, p->blocks_coord, &f[0]);
    size_t e = oblq__locate(xe, p->blocks_e_n, &f[1]);
    size_t leaf, n1, sc, se, i;
    const double *v;
    leaf = oblq__descend(p, b * p->blocks_e_n + e, f, 2);
    n1 = p->m + 1;
    sc = oblq__stencil4(f[0] * (double)p->m, n1, wc);
    se = oblq__stencil4(f[1] * (double)p->m, n1, we);
    v = p->p + leaf * n1 * n1 + sc * n1 + se;
    for (i = 0; i < 4; i++) {
        const double *row = v + i * n1;
        r[i] = row[0] * we[0] + row[1] * we[1] + row[2] * we[2] + row[3] * we[3];
    }
    return wc[0] * r[0] + wc[1] * r[1] + wc[2] * r[2] + wc[3] * r[3];
}

/* Step 5 with knots (layout versions 5 and 7): c' of the clamped c where the knots apply, at
   root-cell positions v_gamma = x blocks_gamma and v_e = x_e blocks_e_n (clamped as in step 6) with
   from <= v < to on both axes (to included where it is the last root edge); else c. The knot
   values K_j: the cubic stencils on the grid at u = (gamma - gamma_0)/gamma_step and
   w = (e_n - e_n_0)/e_n_step (each clamped to the grid), r_a = we_0 knot[j][sg+a][se] + ...,
   K_j = 0 + wg_0 r_0 + ... + wg_3 r_3, left to right; then the map of c's segment
   (docs/table-format.md, "The knots"). */
OBLQ_FN double oblq__knotted(const oblq_patch *p, double gamma, double c, double xe,
                             double e_n) {
    double bg = (double)p->blocks_gamma, be = (double)p->blocks_e_n;
    double vg = oblq__clamp((gamma - p->gamma_lo) / (p->gamma_hi - p->gamma_lo) * bg, 0.0, bg);
    double ve = oblq__clamp(xe * be, 0.0, be);
    double k[OBLQ_MAX_KNOTS], wg[4], we[4], u, w, k0, c0, k1, c1, width, t;
    size_t sg, se, j, a, s = 0, n = p->k_n;
    const double *r = p->k_region;
    if (!(vg >= r[0] && (vg < r[1] || r[1] >= bg) && ve >= r[2] && (ve < r[3] || r[3] >= be)))
        return c;
    u = oblq__clamp((gamma - p->k_gamma_0) / p->k_gamma_step, 0.0, (double)(p->k_ng - 1));
    w = oblq__clamp((e_n - p->k_e_n_0) / p->k_e_n_step, 0.0, (double)(p->k_ne - 1));
    sg = oblq__stencil4(u, p->k_ng, wg);
    se = oblq__stencil4(w, p->k_ne, we);
    for (j = 0; j < n; j++) {
        double sum = 0.0;
        for (a = 0; a < 4; a++) {
            const double *v = p->k_knot + (j * p->k_ng + sg + a) * p->k_ne + se;
            double inner = we[0] * v[0] + we[1] * v[1] + we[2] * v[2] + we[3] * v[3];
            sum += wg[a] * inner;
        }
        k[j] = sum;
        if (sum < c) s++; /* the segment of c: the number of knots below it */
    }
    k0 = s == 0 ? 0.0 : k[s - 1];
    c0 = s == 0 ? 0.0 : p->k_c_star[s - 1];
    k1 = s == n ? 1.0 : k[s];
    c1 = s == n ? 1.0 : p->k_c_star[s];
    width = k1 - k0;
    if (!(width > 0.0)) return c0; /* an empty segment (or NaN) */
    if (s < n && p->k_grade[s] == 1) {
        t = (c - k0) / width;
        return c0 + (c1 - c0) * (1.0 - sqrt(oblq__max0(1.0 - t)));
    }
    if (s > 0 && p->k_grade[s - 1] == 2) {
        t = (c - k0) / width;
        return c0 + (c1 - c0) * sqrt(oblq__max0(t));
    }
    return c0 + (c1 - c0) * (c - k0) / width;
}

/* The rule of a table with an e_n axis in a region above the line, inside the domain. */
OBLQ_FN double oblq__eval_in_e(const oblq_table *t, int region, double gamma, double alpha,
                               double e_n) {
    const oblq_patch *p = &t->patch[region];
    double c, xe;
    if (!p->present) return -e_n; /* at gamma = 1 exactly the contact sticks at once */
    c = !p->partial  ? oblq__stick_coord(gamma, alpha, t->alpha_max)
        : t->no_line ? oblq__partial_coord_slip(gamma, alpha, e_n)
                     : oblq__partial_coord_e(gamma, alpha, e_n);
    c = oblq__clamp(c, 0.0, 1.0);
    xe = oblq__x_e(t, e_n);
    if (p->k_n) c = oblq__knotted(p, gamma, c, xe, e_n);
    return oblq__clamp(t->pair ? oblq__tensor_pair(p, c, xe) : oblq__tensor3(p, gamma, c, xe),
                       -1.0, 1.0);
}

/* gamma as the rule takes it: in the table of one pair a gamma within 1e-9 (relative) of the
   pair's is the pair's (P moves by far less than the table's error there); any other as it
   is (then refused as outside the domain, or clamped, above the full-slip line). */
OBLQ_FN double oblq__rule_gamma(const oblq_table *t, double gamma) {
    double g = t->gamma_min;
    return t->pair && fabs(gamma - g) <= 1e-9 * g ? g : gamma;
}

/* oblq_p_e of a table with an e_n axis, e_n checked. */
OBLQ_FN int oblq__p_axis(const oblq_table *t, double gamma, double alpha, double e_n, int clamp,
                         double *p) {
    int region = oblq__region_t(t, gamma, alpha, e_n), inside;
    if (region < 0) {
        *p = oblq__line_e(alpha, e_n);
        return OBLQ_OK;
    }
    inside = gamma >= t->gamma_min && gamma <= t->gamma_max;
    if (!(inside && alpha <= t->alpha_max)) {
        if (!clamp) return inside ? OBLQ_E_ALPHA_DOMAIN : OBLQ_E_GAMMA_DOMAIN;
        gamma = oblq__clamp(gamma, t->gamma_min, t->gamma_max);
        alpha = alpha < t->alpha_max ? alpha : t->alpha_max;
        region = oblq__region_t(t, gamma, alpha, e_n);
        if (region < 0) {
            *p = oblq__line_e(alpha, e_n);
            return OBLQ_OK;
        }
    }
    *p = oblq__eval_in_e(t, region, gamma, alpha, e_n);
    return OBLQ_OK;
}

/* P(gamma, alpha, e_n) (dimensionless, -1 <= P <= 1) at normal restitution e_n by the table's
   rule (docs/table-format.md, schema v4). e_n must lie in the table's range [e_n_min, e_n_max]
   (oblq_e_n_range), else OBLQ_E_E_N: it is never clamped, and an elastic table answers
   e_n = 1 only (as oblq_p). On the full-slip line, alpha <= alpha_c1(gamma, e_n) (gamma > 1) or
   alpha_c2 (gamma <= 1), P = 1 - (7/2)(1 + e_n) alpha for any gamma > 0; gamma, alpha and clamp
   otherwise as for oblq_p (clamp moves gamma and alpha only). The table of one pair (t->pair,
   layout version 3, gamma_min == gamma_max) takes a gamma within 1e-9 relative of its own,
   |gamma - gamma_min| <= 1e-9 gamma_min, as its own; above the line it refuses any other
   (OBLQ_E_GAMMA_DOMAIN) or, with clamp, answers at its own. A table of Thornton's law
   (t->no_line, layout version 4) has no full-slip line: every alpha, 0 included, is answered
   from its patches inside the domain (gamma_min >= 1) and refused or clamped outside it. */
OBLQ_FN int oblq_p_e(const oblq_table *t, double gamma, double alpha, double e_n, int clamp,
                     double *p) {
    if (!t || !p) return OBLQ_E_NULL;
    if (!(gamma > 0.0 && gamma < INFINITY)) return OBLQ_E_GAMMA;
    if (!(alpha >= 0.0)) return OBLQ_E_ALPHA; /* NaN or negative */
    if (!(e_n >= t->e_n_min && e_n <= t->e_n_max)) return OBLQ_E_E_N; /* NaN too */
    if (!t->has_e_n) return oblq__p_elastic(t, gamma, alpha, clamp, p);
    return oblq__p_axis(t, oblq__rule_gamma(t, gamma), alpha, e_n, clamp, p);
}

/* P(gamma, alpha) (dimensionless, -1 <= P <= 1) by the table's rule. gamma finite > 0,
   alpha >= 0 (INFINITY: no slip). On the full-slip line P = 1 - 7 alpha for any gamma > 0;
   elsewhere outside the table's domain: OBLQ_E_GAMMA_DOMAIN / OBLQ_E_ALPHA_DOMAIN, or with
   clamp != 0 the answer at the nearest point of the domain. A table with an e_n axis answers
   its elastic slice, oblq_p_e at e_n = 1 (OBLQ_E_E_N when its range ends below 1). */
OBLQ_FN int oblq_p(const oblq_table *t, double gamma, double alpha, int clamp, double *p) {
    if (t && t->has_e_n) return oblq_p_e(t, gamma, alpha, 1.0, clamp, p);
    return oblq__p_elastic(t, gamma, alpha, clamp, p);
}

/* The number of axes of a point of the table (oblq_p_at): 2 (gamma, alpha), 3 with an e_n
   axis (gamma, alpha, e_n). */
OBLQ_FN int oblq_axis_count(const oblq_table *t, int *n) {
    if (!t || !n) return OBLQ_E_NULL;
    *n = 2 + (t->has_e_n != 0);
    return OBLQ_OK;
}

/* The name of axis i of a point of the table (0 <= i < oblq_axis_count): "gamma", "alpha",
   "e_n"; NULL for another i (or t NULL). A static string. */
OBLQ_FN const char *oblq_axis_name(const oblq_table *t, int i) {
    if (!t || i < 0 || i >= 2 + (t->has_e_n != 0)) return (const char *)0;
    return i == 0 ? "gamma" : i == 1 ? "alpha" : "e_n";
}

/* P at the point x[0..n), one value per axis of the table in order (oblq_axis_name): oblq_p
   for {gamma, alpha} of an elastic table, oblq_p_e for {gamma, alpha, e_n} of a table with an
   e_n axis, the same bits; another n is OBLQ_E_AXES. */
OBLQ_FN int oblq_p_at(const oblq_table *t, const double *x, int n, int clamp, double *p) {
    if (!t || !x || !p) return OBLQ_E_NULL;
    if (n != 2 + (t->has_e_n != 0)) return OBLQ_E_AXES;
    if (n == 2) return oblq_p(t, x[0], x[1], clamp, p);
    return oblq_p_e(t, x[0], x[1], x[2], clamp, p);
}

/* The e_n range [e_n_min, e_n_max] the table answers (oblq_p_e): 1, 1 for an elastic table. */
OBLQ_FN int oblq_e_n_range(const oblq_table *t, double *e_n_min, double *e_n_max) {
    if (!t || !e_n_min || !e_n_max) return OBLQ_E_NULL;
    *e_n_min = t->e_n_min;
    *e_n_max = t->e_n_max;
    return OBLQ_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Curves: P(alpha) at one gamma                                                              */

/* The i-th curve of the export (0 <= i < t->n_curves). */
OBLQ_FN int oblq_curve_get(const oblq_table *t, size_t i, oblq_curve *c) {
    oblq_curve out;
    int rc;
    if (!t || !c) return OBLQ_E_NULL;
    if (i >= t->n_curves) return OBLQ_E_NO_CURVE;
    rc = oblq__curve_at(t, i, &out);
    if (rc == OBLQ_OK) *c = out;
    return rc;
}

/* The curve of the export whose gamma is nearest to `gamma`, if within `rel_tol` relative
   (0: the exact value exported). */
OBLQ_FN int oblq_curve_find(const oblq_table *t, double gamma, double rel_tol, oblq_curve *c) {
    size_t i, best = 0;
    double dbest = INFINITY;
    if (!t || !c) return OBLQ_E_NULL;
    if (!(isfinite(gamma) && gamma > 0.0)) return OBLQ_E_GAMMA;
    for (i = 0; i < t->n_curves; i++) {
        double g = oblq__f64(t->data + t->curves + 168 * i);
        double dist = fabs(g - gamma);
        if (dist < dbest) {
            dbest = dist;
            best = i;
        }
    }
    if (!(dbest <= rel_tol * gamma)) return OBLQ_E_NO_CURVE;
    return oblq_curve_get(t, best, c);
}

/* Make a curve of the table `from` (oblq_curve_get or oblq_curve_find) refer to the same
   bytes in `to`, a copy of `from` moved by oblq_rebase (e.g. to the device). OBLQ_E_NO_CURVE
   when the curve does not point into `from`'s export. */
OBLQ_FN int oblq_curve_rebase(oblq_curve *c, const oblq_table *from, const oblq_table *to) {
    oblq_curve out;
    oblq_piece *pc[2];
    int k;
    if (!c || !from || !to || !from->data || !to->data) return OBLQ_E_NULL;
    if (from->size != to->size) return OBLQ_E_CORRUPT;
    out = *c;
    pc[0] = &out.partial;
    pc[1] = &out.stick;
    for (k = 0; k < 2; k++) {
        uintptr_t at = (uintptr_t)pc[k]->coef, lo = (uintptr_t)from->data;
        if (!pc[k]->present) continue;
        if (at < lo || at - lo > from->size || 32 * (uint64_t)pc[k]->n > from->size - (at - lo))
            return OBLQ_E_NO_CURVE;
        pc[k]->coef = (const double *)oblq__moved(pc[k]->coef, from->data, to->data);
    }
    *c = out;
    return OBLQ_OK;
}

OBLQ_FN double oblq__piece_eval(const oblq_piece *pc, double c) {
    double u, s;
    size_t i;
    const double *a;
    if (pc->warp) c = oblq__warp_apply(pc->k, pc->c_star, c);
    u = c * (double)pc->n;
    i = oblq__floor_index(u, pc->n - 1);
    s = u - (double)i - 0.5;
    a = pc->coef + 4 * i;
    return oblq__clamp(((a[3] * s + a[2]) * s + a[1]) * s + a[0], -1.0, 1.0);
}

/* P(gamma, alpha) of the curve's gamma, for alpha >= 0: the table's answer to about 1e-15.
   alpha above the table's alpha_max: OBLQ_E_ALPHA_DOMAIN, or with clamp != 0 at alpha_max. */
OBLQ_FN int oblq_curve_p(const oblq_curve *cv, double alpha, int clamp, double *p) {
    double c;
    if (!cv || !p) return OBLQ_E_NULL;
    if (!(alpha >= 0.0)) return OBLQ_E_ALPHA; /* NaN or negative */
    if (alpha <= cv->alpha_lin) {
        *p = 1.0 - 7.0 * alpha;
        return OBLQ_OK;
    }
    if (alpha > cv->alpha_max) {
        if (!clamp) return OBLQ_E_ALPHA_DOMAIN;
        alpha = cv->alpha_max;
        if (alpha <= cv->alpha_lin) {
            *p = 1.0 - 7.0 * alpha;
            return OBLQ_OK;
        }
    }
    if (cv->high && alpha < cv->alpha_c2) {
        double l;
        if (!cv->partial.present) {
            *p = -1.0;
            return OBLQ_OK;
        }
        l = log(7.0 * alpha * cv->ratio / cv->g2) / cv->ln_ratio;
        c = 1.0 - sqrt(oblq__max0(1.0 - l));
        *p = oblq__piece_eval(&cv->partial, oblq__clamp(c, 0.0, 1.0));
        return OBLQ_OK;
    }
    if (!cv->stick.present) {
        *p = -1.0;
        return OBLQ_OK;
    }
    if (alpha == INFINITY) {
        c = 1.0;
    } else {
        double d = alpha - cv->stick_c2;
        c = d / (d + cv->rho_c2);
        if (cv->s_max == cv->s_max) c = c / cv->s_max; /* s_max is NaN for alpha_max = inf */
    }
    *p = oblq__piece_eval(&cv->stick, oblq__clamp(c, 0.0, 1.0));
    return OBLQ_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Closed forms                                                                               */

/* Tangential restitution of the centre, e_t = v_x/v_x0 = 1 - (kappa/(1 + kappa))(1 - P), of a
   sphere (I = kappa m R^2) hitting a wall without spin; (2P + 5)/7 for kappa = 0.4. */
OBLQ_FN int oblq_e_t(double p, double kappa, double *e_t) {
    if (!e_t) return OBLQ_E_NULL;
    if (!(isfinite(p) && p >= -1.0 && p <= 1.0)) return OBLQ_E_P_RANGE;
    if (!(isfinite(kappa) && kappa > 0.0)) return OBLQ_E_KAPPA;
    *e_t = 1.0 - kappa / (1.0 + kappa) * (1.0 - p);
    return OBLQ_OK;
}

/* Friction regime of (gamma, alpha): 0 full slip, 1 partial slip, 2 stick. */
OBLQ_FN int oblq_regime(double gamma, double alpha, int *regime) {
    if (!regime) return OBLQ_E_NULL;
    if (!(isfinite(gamma) && gamma > 0.0)) return OBLQ_E_GAMMA;
    if (isnan(alpha) || alpha < 0.0) return OBLQ_E_ALPHA;
    *regime = alpha <= oblq_linear_limit(gamma) ? 0 : (alpha < oblq_alpha_c2(gamma) ? 1 : 2);
    return OBLQ_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Bodies, materials and rebounds (SI units)                                                  */

/* A sphere: mass m (kg), radius R (m), inertia factor kappa in I = kappa m R^2 (0.4 solid). */
typedef struct {
    double mass, radius, kappa;
} oblq_body;

/* Elastic constants: Young's modulus E (Pa; INFINITY for a rigid body), Poisson's ratio nu. */
typedef struct {
    double youngs_modulus, poisson_ratio;
} oblq_material;

/* A pair of bodies with its contact, checked and reduced once (oblq_pair_init,
   oblq_pair_init_e). */
typedef struct {
    int wall; /* 1: sphere 1 on a fixed wall */
    double gamma, friction;
    double alpha_scale, tangential_mass, two_normal_mass; /* two_normal_mass: (1 + e_n) m* */
    double inv_m1, spin1, r1, inv_m2, spin2, r2;
    double e_n;          /* normal restitution (1: elastic) */
    double normal_mass;  /* m* (kg) */
    double normal_loss;  /* (m* / 2)(1 - e_n^2) (kg): energy lost per unit v_z0^2 */
} oblq_pair;

/* Velocity v (m/s) and angular velocity w (rad/s) of one body. */
typedef struct {
    double v[3], w[3];
} oblq_motion3;

/* Both bodies before a 3-D impact, and the contact normal n from sphere 1's centre into the
   wall or towards sphere 2's centre (any non-zero length). A wall's motion must be zero. */
typedef struct {
    oblq_motion3 sphere, other;
    double normal[3];
} oblq_incident3;

/* The outcome of a 3-D impact. */
typedef struct {
    oblq_motion3 sphere, other;  /* after (other: unchanged zero for a wall) */
    double tangent[3];           /* t: direction of the incident slip of the contact point */
    double gamma, alpha;         /* the groups used */
    double p;                    /* P = u_after/u_before (NaN when u0 = 0) */
    double e_t;                  /* tangential restitution of the centres (NaN: none) */
    double slip_before, slip_after;      /* |u0| and P |u0| along t (m/s) */
    double tangential_impulse;   /* J on body 2 along +t (N s) */
    double normal_impulse;       /* (1 + e_n) m* v_z0 on body 2 along +n (N s) */
    double approach_speed;       /* v_z0 (m/s) */
    double energy_lost;          /* (m_t/2) u0^2 (1 - P^2) + (m* / 2) v_z0^2 (1 - e_n^2) (J) */
    double e_n;                  /* the pair's normal restitution: separation at e_n v_z0 */
} oblq_rebound3;

OBLQ_FN int oblq__body_ok(const oblq_body *b) {
    if (!(isfinite(b->mass) && b->mass > 0.0)) return OBLQ_E_MASS;
    if (!(isfinite(b->radius) && b->radius > 0.0)) return OBLQ_E_RADIUS;
    if (!(isfinite(b->kappa) && b->kappa > 0.0)) return OBLQ_E_KAPPA;
    return OBLQ_OK;
}

OBLQ_FN double oblq__inv_mt(const oblq_body *b) {
    double inertia = b->kappa * b->mass * b->radius * b->radius;
    return 1.0 / b->mass + b->radius * b->radius / inertia;
}

/* gamma = sqrt((m* / m_t) G* / E*) of sphere 1 (material a) on a wall (other = NULL) or on
   sphere 2 (material b is the wall's or sphere 2's). */
OBLQ_FN int oblq_gamma_of(const oblq_body *sphere, const oblq_body *other,
                          const oblq_material *a, const oblq_material *b, double *gamma) {
    const oblq_material *m[2];
    double ce[2], cg[2], e_star, g_star, inv_mt, normal_mass;
    int k, rc;
    if (!sphere || !a || !b || !gamma) return OBLQ_E_NULL;
    if ((rc = oblq__body_ok(sphere)) != OBLQ_OK) return rc;
    if (other && (rc = oblq__body_ok(other)) != OBLQ_OK) return rc;
    m[0] = a;
    m[1] = b;
    for (k = 0; k < 2; k++) {
        double e = m[k]->youngs_modulus, nu = m[k]->poisson_ratio;
        if (isnan(e) || e <= 0.0) return OBLQ_E_MODULUS;
        if (!(nu > -1.0 && nu <= 0.5)) return OBLQ_E_POISSON;
    }
    if (isinf(a->youngs_modulus) && isinf(b->youngs_modulus)) return OBLQ_E_MODULUS;
    for (k = 0; k < 2; k++) {
        double e = m[k]->youngs_modulus, nu = m[k]->poisson_ratio;
        if (isinf(e)) {
            ce[k] = 0.0;
            cg[k] = 0.0;
        } else {
            double g = e / (2.0 * (1.0 + nu));
            ce[k] = (1.0 - nu * nu) / e;
            cg[k] = (2.0 - nu) / (4.0 * g);
        }
    }
    e_star = 1.0 / (ce[0] + ce[1]);
    g_star = 1.0 / (cg[0] + cg[1]);
    normal_mass = other ? 1.0 / (1.0 / sphere->mass + 1.0 / other->mass) : sphere->mass;
    inv_mt = oblq__inv_mt(sphere) + (other ? oblq__inv_mt(other) : 0.0);
    *gamma = sqrt(normal_mass / (1.0 / inv_mt) * g_star / e_star);
    return OBLQ_OK;
}

/* Check a pair (sphere 1 on a wall when other = NULL, else on sphere 2), its gamma (from
   oblq_gamma_of, or given), friction mu >= 0 (INFINITY: no slip) and normal restitution
   0 <= e_n <= 1 (else OBLQ_E_E_N), once for many impacts. The normal relative velocity
   reverses to e_n times its value: normal impulse (1 + e_n) m* v_z0, and (m* / 2) v_z0^2
   (1 - e_n^2) more energy lost (as Rust's Prepared::new with Contact::with_restitution). The
   rebounds then ask the table for P(gamma, alpha, e_n) (oblq_p_e): e_n must lie in its e_n
   range, else they return OBLQ_E_E_N (an elastic table: e_n = 1 only; curves: e_n = 1 only),
   on every path: a pure normal impact (u0 = 0), whose P is not needed, is refused the same way
   (as in Rust, Python and the C ABI). */
OBLQ_FN int oblq_pair_init_e(oblq_pair *k, const oblq_body *sphere, const oblq_body *other,
                             double gamma, double friction, double e_n) {
    double inv_mt, normal_mass, mt;
    int rc;
    if (!k || !sphere) return OBLQ_E_NULL;
    if ((rc = oblq__body_ok(sphere)) != OBLQ_OK) return rc;
    if (other && (rc = oblq__body_ok(other)) != OBLQ_OK) return rc;
    if (!(isfinite(gamma) && gamma > 0.0)) return OBLQ_E_GAMMA;
    if (isnan(friction) || friction < 0.0) return OBLQ_E_FRICTION;
    if (!(e_n >= 0.0 && e_n <= 1.0)) return OBLQ_E_E_N; /* NaN too */
    normal_mass = other ? 1.0 / (1.0 / sphere->mass + 1.0 / other->mass) : sphere->mass;
    inv_mt = oblq__inv_mt(sphere) + (other ? oblq__inv_mt(other) : 0.0);
    mt = 1.0 / inv_mt;
    k->wall = other == NULL;
    k->gamma = gamma;
    k->friction = friction;
    k->alpha_scale = 2.0 / 7.0 * (normal_mass / mt) * friction;
    k->tangential_mass = mt;
    k->two_normal_mass = (1.0 + e_n) * normal_mass; /* 2 m* exactly for e_n = 1 */
    k->e_n = e_n;
    k->normal_mass = normal_mass;
    k->normal_loss = 0.5 * normal_mass * (1.0 - e_n * e_n);
    k->inv_m1 = 1.0 / sphere->mass;
    k->spin1 = sphere->radius / (sphere->kappa * sphere->mass * sphere->radius * sphere->radius);
    k->r1 = sphere->radius;
    if (other) {
        k->inv_m2 = 1.0 / other->mass;
        k->spin2 = other->radius / (other->kappa * other->mass * other->radius * other->radius);
        k->r2 = other->radius;
    } else {
        k->inv_m2 = 0.0;
        k->spin2 = 0.0;
        k->r2 = 0.0;
    }
    return OBLQ_OK;
}

/* oblq_pair_init_e of an elastic impact, e_n = 1. */
OBLQ_FN int oblq_pair_init(oblq_pair *k, const oblq_body *sphere, const oblq_body *other,
                           double gamma, double friction) {
    return oblq_pair_init_e(k, sphere, other, gamma, friction, 1.0);
}

OBLQ_FN double oblq__dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

OBLQ_FN void oblq__cross(const double a[3], const double b[3], double o[3]) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* o = y + a x */
OBLQ_FN void oblq__axpy(const double y[3], double a, const double x[3], double o[3]) {
    o[0] = y[0] + a * x[0];
    o[1] = y[1] + a * x[1];
    o[2] = y[2] + a * x[2];
}

/* The 3-D rebound with P from the table (curve = NULL) or from a curve of the pair's gamma. */
OBLQ_FN int oblq__rebound_3d(const oblq_table *t, const oblq_curve *cv, const oblq_pair *k,
                           const oblq_incident3 *s, int clamp, oblq_rebound3 *out) {
    double len, n[3], c1[3], c2[3], u[3], u_t[3], tmp[3], slip, tg[3], b[3], v0, u0, alpha, p;
    double j, nn, d[3], w0[3], w1[3], w0w0;
    oblq_rebound3 *r = out; /* written only after the last check */
    const oblq_motion3 *m1, *m2;
    int i, rc;
    if (!k || !s || !out || (!t && !cv)) return OBLQ_E_NULL;
    if (cv && k->e_n != 1.0) return OBLQ_E_E_N; /* curves are elastic */
    {
        /* Every component finite: x * 0 is (+-)0 for a finite x and NaN otherwise. */
        double z = 0.0;
        for (i = 0; i < 3; i++)
            z += s->sphere.v[i] * 0.0 + s->sphere.w[i] * 0.0 + s->other.v[i] * 0.0 +
                 s->other.w[i] * 0.0 + s->normal[i] * 0.0;
        if (z != 0.0) return OBLQ_E_MOTION;
    }
    if (k->wall)
        for (i = 0; i < 3; i++)
            if (s->other.v[i] != 0.0 || s->other.w[i] != 0.0) return OBLQ_E_WALL_MOTION;
    len = sqrt(oblq__dot(s->normal, s->normal));
    if (!(len > 0.0 && len < INFINITY)) return OBLQ_E_NORMAL;
    for (i = 0; i < 3; i++) n[i] = (1.0 / len) * s->normal[i];
    m1 = &s->sphere;
    m2 = &s->other;
    oblq__cross(m1->w, n, tmp);
    oblq__axpy(m1->v, k->r1, tmp, c1);
    oblq__cross(m2->w, n, tmp);
    oblq__axpy(m2->v, -k->r2, tmp, c2);
    for (i = 0; i < 3; i++) u[i] = c1[i] - c2[i];
    oblq__axpy(u, -oblq__dot(u, n), n, u_t);
    slip = sqrt(oblq__dot(u_t, u_t));
    /* The relative centre velocity (sphere 1's own for a wall, whose motion is zero). */
    for (i = 0; i < 3; i++) d[i] = m1->v[i] - m2->v[i];
    v0 = oblq__dot(d, n);
    if (!(v0 > 0.0 && v0 < INFINITY)) return OBLQ_E_APPROACH;
    if (!(slip < INFINITY)) return OBLQ_E_MOTION;
    oblq__axpy(d, -oblq__dot(d, n), n, w0);
    if (slip > 0.0) {
        for (i = 0; i < 3; i++) tg[i] = (1.0 / slip) * u_t[i];
        u0 = slip;
        alpha = k->alpha_scale * v0 / u0;
        if (alpha != alpha) alpha = INFINITY; /* 0 * inf (no friction, no slip speed) */
        rc = cv ? oblq_curve_p(cv, alpha, clamp, &p)
                : oblq_p_e(t, k->gamma, alpha, k->e_n, clamp, &p);
        if (rc != OBLQ_OK) return rc;
        j = k->tangential_mass * (1.0 - p) * u0;
    } else {
        /* u0 = 0: a pure normal impact; the tangent along the centres' tangential motion, or
           the axis least aligned with n. P is not needed, but an e_n the table does not
           answer is refused as on every other path. */
        double wl = sqrt(oblq__dot(w0, w0));
        if (!cv && !(k->e_n >= t->e_n_min && k->e_n <= t->e_n_max)) return OBLQ_E_E_N;
        if (wl > 0.0) {
            for (i = 0; i < 3; i++) tg[i] = w0[i] / wl;
        } else {
            int a = 0;
            double e[3] = {0.0, 0.0, 0.0}, el;
            if (fabs(n[1]) < fabs(n[a])) a = 1;
            if (fabs(n[2]) < fabs(n[a])) a = 2;
            e[a] = 1.0;
            oblq__axpy(e, -n[a], n, tmp);
            el = sqrt(oblq__dot(tmp, tmp));
            for (i = 0; i < 3; i++) tg[i] = tmp[i] / el;
        }
        u0 = 0.0;
        alpha = INFINITY;
        p = NAN;
        j = 0.0;
    }
    oblq__cross(n, tg, b);
    nn = k->two_normal_mass * v0;
    oblq__axpy(m1->v, -j * k->inv_m1, tg, tmp);
    oblq__axpy(tmp, -nn * k->inv_m1, n, r->sphere.v);
    oblq__axpy(m1->w, -j * k->spin1, b, r->sphere.w);
    if (k->wall) {
        r->other = *m2;
    } else {
        oblq__axpy(m2->v, j * k->inv_m2, tg, tmp);
        oblq__axpy(tmp, nn * k->inv_m2, n, r->other.v);
        oblq__axpy(m2->w, -j * k->spin2, b, r->other.w);
    }
    oblq__axpy(w0, -j * (k->inv_m1 + k->inv_m2), tg, w1);
    w0w0 = oblq__dot(w0, w0);
    for (i = 0; i < 3; i++) r->tangent[i] = tg[i];
    r->gamma = k->gamma;
    r->alpha = alpha;
    r->p = p;
    r->e_t = w0w0 == 0.0 ? NAN : oblq__dot(w1, w0) / w0w0;
    r->slip_before = u0;
    r->slip_after = u0 == 0.0 ? 0.0 : p * u0;
    r->tangential_impulse = j;
    r->normal_impulse = nn;
    r->approach_speed = v0;
    /* The operations of the Rust library: its fast path for u0 > 0, its step-by-step one
       (Pair::rebound_in_plane_dissipative) for u0 = 0. */
    r->energy_lost = u0 == 0.0
                         ? 0.0 + 0.5 * k->normal_mass * v0 * v0 * (1.0 - k->e_n * k->e_n)
                         : 0.5 * k->tangential_mass * u0 * u0 * (1.0 - p * p) +
                               (k->normal_loss == 0.0 ? 0.0 : k->normal_loss * v0 * v0);
    r->e_n = k->e_n;
    return OBLQ_OK;
}

/* A 3-D impact of a pair, P from the table. */
OBLQ_FN int oblq_rebound_3d(const oblq_table *t, const oblq_pair *k, const oblq_incident3 *s,
                          int clamp, oblq_rebound3 *out) {
    if (!t) return OBLQ_E_NULL;
    return oblq__rebound_3d(t, NULL, k, s, clamp, out);
}

/* A 3-D impact of a pair, P from a curve of the export at the pair's gamma (the same answer
   to about 1e-15 in P, fewer operations). Curves are elastic: a pair of e_n != 1 is refused
   (OBLQ_E_E_N). */
OBLQ_FN int oblq_rebound_3d_curve(const oblq_curve *c, const oblq_pair *k,
                                const oblq_incident3 *s, int clamp, oblq_rebound3 *out) {
    if (!c) return OBLQ_E_NULL;
    return oblq__rebound_3d(NULL, c, k, s, clamp, out);
}

/* A 2-D impact in its plane: z the normal from sphere 1 into the other body (v_z > 0
   approaches), x the tangent; a spin omega is signed so that sphere 1's contact point moves at
   v_x + R omega (sphere 2's at v_x - R omega). Fields: v_x, v_z (m/s), omega (rad/s). */
typedef struct {
    double v_x, v_z, omega;
} oblq_state;

typedef struct {
    oblq_state sphere, other; /* after (other unchanged for a wall) */
    double gamma, alpha, p, e_t, slip_before, slip_after, tangential_impulse, normal_impulse,
        energy_lost;
    double e_n; /* the pair's normal restitution */
} oblq_rebound2;

/* A 2-D impact (sphere and other states before), P from the table or a curve (one of them may
   be NULL). Uses only the pair's masses, radii and inertia through oblq_pair, and its e_n
   (oblq_pair_init_e; a curve answers e_n = 1 only, else OBLQ_E_E_N). */
OBLQ_FN int oblq_rebound_2d(const oblq_table *t, const oblq_curve *cv, const oblq_pair *k,
                          const oblq_state *s1, const oblq_state *s2, int clamp,
                          oblq_rebound2 *out) {
    oblq_incident3 in;
    oblq_rebound3 r;
    int rc;
    if (!k || !s1 || !out || (!t && !cv) || (!k->wall && !s2)) return OBLQ_E_NULL;
    /* The plane of impact as a 3-D impact: x the tangent, y = z x x the spin axis, z normal. */
    memset(&in, 0, sizeof in);
    in.sphere.v[0] = s1->v_x;
    in.sphere.v[2] = s1->v_z;
    in.sphere.w[1] = s1->omega;
    if (!k->wall) {
        in.other.v[0] = s2->v_x;
        in.other.v[2] = s2->v_z;
        in.other.w[1] = s2->omega;
    } else if (s2 && (s2->v_x != 0.0 || s2->v_z != 0.0 || s2->omega != 0.0)) {
        return OBLQ_E_WALL_MOTION;
    }
    in.normal[2] = 1.0;
    rc = oblq__rebound_3d(t, cv, k, &in, clamp, &r);
    if (rc != OBLQ_OK) return rc;
    out->sphere.v_x = r.sphere.v[0];
    out->sphere.v_z = r.sphere.v[2];
    out->sphere.omega = r.sphere.w[1];
    out->other.v_x = r.other.v[0];
    out->other.v_z = r.other.v[2];
    out->other.omega = r.other.w[1];
    out->gamma = r.gamma;
    out->alpha = r.alpha;
    out->p = r.p;
    out->e_t = r.e_t;
    /* Signed along +x, as in the 2-D algebra. */
    out->slip_before = r.slip_before * r.tangent[0];
    out->slip_after = r.slip_after * r.tangent[0];
    out->tangential_impulse = r.tangential_impulse * r.tangent[0];
    out->normal_impulse = r.normal_impulse;
    out->energy_lost = r.energy_lost;
    out->e_n = r.e_n;
    return OBLQ_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Loading an export from a file (host only)                                                  */

#ifndef OBLQ_NO_STDIO
/* Read the export file at `path` (a NUL-terminated name) into memory (malloc: 8-byte aligned)
   and open it (oblq_open). On OBLQ_OK, *t is the table and owns that memory (t->data): free it
   with oblq_free_file(t) once t and the curves made from it are no longer used. On an error,
   *t is untouched and nothing stays allocated: OBLQ_E_NULL (t is NULL), OBLQ_E_FILE (path is
   NULL, or the file cannot be opened or read; errno as the failing call left it), OBLQ_E_NOT_FILE (a directory, FIFO, device or
   socket: refused before it is opened, so that a FIFO does not block and /dev/zero is not read
   until memory runs out), OBLQ_E_NO_MEMORY, or oblq_open's code for the contents.
   No more bytes are read than the file had when it was opened (a file that grows meanwhile is
   refused, OBLQ_E_FILE).

       oblq_table t;
       int rc = oblq_load_file(&t, "full.oblq");
       if (rc != OBLQ_OK) { fprintf(stderr, "full.oblq: %s\n", oblq_error_message(rc)); ... }
       ...
       oblq_free_file(&t);

   Host code only (C stdio and malloc; not marked OBLQ_FN, so CUDA device code cannot call it:
   load on the host, then copy t.data to the device as above). The only function of this header
   that allocates or touches files; define OBLQ_NO_STDIO before including to leave it out (and
   the headers stdio.h, stdlib.h, errno.h it needs). */
static inline int oblq_load_file(oblq_table *t, const char *path) {
    FILE *f;
    char *buf = NULL;
    size_t cap = 0, len = 0, n, limit = (size_t)-1;
    oblq_table opened;
    int rc, saved;
#if defined(__unix__) || defined(__APPLE__)
    struct stat st;
#endif
    if (!t) return OBLQ_E_NULL;
    if (!path) return OBLQ_E_FILE;
#if defined(__unix__) || defined(__APPLE__)
    if (stat(path, &st) != 0) return OBLQ_E_FILE;
    if (!S_ISREG(st.st_mode)) return OBLQ_E_NOT_FILE;
    if ((unsigned long long)st.st_size < (unsigned long long)((size_t)-1))
        limit = (size_t)st.st_size + 1;
#endif
    f = fopen(path, "rb");
    if (!f) return OBLQ_E_FILE;
    for (;;) {
        if (len == cap) {
            char *bigger;
            cap = cap ? 2 * cap : (limit != (size_t)-1 && limit > 0 ? limit : (size_t)1 << 20);
            bigger = (char *)realloc(buf, cap);
            if (!bigger) {
                free(buf);
                fclose(f);
                return OBLQ_E_NO_MEMORY;
            }
            buf = bigger;
        }
        n = fread(buf + len, 1, (cap - len < limit - len) ? cap - len : limit - len, f);
        len += n;
        if (n == 0 || len == limit) break;
    }
    if ((limit != (size_t)-1 && len == limit) || ferror(f)) { /* it grew, or a read failed */
        saved = errno;
        free(buf);
        fclose(f);
        errno = saved;
        return OBLQ_E_FILE;
    }
    fclose(f);
    rc = oblq_open(&opened, buf, len);
    if (rc != OBLQ_OK) {
        free(buf);
        return rc;
    }
    *t = opened;
    return OBLQ_OK;
}

/* Free the memory of a table made by oblq_load_file (and clear *t); NULL, or a table whose
   memory was already freed, does nothing. Not for a table made by oblq_open on memory of the
   caller's. */
static inline void oblq_free_file(oblq_table *t) {
    if (!t || !t->data) return;
    free((void *)t->data);
    memset(t, 0, sizeof *t);
}
#endif /* OBLQ_NO_STDIO */

#ifdef __cplusplus
}
#endif

#endif /* OBLIQUE_EVAL_H */
