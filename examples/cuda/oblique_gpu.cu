/* P(gamma, alpha) (P(gamma, alpha, e_n) of a table with an e_n axis), a curve P(alpha) and 3-D
   rebounds on a CUDA device, from an export of a table (`sweep export TABLE -o FILE`), each
   checked against the same header on the host, with the kernels' throughput. Needs the CUDA
   toolkit (nvcc) and the header only:

       nvcc -O2 -fmad=false -arch=native -I include -o oblique_gpu examples/cuda/oblique_gpu.cu
       ./oblique_gpu full.oblq [N]              N random points and impacts (default 10^6)
       ./oblique_gpu full.oblq --check FILE     the lines "gamma,alpha,P,..." of FILE (what
                                                `sweep query TABLE --batch` writes; - for stdin)

   A table with an e_n axis (oblq_table.has_e_n: tables/default.h5, tables/dissipative.h5) is
   answered by oblq_p_e: --check reads the lines "gamma,alpha,e_n,P,..." (`sweep query TABLE
   --batch` of lines `gamma,alpha,e_n`), the random points draw e_n too, and the impacts are of
   pairs with a normal restitution e_n (oblq_pair_init_e), spheres on spheres and on walls.
   Where the partial-slip patch has knots (layout version 5), a third of the random points and
   pairs lie in the knots' region, and the output counts the points whose answer took the knots'
   map. The table is opened and checked on the host (oblq_open), its bytes copied to the device,
   and a copy of the table moved there (oblq_rebase), then passed to the kernels by value; one
   thread answers one query. -fmad=false keeps the device's arithmetic the host's (no fused
   multiply-add); the device's log may round differently, so "differ" counts answers that are
   not the host's to the bit, and "max" is the largest |device - host| / max(1, |host|).
   Exit status: 0 when every answer has the host's status and max <= 1e-12, 1 otherwise or on
   a CUDA error, 2 for bad arguments, an unreadable export or an unreadable FILE. */
#define OBLQ_FN __host__ __device__ static inline
#include "oblique_eval.h"

#include <cuda_runtime.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static void cuda_check(cudaError_t e, const char *what) {
    if (e != cudaSuccess) {
        fprintf(stderr, "error: %s: %s\n", what, cudaGetErrorString(e));
        exit(1);
    }
}
#define CUDA(call) cuda_check((call), #call)

struct Point {
    double gamma, alpha;
};

/* A point of a table with an e_n axis. */
struct PointE {
    double gamma, alpha, e_n;
};

/* ---- Kernels: one thread per query --------------------------------------------------------- */

__global__ void p_kernel(oblq_table t, const Point *q, size_t n, double *p, int *rc) {
    size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x;
    double v = NAN;
    if (i >= n) return;
    rc[i] = oblq_p(&t, q[i].gamma, q[i].alpha, 0, &v);
    p[i] = v;
}

__global__ void p_e_kernel(oblq_table t, const PointE *q, size_t n, double *p, int *rc) {
    size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x;
    double v = NAN;
    if (i >= n) return;
    rc[i] = oblq_p_e(&t, q[i].gamma, q[i].alpha, q[i].e_n, 0, &v);
    p[i] = v;
}

__global__ void curve_kernel(oblq_curve c, const double *alpha, size_t n, double *p, int *rc) {
    size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x;
    double v = NAN;
    if (i >= n) return;
    rc[i] = oblq_curve_p(&c, alpha[i], 0, &v);
    p[i] = v;
}

__global__ void rebound_kernel(oblq_table t, const oblq_pair *pairs, size_t n_pairs,
                               const oblq_incident3 *s, size_t n, oblq_rebound3 *r, int *rc) {
    size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x;
    oblq_rebound3 out{};
    if (i >= n) return;
    rc[i] = oblq_rebound_3d(&t, &pairs[i % n_pairs], &s[i], 1, &out);
    r[i] = out;
}

/* oblq_open in device code (one thread; it reads the whole export serially). */
__global__ void open_kernel(const unsigned char *bytes, size_t size, oblq_table *t, int *rc) {
    *rc = oblq_open(t, bytes, size);
}

/* ---- Host helpers ------------------------------------------------------------------------- */

