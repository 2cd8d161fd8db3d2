/* P(gamma, alpha), a curve P(alpha) and 3-D sphere-sphere rebounds on a CUDA device, from an
   export of a table (`sweep export TABLE -o FILE`), each checked against the same header on
   the host, with the kernels' throughput. Needs the CUDA toolkit (nvcc) and the header only:

       nvcc -O2 -fmad=false -arch=native -I include -o oblique_gpu examples/cuda/oblique_gpu.cu
       ./oblique_gpu full.oblq [N]              N random points and impacts (default 10^6)
       ./oblique_gpu full.oblq --check FILE     the lines "gamma,alpha,P,..." of FILE (what
                                                `sweep query TABLE --batch` writes; - for stdin)

   The table is opened and checked on the host (oblq_open), its bytes copied to the device, and
   a copy of the table moved there (oblq_rebase), then passed to the kernels by value; one
   thread answers one query. -fmad=false keeps the device's arithmetic the host's (no fused
   multiply-add); the device's log may round differently, so "differ" counts answers that are
   not the host's to the bit, and "max" is the largest |device - host| / max(1, |host|).
   Exit status: 0 when every answer has the host's status and max <= 1e-12, 1 otherwise or on
   a CUDA error, 2 for bad arguments or an unreadable export. */
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

/* ---- Kernels: one thread per query --------------------------------------------------------- */

