// A sphere-sphere collision operator as a DEM code would write it, on the dependency-free
// evaluator: post-collision velocities and spins of two particles from their positions,
// velocities, spins, radii, masses, materials and the friction coefficient. The normal motion
// is elastic (e_n = 1); the tangential part comes from the exported table (P from the curve of
// the pair's gamma when the export has it, else from the whole table).
//
//   sweep export tables/full.h5 -o full.oblq
//   g++ -std=c++11 -O2 -I include -o collision examples/cpp/collision.cpp -lm
//   ./collision full.oblq
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "oblique_eval.h"

struct Material {
    double youngs_modulus;  // Pa
    double poisson_ratio;
};

struct Particle {
    double x[3];      // position of the centre (m)
    double v[3];      // velocity (m/s)
    double w[3];      // angular velocity (rad/s)
    double radius;    // m
    double mass;      // kg
    double kappa;     // I = kappa m R^2 (0.4: solid sphere)
    int material;     // index into the material list
};

class ObliqueCollision {
  public:
    // Reads an export (sweep export) and keeps it in memory for the lifetime of the operator.
    ObliqueCollision(const std::string &path, std::vector<Material> materials, double friction)
        : materials_(std::move(materials)), friction_(friction) {
        std::ifstream in(path.c_str(), std::ios::binary | std::ios::ate);
        if (!in) throw std::runtime_error("cannot read " + path);
        std::streamsize size = in.tellg();
        in.seekg(0);
        // 8-byte aligned storage for the export.
        data_.resize(static_cast<size_t>(size + 7) / 8);
        if (!in.read(reinterpret_cast<char *>(data_.data()), size))
            throw std::runtime_error("cannot read " + path);
        int rc = oblq_open(&table_, data_.data(), static_cast<size_t>(size));
        if (rc != OBLQ_OK) throw std::runtime_error(path + ": " + oblq_error_message(rc));
    }

    // Collide a and b (in contact, approaching): updates their velocities and spins. Returns
    // the rebound (P, e_t, energy lost, ...) or throws with the evaluator's message.
    oblq_rebound3 collide(Particle &a, Particle &b) const {
        oblq_body ba = {a.mass, a.radius, a.kappa}, bb = {b.mass, b.radius, b.kappa};
        const Material &ma = materials_.at(a.material), &mb = materials_.at(b.material);
        oblq_material ea = {ma.youngs_modulus, ma.poisson_ratio};
        oblq_material eb = {mb.youngs_modulus, mb.poisson_ratio};
        double gamma;
        check(oblq_gamma_of(&ba, &bb, &ea, &eb, &gamma));
        oblq_pair pair;
        check(oblq_pair_init(&pair, &ba, &bb, gamma, friction_));
        oblq_incident3 s;
        for (int i = 0; i < 3; i++) {
            s.sphere.v[i] = a.v[i];
            s.sphere.w[i] = a.w[i];
            s.other.v[i] = b.v[i];
            s.other.w[i] = b.w[i];
            s.normal[i] = b.x[i] - a.x[i];  // from a's centre towards b's
        }
        oblq_rebound3 r;
        oblq_curve curve;
        if (oblq_curve_find(&table_, gamma, 1e-12, &curve) == OBLQ_OK)
            check(oblq_rebound_3d_curve(&curve, &pair, &s, 0, &r));
        else
            check(oblq_rebound_3d(&table_, &pair, &s, 0, &r));
        for (int i = 0; i < 3; i++) {
            a.v[i] = r.sphere.v[i];
            a.w[i] = r.sphere.w[i];
            b.v[i] = r.other.v[i];
            b.w[i] = r.other.w[i];
        }
        return r;
    }

  private:
    static void check(int rc) {
        if (rc != OBLQ_OK) throw std::runtime_error(oblq_error_message(rc));
    }
    std::vector<unsigned long long> data_;
    oblq_table table_;
    std::vector<Material> materials_;
    double friction_;
};

static double kinetic(const Particle &p) {
    double e = 0.0;
    for (int i = 0; i < 3; i++)
        e += 0.5 * p.mass * p.v[i] * p.v[i] + 0.5 * p.kappa * p.mass * p.radius * p.radius * p.w[i] * p.w[i];
    return e;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s EXPORT\n", argv[0]);
        return 2;
    }
    try {
        const double pi = 3.14159265358979323846;
        std::vector<Material> materials;
        materials.push_back(Material{210e9, 0.29});  // steel
        materials.push_back(Material{73e9, 0.217});  // soda-lime glass
        ObliqueCollision op(argv[1], materials, 0.3);
        double r1 = 5e-3, r2 = 3e-3;
        Particle a = {{0.0, 0.0, 0.0}, {1.0, 0.2, 2.0}, {0.0, 50.0, 0.0}, r1,
                      7850.0 * 4.0 / 3.0 * pi * r1 * r1 * r1, 0.4, 0};
        Particle b = {{0.0, 0.0, r1 + r2}, {0.0, 0.0, -1.0}, {0.0, 0.0, 10.0}, r2,
                      2500.0 * 4.0 / 3.0 * pi * r2 * r2 * r2, 0.4, 1};
        double e0 = kinetic(a) + kinetic(b);
        oblq_rebound3 r = op.collide(a, b);
        std::printf("gamma,%.17g\nalpha,%.17g\nP,%.17g\ne_t,%.17g\n", r.gamma, r.alpha, r.p, r.e_t);
        std::printf("a.v,%.17g,%.17g,%.17g\na.w,%.17g,%.17g,%.17g\n", a.v[0], a.v[1], a.v[2],
                    a.w[0], a.w[1], a.w[2]);
        std::printf("b.v,%.17g,%.17g,%.17g\nb.w,%.17g,%.17g,%.17g\n", b.v[0], b.v[1], b.v[2],
                    b.w[0], b.w[1], b.w[2]);
        std::printf("energy_lost,%.17g\nenergy_balance,%.3g\n", r.energy_lost,
                    (e0 - kinetic(a) - kinetic(b) - r.energy_lost) / e0);
        // A collision of particles that separate is refused with the evaluator's message.
        try {
            op.collide(a, b);
        } catch (const std::exception &e) {
            std::printf("refused,%s\n", e.what());
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