template <class T> static T *upload(const std::vector<T> &v) {
    T *d = nullptr;
    CUDA(cudaMalloc(&d, v.size() * sizeof(T)));
    CUDA(cudaMemcpy(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice));
    return d;
}

template <class T> static T *device_array(size_t n) {
    T *d = nullptr;
    CUDA(cudaMalloc(&d, n * sizeof(T)));
    return d;
}

template <class T> static std::vector<T> download(const T *d, size_t n) {
    std::vector<T> v(n);
    CUDA(cudaMemcpy(v.data(), d, n * sizeof(T), cudaMemcpyDeviceToHost));
    return v;
}

static unsigned blocks(size_t n) { return (unsigned)((n + 255) / 256); }

/* Milliseconds per launch: one launch (the answers), then the mean of 10 timed by events. */
template <class F> static double kernel_ms(F launch) {
    cudaEvent_t a, b;
    float ms = 0.0f;
    launch();
    CUDA(cudaGetLastError());
    CUDA(cudaDeviceSynchronize());
    CUDA(cudaEventCreate(&a));
    CUDA(cudaEventCreate(&b));
    CUDA(cudaEventRecord(a));
    for (int r = 0; r < 10; r++) launch();
    CUDA(cudaEventRecord(b));
    CUDA(cudaEventSynchronize(b));
    CUDA(cudaGetLastError());
    CUDA(cudaEventElapsedTime(&ms, a, b));
    CUDA(cudaEventDestroy(a));
    CUDA(cudaEventDestroy(b));
    return ms / 10.0;
}

static uint64_t rng_state = 20240531;
static double uniform() { /* splitmix64, 53 bits in [0, 1) */
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return ldexp((double)((z ^ (z >> 31)) >> 11), -53);
}

/* alpha over every regime at a gamma whose stick starts at c2: half below c2, 1 in 64 no slip. */
static double random_alpha(double c2, double alpha_max) {
    double u = uniform(), a = uniform() < 1.0 / 64.0 ? INFINITY : c2 * u / (1.0 - u);
    return a > alpha_max ? alpha_max * uniform() : a;
}

/* e_n over the range [lo, hi] of a table with an e_n axis: uniform, and 1 in 32 each exactly
   at 1 (at hi where the range stops below 1), at lo and at hi. */
static double random_e_n(double lo, double hi) {
    double u = uniform();
    if (u < 1.0 / 32.0) return hi < 1.0 ? hi : 1.0;
    if (u < 2.0 / 32.0) return lo;
    if (u < 3.0 / 32.0) return hi;
    return lo + (hi - lo) * uniform();
}

/* alpha_c1(gamma, e_n) = 2 gamma^2 / (7 (gamma^2 (1 + e_n) - e_n)), gamma > 1: the end of full
   slip at normal restitution e_n (physics.md); P = 1 - (7/2)(1 + e_n) alpha below it. */
static double alpha_c1_e(double gamma, double e_n) {
    double g2 = gamma * gamma;
    return 2.0 * g2 / (7.0 * (g2 * (1.0 + e_n) - e_n));
}

/* The knots of the partial-slip patch (patch[1], layout version 5): oblq_p_e maps the
   partial-slip coordinate by them inside their region, given in the patch's root cells along
   gamma and e_n (docs/table-format.md, "The knots"); here also as a box in gamma and e_n. */
struct Knots {
    bool any = false;
    double gamma_from = 0.0, gamma_to = 0.0, e_n_from = 0.0, e_n_to = 0.0;
};

static Knots knots_of(const oblq_table &t) {
    Knots k;
    const oblq_patch &p = t.patch[1];
    if (!t.has_e_n || !p.present || p.k_n == 0) return k;
    double wg = (p.gamma_hi - p.gamma_lo) / (double)p.blocks_gamma;
    k.any = true;
    k.gamma_from = p.gamma_lo + p.k_region[0] * wg;
    k.gamma_to = p.gamma_lo + p.k_region[1] * wg;
    /* Along e_n through the axis's map (layout version 8: over (1 - e_n)^(1/4)). */
    k.e_n_from = oblq__e_n_at(&t, p.k_region[2], (double)p.blocks_e_n);
    k.e_n_to = oblq__e_n_at(&t, p.k_region[3], (double)p.blocks_e_n);
    return k;
}