__global__ void p_kernel(oblq_table t, const Point *q, size_t n, double *p, int *rc) {
    size_t i = blockIdx.x * (size_t)blockDim.x + threadIdx.x;
    double v = NAN;
    if (i >= n) return;
    rc[i] = oblq_p(&t, q[i].gamma, q[i].alpha, 0, &v);
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

/* P of the points on the device (by the table `dev`) and the host; returns the device's. */
static std::vector<double> p_both(const oblq_table &host, const oblq_table &dev,
                                  const std::vector<Point> &q, std::vector<int> &rc_dev,
                                  Agreement &agree, double &ms) {
    size_t n = q.size();
    Point *d_q = upload(q);
    double *d_p = device_array<double>(n);
    int *d_rc = device_array<int>(n);
    ms = kernel_ms([&] { p_kernel<<<blocks(n), 256>>>(dev, d_q, n, d_p, d_rc); });
    std::vector<double> p = download(d_p, n);
    rc_dev = download(d_rc, n);
    for (size_t i = 0; i < n; i++) {
        double h = NAN;
        int rc = oblq_p(&host, q[i].gamma, q[i].alpha, 0, &h);
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

int main(int argc, char **argv) {
    size_t size = 0, n = 1000000;
    oblq_table host, dev, opened;
    const char *check = nullptr;
    bool ok = true;
    if (argc == 4 && !strcmp(argv[2], "--check")) {
        check = argv[3];
    } else if (argc == 3) {
        n = strtoull(argv[2], nullptr, 10);
    } else if (argc != 2) {
        fprintf(stderr, "usage: %s EXPORT [N] | EXPORT --check FILE\n", argv[0]);
        return 2;
    }
    std::vector<uint64_t> file;
    if (!read_export(argv[1], file, size) || n == 0) {
        fprintf(stderr, "error: cannot read %s (or N is 0)\n", argv[1]);
        return 2;
    }
    const unsigned char *bytes = reinterpret_cast<const unsigned char *>(file.data());
    int rc = oblq_open(&host, bytes, size);
    if (rc != OBLQ_OK) {
        fprintf(stderr, "error: %s: %s\n", argv[1], oblq_error_message(rc));
        return 2;
    }

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
        /* The P of a file's lines (the CLI's answers) against the device's and the host's. */
        FILE *f = strcmp(check, "-") ? fopen(check, "r") : stdin;
        char line[512];
        std::vector<Point> q;
        std::vector<double> cli;
        std::vector<int> rc_dev;
        Agreement dev_host, dev_cli, host_cli;
        double ms;
        if (!f) {
            fprintf(stderr, "error: cannot read %s\n", check);
            return 2;
        }
        while (fgets(line, sizeof line, f)) {
            Point x;
            double p;
            if (sscanf(line, "%lf,%lf,%lf", &x.gamma, &x.alpha, &p) != 3) continue; /* header */
            q.push_back(x);
            cli.push_back(p);
        }
        if (q.empty()) {
            fprintf(stderr, "error: no lines gamma,alpha,P in %s\n", check);
            return 2;
        }
        std::vector<double> p = p_both(host, dev, q, rc_dev, dev_host, ms);
        for (size_t i = 0; i < q.size(); i++) {
            double h = NAN;
            int rc_host = oblq_p(&host, q[i].gamma, q[i].alpha, 0, &h);
            dev_cli.add(OBLQ_OK, rc_dev[i], &cli[i], &p[i], 1);
            host_cli.add(OBLQ_OK, rc_host, &cli[i], &h, 1);
        }
        dev_host.print("P, device vs host", "host", 0.0);
        dev_cli.print("P, device vs file", "file", 0.0);
        host_cli.print("P, host vs file", "file", 0.0);
        ok = ok && dev_host.ok() && dev_cli.ok() && host_cli.ok();
        printf("%s\n", ok ? "ok" : "FAILED");
        return ok ? 0 : 1;
    }

    /* P at n random points of the domain. */
    {
        std::vector<Point> q(n);
        std::vector<int> rc_dev;
        Agreement agree, same;
        double ms;
        for (Point &x : q) {
            x.gamma = host.gamma_min + (host.gamma_max - host.gamma_min) * uniform();
            x.alpha = random_alpha(oblq_alpha_c2(x.gamma), host.alpha_max);
        }
        std::vector<double> p = p_both(host, dev, q, rc_dev, agree, ms);
        agree.print("P(gamma, alpha)", "host", ms);
        ok = ok && agree.ok();
        /* The table oblq_open made on the device answers as the rebased one, to the bit. */
        if (ok) {
            size_t bits = 0;
            q.resize(n < 65536 ? n : 65536);
            std::vector<double> p2 = p_both(host, opened, q, rc_dev, same, ms);
            for (size_t i = 0; i < q.size(); i++) bits += memcmp(&p[i], &p2[i], sizeof(double)) != 0;
            printf("%-26s %10zu answers, %zu differ from the rebased table's bits\n",
                   "P, table opened on device", q.size(), bits);
            ok = bits == 0;
        }
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

    /* n sphere-sphere impacts (8 pairs of steel-like spheres, mu 0.1 to 0.5), P by the table. */
    {
        std::vector<oblq_pair> pairs(8);
        std::vector<oblq_incident3> s(n);
        Agreement agree;
        for (oblq_pair &k : pairs) {
            double r1 = 1e-3 * (1.0 + uniform()), r2 = 1e-3 * (1.0 + uniform());
            oblq_body b1 = {7800.0 * 4.18879 * r1 * r1 * r1, r1, 0.4};
            oblq_body b2 = {7800.0 * 4.18879 * r2 * r2 * r2, r2, 0.4};
            double gamma = host.gamma_min + (host.gamma_max - host.gamma_min) * uniform();
            oblq_check(oblq_pair_init(&k, &b1, &b2, gamma, 0.1 + 0.4 * uniform()), "oblq_pair_init");
        }
        for (oblq_incident3 &x : s) {
            double d = 0.0;
            for (int j = 0; j < 3; j++) {
                x.sphere.v[j] = 2.0 * uniform() - 1.0;
                x.sphere.w[j] = 200.0 * uniform() - 100.0;
                x.other.v[j] = 2.0 * uniform() - 1.0;
                x.other.w[j] = 200.0 * uniform() - 100.0;
                x.normal[j] = 2.0 * uniform() - 1.0;
                d += (x.sphere.v[j] - x.other.v[j]) * x.normal[j];
            }
            if (d < 0.0) /* approaching along the normal */
                for (int j = 0; j < 3; j++) x.normal[j] = -x.normal[j];
        }
        oblq_pair *d_pairs = upload(pairs);
        oblq_incident3 *d_s = upload(s);
        oblq_rebound3 *d_r = device_array<oblq_rebound3>(n);
        int *d_rc = device_array<int>(n);
        size_t np = pairs.size();
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
        agree.print("rebound_3d (every field)", "host", ms);
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