/* Whether oblq_p_e answers a point of the domain through the knots' map: the point is in
   partial slip (gamma > 1, alpha_c1(gamma, e_n) < alpha < alpha_c2; alpha < alpha_c2 and
   gamma >= 1 in a table without the full-slip line) and in the region, tested in root cells
   as the header tests it. */
static bool knotted(const oblq_table &t, const PointE &x) {
    const oblq_patch &p = t.patch[1];
    if (!t.has_e_n || !p.present || p.k_n == 0) return false;
    bool partial = t.no_line ? x.gamma >= 1.0 && x.alpha < oblq_alpha_c2(x.gamma)
                             : x.gamma > 1.0 && x.alpha > alpha_c1_e(x.gamma, x.e_n) &&
                                   x.alpha < oblq_alpha_c2(x.gamma);
    double bg = (double)p.blocks_gamma, be = (double)p.blocks_e_n;
    double vg = fmin(fmax((x.gamma - p.gamma_lo) / (p.gamma_hi - p.gamma_lo) * bg, 0.0), bg);
    double ve = fmin(fmax(oblq__x_e(&t, x.e_n) * be, 0.0), be);
    const double *r = p.k_region;
    return partial && vg >= r[0] && (vg < r[1] || r[1] >= bg) && ve >= r[2] &&
           (ve < r[3] || r[3] >= be);
}

static void print_knotted(const oblq_table &t, const std::vector<PointE> &q) {
    Knots k = knots_of(t);
    size_t in = 0;
    if (!k.any) return;
    for (const PointE &x : q) in += knotted(t, x);
    printf("%-26s %10zu of the %zu points in partial slip inside the knots' region "
           "(gamma [%.6g, %.6g], e_n [%.6g, %.6g])\n",
           "through the knots' map", in, q.size(), k.gamma_from, k.gamma_to, k.e_n_from,
           k.e_n_to);
}

/* Device answers against the host's (or the CLI's), k doubles per answer. */
struct Agreement {
    size_t answers = 0, refused = 0, differ = 0, status = 0;
    double max = 0.0;
    void add(int rc_host, int rc_dev, const double *h, const double *d, size_t k) {
        bool any = false;
        answers++;
        if (rc_host != rc_dev) {
            status++;
            return;
        }
        if (rc_host != OBLQ_OK) {
            refused++;
            return;
        }
        for (size_t j = 0; j < k; j++) {
            double diff;
            if (memcmp(&h[j], &d[j], sizeof(double)) == 0 || (std::isnan(h[j]) && std::isnan(d[j])))
                continue;
            any = true;
            diff = fabs(d[j] - h[j]) / fmax(1.0, fabs(h[j]));
            if (!(diff <= max)) max = std::isnan(diff) ? INFINITY : diff;
        }
        if (any) differ++;
    }
    bool ok() const { return status == 0 && max <= 1e-12; }
    void print(const char *what, const char *against, double ms) const {
        printf("%-26s %10zu answers (%zu refused alike), %zu differ from the %s's bits (max %.2g)"
               ", %zu statuses differ",
               what, answers, refused, differ, against, max, status);
        if (ms > 0.0) printf("; %.4f ms, %.3g queries/s", ms, (double)answers / (ms * 1e-3));
        printf("\n");
    }
};

/* P of a point: oblq_p at (gamma, alpha), oblq_p_e at (gamma, alpha, e_n); on the host, and
   launched on the device for n points. */
static int host_p(const oblq_table &t, const Point &x, double *p) {
    return oblq_p(&t, x.gamma, x.alpha, 0, p);
}
static int host_p(const oblq_table &t, const PointE &x, double *p) {
    return oblq_p_e(&t, x.gamma, x.alpha, x.e_n, 0, p);
}
static void launch_p(const oblq_table &t, const Point *q, size_t n, double *p, int *rc) {
    p_kernel<<<blocks(n), 256>>>(t, q, n, p, rc);
}
static void launch_p(const oblq_table &t, const PointE *q, size_t n, double *p, int *rc) {
    p_e_kernel<<<blocks(n), 256>>>(t, q, n, p, rc);
}

/* P of the points on the device (by the table `dev`) and the host; returns the device's. */
template <class Pt>
static std::vector<double> p_both(const oblq_table &host, const oblq_table &dev,
                                  const std::vector<Pt> &q, std::vector<int> &rc_dev,
                                  Agreement &agree, double &ms) {
    size_t n = q.size();
    Pt *d_q = upload(q);
    double *d_p = device_array<double>(n);
    int *d_rc = device_array<int>(n);
    ms = kernel_ms([&] { launch_p(dev, d_q, n, d_p, d_rc); });
    std::vector<double> p = download(d_p, n);
    rc_dev = download(d_rc, n);
    for (size_t i = 0; i < n; i++) {
        double h = NAN;
        int rc = host_p(host, q[i], &h);
        agree.add(rc, rc_dev[i], &h, &p[i], 1);
    }
    CUDA(cudaFree(d_q));
    CUDA(cudaFree(d_p));
    CUDA(cudaFree(d_rc));
    return p;
}

/* The whole file in 8-byte aligned memory, as oblq_open requires. */
static bool read_export(const char *path, std::vector<uint64_t> &words, size_t &size) {
    FILE *f = fopen(path, "rb");
    long len = -1;
    bool ok = f && fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0;
    if (ok) {
        words.assign(((size_t)len + 7) / 8, 0);
        ok = fread(words.data(), 1, (size_t)len, f) == (size_t)len;
        size = (size_t)len;
    }
    if (f) fclose(f);
    return ok;
}

static void oblq_check(int rc, const char *what) {
    if (rc != OBLQ_OK) {
        fprintf(stderr, "error: %s: %s\n", what, oblq_error_message(rc));
        exit(1);
    }
}

/* The points and P of a file's lines: "gamma,alpha,P,..." (an elastic table: other lines are
   skipped), or "gamma,alpha,e_n,P,..." (a table with an e_n axis: a line of other numbers, or
   a header other than "gamma,alpha,e_n,P...", is refused; blank and "#" lines are skipped).
   Returns 0, or 2 with a message. */
static int read_check(const char *path, bool e_n, std::vector<Point> &q, std::vector<PointE> &qe,
                      std::vector<double> &cli) {
    FILE *f = strcmp(path, "-") ? fopen(path, "r") : stdin;
    char line[512];
    size_t number = 0;
    if (!f) {
        fprintf(stderr, "error: cannot read %s\n", path);
        return 2;
    }
    while (fgets(line, sizeof line, f)) {
        double p;
        number++;
        if (!e_n) {
            Point x;
            if (sscanf(line, "%lf,%lf,%lf", &x.gamma, &x.alpha, &p) != 3) continue; /* header */
            q.push_back(x);
            cli.push_back(p);
            continue;
        }
        PointE x;
        if (sscanf(line, "%lf,%lf,%lf,%lf", &x.gamma, &x.alpha, &x.e_n, &p) == 4) {
            qe.push_back(x);
            cli.push_back(p);
        } else if (!(line[0] == '\n' || line[0] == '#' ||
                     (number == 1 && !strncmp(line, "gamma,alpha,e_n,P", 17)))) {
            fprintf(stderr, "error: %s, line %zu: not gamma,alpha,e_n,P (a table with an e_n axis)\n",
                    path, number);
            if (f != stdin) fclose(f);
            return 2;
        }
    }
    if (f != stdin) fclose(f);
    if (cli.empty()) {
        fprintf(stderr, "error: no lines %s in %s\n", e_n ? "gamma,alpha,e_n,P" : "gamma,alpha,P",
                path);
        return 2;
    }
    return 0;
}

/* The P of a file's points (the CLI's answers) against the device's and the host's. */
template <class Pt>
static bool check_points(const oblq_table &host, const oblq_table &dev, const std::vector<Pt> &q,
                         const std::vector<double> &cli) {
    std::vector<int> rc_dev;
    Agreement dev_host, dev_cli, host_cli;
    double ms;
    std::vector<double> p = p_both(host, dev, q, rc_dev, dev_host, ms);
    for (size_t i = 0; i < q.size(); i++) {
        double h = NAN;
        int rc_host = host_p(host, q[i], &h);
        dev_cli.add(OBLQ_OK, rc_dev[i], &cli[i], &p[i], 1);
        host_cli.add(OBLQ_OK, rc_host, &cli[i], &h, 1);
    }
    dev_host.print("P, device vs host", "host", 0.0);
    dev_cli.print("P, device vs file", "file", 0.0);
    host_cli.print("P, host vs file", "file", 0.0);
    return dev_host.ok() && dev_cli.ok() && host_cli.ok();
}

/* P at random points of the domain on the device and the host, then, when `opened_ok` and the
   device agrees, by the table oblq_open made on the device (at most 65536 points), which must
   answer as the rebased one, to the bit. Returns whether all of it holds. */
template <class Pt>
static bool random_points(const oblq_table &host, const oblq_table &dev,
                          const oblq_table &opened, bool opened_ok, std::vector<Pt> q,
                          const char *what) {
    std::vector<int> rc_dev;
    Agreement agree, same;
    double ms;
    size_t n = q.size();
    bool ok;
    std::vector<double> p = p_both(host, dev, q, rc_dev, agree, ms);
    agree.print(what, "host", ms);
    ok = opened_ok && agree.ok();
    if (ok) {
        size_t bits = 0;
        q.resize(n < 65536 ? n : 65536);
        std::vector<double> p2 = p_both(host, opened, q, rc_dev, same, ms);
        for (size_t i = 0; i < q.size(); i++) bits += memcmp(&p[i], &p2[i], sizeof(double)) != 0;
        printf("%-26s %10zu answers, %zu differ from the rebased table's bits\n",
               "P, table opened on device", q.size(), bits);
        ok = bits == 0;
    }
    return ok;
}

int main(int argc, char **argv) {
    size_t size = 0, n = 1000000;
    oblq_table host, dev, opened;
    const char *check = nullptr;
    bool ok = true;
    if (argc == 4 && !strcmp(argv[2], "--check")) {
        check = argv[3];
    } else if (argc == 3) {
        char *end = nullptr;
        n = strtoull(argv[2], &end, 10);
        if (argv[2][0] < '0' || argv[2][0] > '9' || *end != '\0') n = 0;
    } else if (argc != 2) {
        fprintf(stderr, "usage: %s EXPORT [N] | EXPORT --check FILE\n", argv[0]);
        return 2;
    }
    if (n == 0) {
        fprintf(stderr, "error: N must be a whole number > 0, not %s\n", argv[2]);
        return 2;
    }
    std::vector<uint64_t> file;
    if (!read_export(argv[1], file, size)) {
        fprintf(stderr, "error: cannot read %s\n", argv[1]);
        return 2;
    }
    const unsigned char *bytes = reinterpret_cast<const unsigned char *>(file.data());
    int rc = oblq_open(&host, bytes, size);
    if (rc != OBLQ_OK) {
        fprintf(stderr, "error: %s: %s\n", argv[1], oblq_error_message(rc));
        return 2;
    }
    /* The file's points, read before the device is used. */
    std::vector<Point> q_check;
    std::vector<PointE> qe_check;
    std::vector<double> cli;
    if (check && (rc = read_check(check, host.has_e_n, q_check, qe_check, cli)) != 0) return rc;

    /* The export on the device, and the table moved there. */
    cudaDeviceProp prop;
    CUDA(cudaGetDeviceProperties(&prop, 0));
    unsigned char *d_bytes = device_array<unsigned char>(size);
    CUDA(cudaMemcpy(d_bytes, bytes, size, cudaMemcpyHostToDevice));
    dev = host;
    oblq_check(oblq_rebase(&dev, d_bytes), "oblq_rebase");
    printf("%s: %zu bytes, gamma [%g, %g], alpha_max %g, %zu curves; device %s (sm_%d%d)\n",
           argv[1], size, host.gamma_min, host.gamma_max, host.alpha_max, host.n_curves,
           prop.name, prop.major, prop.minor);
    Knots knots = knots_of(host);
    if (host.has_e_n)
        printf("e_n axis [%g, %g]: P(gamma, alpha, e_n) by oblq_p_e; %s\n", host.e_n_min,
               host.e_n_max,
               knots.any ? "the partial-slip patch has knots" : "no knots");

    /* oblq_open on the device gives a table that answers as the rebased one. */
    {
        oblq_table *d_t = device_array<oblq_table>(1);
        int *d_rc = device_array<int>(1);
        open_kernel<<<1, 1>>>(d_bytes, size, d_t, d_rc);
        CUDA(cudaGetLastError());
        opened = download(d_t, 1)[0];
        rc = download(d_rc, 1)[0];
        printf("oblq_open on the device: %s\n", oblq_error_message(rc));
        ok = ok && rc == OBLQ_OK && opened.data == d_bytes;
        CUDA(cudaFree(d_t));
        CUDA(cudaFree(d_rc));
    }

    if (check) {
        if (host.has_e_n) {
            ok = check_points(host, dev, qe_check, cli) && ok;
            print_knotted(host, qe_check);
        } else {
            ok = check_points(host, dev, q_check, cli) && ok;
        }
        printf("%s\n", ok ? "ok" : "FAILED");
        return ok ? 0 : 1;
    }

    /* P at n random points of the domain (with e_n: a third in the knots' region, in partial
       slip, where the table has knots). */
    if (!host.has_e_n) {
        std::vector<Point> q(n);
        for (Point &x : q) {
            x.gamma = host.gamma_min + (host.gamma_max - host.gamma_min) * uniform();
            x.alpha = random_alpha(oblq_alpha_c2(x.gamma), host.alpha_max);
        }
        ok = random_points(host, dev, opened, ok, q, "P(gamma, alpha)");
    } else {
        std::vector<PointE> q(n);
        for (size_t i = 0; i < n; i++) {
            PointE &x = q[i];
            if (knots.any && i % 3 == 0) {
                x.gamma = knots.gamma_from + (knots.gamma_to - knots.gamma_from) * uniform();
                x.e_n = knots.e_n_from + (knots.e_n_to - knots.e_n_from) * uniform();
                double lo = host.no_line ? 0.0 : alpha_c1_e(x.gamma, x.e_n);
                x.alpha = lo + (oblq_alpha_c2(x.gamma) - lo) * uniform();
            } else {
                x.gamma = host.gamma_min + (host.gamma_max - host.gamma_min) * uniform();
                x.e_n = random_e_n(host.e_n_min, host.e_n_max);
                x.alpha = random_alpha(oblq_alpha_c2(x.gamma), host.alpha_max);
            }
        }
        ok = random_points(host, dev, opened, ok, q, "P(gamma, alpha, e_n)");
        print_knotted(host, q);
    }

    /* P(alpha) of the export's first curve, at n random alpha. */
    if (host.n_curves > 0) {
        oblq_curve hc, dc;
        std::vector<double> alpha(n);
        Agreement agree;
        oblq_check(oblq_curve_get(&host, 0, &hc), "oblq_curve_get");
        dc = hc;
        oblq_check(oblq_curve_rebase(&dc, &host, &dev), "oblq_curve_rebase");
        for (double &a : alpha) a = random_alpha(hc.alpha_c2, hc.alpha_max);
        double *d_a = upload(alpha), *d_p = device_array<double>(n);
        int *d_rc = device_array<int>(n);
        double ms = kernel_ms([&] { curve_kernel<<<blocks(n), 256>>>(dc, d_a, n, d_p, d_rc); });
        std::vector<double> p = download(d_p, n);
        std::vector<int> rc_dev = download(d_rc, n);
        for (size_t i = 0; i < n; i++) {
            double h = NAN;
            int rc_host = oblq_curve_p(&hc, alpha[i], 0, &h);
            agree.add(rc_host, rc_dev[i], &h, &p[i], 1);
        }
        char what[64];
        snprintf(what, sizeof what, "curve P(alpha), gamma %.5g", hc.gamma);
        agree.print(what, "host", ms);
        ok = ok && agree.ok();
        CUDA(cudaFree(d_a));
        CUDA(cudaFree(d_p));
        CUDA(cudaFree(d_rc));
    }

    /* n impacts, P by the table: an elastic table, 8 pairs of steel-like spheres (mu 0.1 to
       0.5); a table with an e_n axis, 64 pairs of a random e_n (random_e_n), every other
       one a sphere on a wall, and a third (the walls' too) with gamma and e_n in the knots'
       region where the table has knots. */
    {
        std::vector<oblq_pair> pairs(host.has_e_n ? 64 : 8);
        std::vector<oblq_incident3> s(n);
        Agreement agree;
        size_t walls = 0;
        for (size_t j = 0; j < pairs.size(); j++) {
            double r1 = 1e-3 * (1.0 + uniform()), r2 = 1e-3 * (1.0 + uniform());
            oblq_body b1 = {7800.0 * 4.18879 * r1 * r1 * r1, r1, 0.4};
            oblq_body b2 = {7800.0 * 4.18879 * r2 * r2 * r2, r2, 0.4};
            double gamma = host.gamma_min + (host.gamma_max - host.gamma_min) * uniform();
            if (!host.has_e_n) {
                oblq_check(oblq_pair_init(&pairs[j], &b1, &b2, gamma, 0.1 + 0.4 * uniform()),
                           "oblq_pair_init");
                continue;
            }
            double e_n = random_e_n(host.e_n_min, host.e_n_max);
            if (knots.any && j % 3 == 0) {
                gamma = knots.gamma_from + (knots.gamma_to - knots.gamma_from) * uniform();
                e_n = knots.e_n_from + (knots.e_n_to - knots.e_n_from) * uniform();
            }
            walls += j % 2;
            oblq_check(oblq_pair_init_e(&pairs[j], &b1, j % 2 ? nullptr : &b2, gamma,
                                        0.1 + 0.4 * uniform(), e_n),
                       "oblq_pair_init_e");
        }
        size_t np = pairs.size();
        for (size_t i = 0; i < n; i++) {
            oblq_incident3 &x = s[i];
            double d = 0.0;
            for (int j = 0; j < 3; j++) {
                x.sphere.v[j] = 2.0 * uniform() - 1.0;
                x.sphere.w[j] = 200.0 * uniform() - 100.0;
                x.other.v[j] = 2.0 * uniform() - 1.0;
                x.other.w[j] = 200.0 * uniform() - 100.0;
                x.normal[j] = 2.0 * uniform() - 1.0;
            }
            if (pairs[i % np].wall) x.other = oblq_motion3{}; /* a wall does not move */
            for (int j = 0; j < 3; j++) d += (x.sphere.v[j] - x.other.v[j]) * x.normal[j];
            if (d < 0.0) /* approaching along the normal */
                for (int j = 0; j < 3; j++) x.normal[j] = -x.normal[j];
        }
        oblq_pair *d_pairs = upload(pairs);
        oblq_incident3 *d_s = upload(s);
        oblq_rebound3 *d_r = device_array<oblq_rebound3>(n);
        int *d_rc = device_array<int>(n);
        double ms = kernel_ms(
            [&] { rebound_kernel<<<blocks(n), 256>>>(dev, d_pairs, np, d_s, n, d_r, d_rc); });
        std::vector<oblq_rebound3> r = download(d_r, n);
        std::vector<int> rc_dev = download(d_rc, n);
        for (size_t i = 0; i < n; i++) {
            oblq_rebound3 h{};
            int rc_host = oblq_rebound_3d(&host, &pairs[i % np], &s[i], 1, &h);
            agree.add(rc_host, rc_dev[i], reinterpret_cast<const double *>(&h),
                      reinterpret_cast<const double *>(&r[i]), sizeof h / sizeof(double));
        }
        if (host.has_e_n)
            printf("impacts: %zu pairs, %zu of them a sphere on a wall, e_n by the pair\n", np,
                   walls);
        agree.print(host.has_e_n ? "rebound_3d e_n, all fields" : "rebound_3d (every field)",
                    "host", ms);
        ok = ok && agree.ok();
        CUDA(cudaFree(d_pairs));
        CUDA(cudaFree(d_s));
        CUDA(cudaFree(d_r));
        CUDA(cudaFree(d_rc));
    }
    CUDA(cudaFree(d_bytes));
    printf("%s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
