//! The Fortran bindings (`fortran/oblique_eval_f.c`, the module `fortran/oblique_eval.f90` and
//! `fortran/example.f90`) against the Rust library: compiled warning-free with gcc and gfortran
//! (and once more under AddressSanitizer and UndefinedBehaviorSanitizer), linked to nothing but
//! the C and Fortran runtimes, the example's P values bit-for-bit, its rebound to 1e-12, its
//! error report; and a driver written here that takes the module through random points, curves,
//! wall and sphere rebounds, every refusal and every message. A missing gcc or gfortran fails
//! the test (scripts/test installs gfortran).

mod common;
mod evaluator;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use evaluator::{
    anisotropic_table, dissipative_table, points_e, random_body, random_impact, rebound_fields,
    run, run_ok, sealed, status_of, ANISOTROPIC_GAMMAS,
};
use oblique_lookup::rebound::{Body, Elastic, Incident3, Motion3, Pair};
use oblique_lookup::{Contact, OutOfDomain, Prepared, Table};
use oblique_physics::sample::SplitMix;
use oblique_table::export;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const F_FLAGS: [&str; 6] = [
    "-std=f2008",
    "-Wall",
    "-Wextra",
    "-Werror",
    "-pedantic",
    "-O2",
];
const SANITIZE: [&str; 3] = [
    "-g",
    "-fsanitize=address,undefined",
    "-fno-sanitize-recover=all",
];
/// The curve the export holds (an isotropic material's gamma); the example finds it near 1.75.
const CURVE_GAMMA: f64 = 1.749_785_860_077_429_9;

fn root(p: &str) -> PathBuf {
    Path::new(ROOT).join(p)
}

/// This process's scratch folder (made once).
fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| common::subdir("fortran"))
}

fn table() -> &'static Table {
    static FULL: OnceLock<Table> = OnceLock::new();
    FULL.get_or_init(|| Table::open(root("tables/full.h5")).expect("shipped table"))
}

/// The export of tables/full.h5 with the curve of `CURVE_GAMMA`, written once; its path.
fn export_file() -> &'static Path {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| {
        let t = table();
        let curve = t
            .curve(CURVE_GAMMA, OutOfDomain::Error)
            .expect("curve")
            .export_data()
            .expect("inside the domain");
        let bytes = export::export(t.surface(), t.error_bound(), true, &[curve]);
        let path = dir().join("full.oblq");
        std::fs::write(&path, bytes).expect("write export");
        path
    })
}

/// Run a compiler; a missing one fails with how to install it.
fn run_compiler(tool: &str, args: &[String]) {
    let r = Command::new(tool).args(args).output().unwrap_or_else(|e| {
        panic!(
            "cannot run {tool} ({e}): install it (scripts/test does: \
             OBLIQUE_SETUP_EXTRA=gfortran source scripts/setup.sh)"
        )
    });
    assert!(
        r.status.success(),
        "{tool} {} failed:\n{}{}",
        args.join(" "),
        String::from_utf8_lossy(&r.stdout),
        String::from_utf8_lossy(&r.stderr)
    );
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

fn path_str(p: &Path) -> String {
    p.to_str().expect("utf-8 path").to_string()
}

/// The shim, the module, the example and the driver of this file compiled into `dir()/tag`
/// (with `extra` flags for both languages); the paths of the example and the driver.
fn build(tag: &str, extra: &[&str]) -> (PathBuf, PathBuf) {
    let d = dir().join(tag);
    std::fs::create_dir_all(&d).expect("build folder");
    let mut cflags = strings(&evaluator::C_STRICT);
    cflags.push("-O2".into());
    cflags.extend(strings(extra));
    let mut fflags = strings(&F_FLAGS);
    fflags.extend(strings(extra));
    let shim = d.join("oblique_eval_f.o");
    let module = d.join("oblique_eval.o");
    let mut args = cflags.clone();
    args.extend([
        "-I".into(),
        path_str(&root("include")),
        "-c".into(),
        path_str(&root("fortran/oblique_eval_f.c")),
        "-o".into(),
        path_str(&shim),
    ]);
    run_compiler("gcc", &args);
    let mut args = fflags.clone();
    args.extend([
        "-J".into(),
        path_str(&d),
        "-c".into(),
        path_str(&root("fortran/oblique_eval.f90")),
        "-o".into(),
        path_str(&module),
    ]);
    run_compiler("gfortran", &args);
    let driver_src = d.join("driver.f90");
    std::fs::write(&driver_src, DRIVER).expect("write driver");
    let mut exes = Vec::new();
    for (src, name) in [
        (root("fortran/example.f90"), "example"),
        (driver_src, "driver"),
    ] {
        let exe = d.join(name);
        let mut args = fflags.clone();
        args.extend([
            "-I".into(),
            path_str(&d),
            "-o".into(),
            path_str(&exe),
            path_str(&src),
            path_str(&module),
            path_str(&shim),
        ]);
        run_compiler("gfortran", &args);
        exes.push(exe);
    }
    (exes[0].clone(), exes[1].clone())
}

fn num(s: &str) -> f64 {
    s.trim()
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {s:?}"))
}

/// One dissipative rebound printed by the Fortran driver (`c`: status, then 16 fields) against
/// `Table::rebound_3d` of the same case `(pair, γ, μ, e_n, incident)`: where Rust answers,
/// status 0 and every field with Rust's bits (NaN as NaN), and `true`; where it refuses, the
/// status `refusal` and NaN fields, and `false`.
fn rebound_matches(
    t: &Table,
    c: &[f64],
    (pair, gamma, mu, e_n, s): &(Pair, f64, f64, f64, Incident3),
    refusal: f64,
) -> bool {
    let contact = Contact::with_gamma(*gamma, *mu).with_restitution(*e_n);
    match t.rebound_3d(pair, &contact, s) {
        Ok(a) => {
            assert_eq!(c[0], 0.0);
            let want = &rebound_fields(&a)[..16];
            for (k, (x, y)) in c[1..].iter().zip(want).enumerate() {
                assert!(
                    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
                    "gamma {gamma:?} e_n {e_n:?} field {k}: Fortran {x:?}, Rust {y:?}"
                );
            }
            true
        }
        Err(e) => {
            assert_eq!(c[0], refusal, "{e}");
            assert!(c[1..].iter().all(|x| x.is_nan()));
            false
        }
    }
}

fn nums(s: &str) -> Vec<f64> {
    s.split_whitespace().map(num).collect()
}

/// `x` within `rel` of `want` relative to `scale` (and both NaN, or the same bits, pass).
fn close(x: f64, want: f64, rel: f64, scale: f64) -> bool {
    x.to_bits() == want.to_bits()
        || (x.is_nan() && want.is_nan())
        || (x - want).abs() <= rel * scale.max(want.abs())
}

/// The status codes of the header's enum, by name.
fn header_codes() -> BTreeMap<String, i32> {
    let h = std::fs::read_to_string(root("include/oblique_eval.h")).expect("header");
    let mut codes = BTreeMap::new();
    for line in h.lines() {
        let Some((name, value)) = line.trim().split_once(" = ") else {
            continue;
        };
        let is_code =
            name.starts_with("OBLQ_") && name.chars().all(|c| c.is_ascii_uppercase() || c == '_');
        if is_code {
            let digits: String = value.chars().take_while(char::is_ascii_digit).collect();
            codes.insert(name.to_string(), digits.parse().expect("enum value"));
        }
    }
    codes
}

/// The texts of `oblq_error_message`, by code.
fn header_messages(codes: &BTreeMap<String, i32>) -> BTreeMap<i32, String> {
    let h = std::fs::read_to_string(root("include/oblique_eval.h")).expect("header");
    let mut out = BTreeMap::new();
    for line in h.lines() {
        let l = line.trim();
        if let Some(rest) = l.strip_prefix("case ") {
            if let Some((name, text)) = rest.split_once(": return \"") {
                let text = text.strip_suffix("\";").expect("one-line message");
                out.insert(codes[name.trim()], text.to_string());
            }
        }
    }
    out
}

/// A Fortran program over the module: reads the export named by its first argument, then
/// answers stdin lines, one output line each (status first, reals in G0.17):
///   p GAMMA ALPHA CLAMP             status P
///   pv G1 A1 G2 A2 G3 A3            the elemental form on arrays: 3 x (status P)
///   pe GAMMA ALPHA E_N CLAMP        status P                 (oblique_p_e)
///   pev G1 A1 E1 G2 A2 E2 G3 A3 E3  the elemental oblique_p_e on arrays: 3 x (status P)
///   erange                          status e_n_min e_n_max
///   curve GAMMA REL_TOL             status found_gamma      (the curve is kept)
///   cp ALPHA CLAMP                  status P                 (of the kept curve)
///   r  M1 R1 K1 M2 R2 K2 GAMMA MU V1 W1 V2 W2 N CLAMP        status v1 w1 v2 w2 P e_t E alpha
///   rc M1 R1 K1 M2 R2 K2 MU V1 W1 V2 W2 N CLAMP              the same with P from the curve
///   re M1 R1 K1 M2 R2 K2 GAMMA MU E_N V1 W1 V2 W2 N CLAMP    `r` at normal restitution E_N
///   g  M1 R1 K1 E1 NU1 M2 R2 K2 E2 NU2                       status gamma
///   m CODE                          len:text
///   info                            status gamma_min gamma_max alpha_max bound surface n
///   close                           closes the table (later queries: status 1)
const DRIVER: &str = r#"program driver
   use oblique_eval
   implicit none
   type(oblique_table) :: t
   type(oblique_curve) :: c
   character(len=:), allocatable :: path, msg
   character(len=4096) :: line
   character(len=8) :: cmd
   integer :: length, ios
   integer(c_int) :: status, clamp, code, n, st3(3)
   logical :: surface
   real(c_double) :: g, a, p, m1, r1, k1, m2, r2, k2, mu, e1, nu1, e2, nu2, e_t, lost, alpha
   real(c_double) :: v1(3), w1(3), v2(3), w2(3), nrm(3), v1a(3), w1a(3), v2a(3), w2a(3)
   real(c_double) :: g3(3), a3(3), p3(3), e3(3), gmin, gmax, amax, bound, e, xs(8)
   integer :: k
   character(len=16) :: name
   call get_command_argument(1, length=length)
   allocate (character(len=length) :: path)
   call get_command_argument(1, path)
   call oblique_open(t, path, status)
   write (*, '(I0)') status
   if (status /= OBLQ_OK) stop
   do
      read (*, '(A)', iostat=ios) line
      if (ios /= 0) exit
      read (line, *) cmd
      select case (trim(cmd))
      case ('p')
         read (line, *) cmd, g, a, clamp
         call oblique_p(t, g, a, p, status, clamp=clamp /= 0)
         write (*, '(I0,1X,G0.17)') status, p
      case ('pv')
         read (line, *) cmd, g3(1), a3(1), g3(2), a3(2), g3(3), a3(3)
         call oblique_p(t, g3, a3, p3, st3)
         write (*, '(3(I0,1X,G0.17,:,1X))') (st3(n), p3(n), n = 1, 3)
      case ('pe')
         read (line, *) cmd, g, a, e, clamp
         call oblique_p_e(t, g, a, e, p, status, clamp=clamp /= 0)
         write (*, '(I0,1X,G0.17)') status, p
      case ('pev')
         read (line, *) cmd, (g3(n), a3(n), e3(n), n = 1, 3)
         call oblique_p_e(t, g3, a3, e3, p3, st3)
         write (*, '(3(I0,1X,G0.17,:,1X))') (st3(n), p3(n), n = 1, 3)
      case ('pat')
         ! A point of n values (any number of axes): oblique_p_at.
         read (line, *) cmd, n
         read (line, *) cmd, n, (xs(k), k = 1, n), clamp
         call oblique_p_at(t, xs(1:n), p, status, clamp=clamp /= 0)
         write (*, '(I0,1X,G0.17)') status, p
      case ('axes')
         call oblique_axis_count(t, n, status)
         write (*, '(I0,1X,I0)', advance='no') status, n
         do k = 1, n + 1
            call oblique_axis_name(t, k, name, status)
            write (*, '(1X,I0,":",A)', advance='no') status, trim(name)
         end do
         write (*, '(A)') ''
      case ('erange')
         call oblique_e_n_range(t, gmin, gmax, status)
         write (*, '(I0,2(1X,G0.17))') status, gmin, gmax
      case ('curve')
         read (line, *) cmd, g, a
         call oblique_curve_find(t, g, c, status, rel_tol=a, found_gamma=p)
         write (*, '(I0,1X,G0.17)') status, p
      case ('cp')
         read (line, *) cmd, a, clamp
         call oblique_curve_p(c, a, p, status, clamp=clamp /= 0)
         write (*, '(I0,1X,G0.17)') status, p
      case ('r')
         read (line, *) cmd, m1, r1, k1, m2, r2, k2, g, mu, v1, w1, v2, w2, nrm, clamp
         call oblique_rebound_3d(t, m1, r1, k1, m2, r2, k2, g, mu, v1, w1, v2, w2, nrm, &
                                 v1a, w1a, v2a, w2a, p, e_t, lost, status, &
                                 clamp=clamp /= 0, alpha=alpha)
         write (*, '(I0,16(1X,G0.17))') status, v1a, w1a, v2a, w2a, p, e_t, lost, alpha
      case ('re')
         read (line, *) cmd, m1, r1, k1, m2, r2, k2, g, mu, e, v1, w1, v2, w2, nrm, clamp
         call oblique_rebound_3d(t, m1, r1, k1, m2, r2, k2, g, mu, v1, w1, v2, w2, nrm, &
                                 v1a, w1a, v2a, w2a, p, e_t, lost, status, &
                                 clamp=clamp /= 0, alpha=alpha, e_n=e)
         write (*, '(I0,16(1X,G0.17))') status, v1a, w1a, v2a, w2a, p, e_t, lost, alpha
      case ('rc')
         read (line, *) cmd, m1, r1, k1, m2, r2, k2, mu, v1, w1, v2, w2, nrm, clamp
         call oblique_rebound_3d_curve(c, m1, r1, k1, m2, r2, k2, mu, v1, w1, v2, w2, nrm, &
                                       v1a, w1a, v2a, w2a, p, e_t, lost, status, &
                                       clamp=clamp /= 0, alpha=alpha)
         write (*, '(I0,16(1X,G0.17))') status, v1a, w1a, v2a, w2a, p, e_t, lost, alpha
      case ('g')
         read (line, *) cmd, m1, r1, k1, e1, nu1, m2, r2, k2, e2, nu2
         call oblique_gamma_of(m1, r1, k1, e1, nu1, m2, r2, k2, e2, nu2, g, status)
         write (*, '(I0,1X,G0.17)') status, g
      case ('m')
         read (line, *) cmd, code
         msg = oblique_message(code)
         write (*, '(I0,":",A)') len(msg), msg
      case ('info')
         call oblique_info(t, status, gmin, gmax, amax, bound, surface, n)
         write (*, '(I0,4(1X,G0.17),1X,L1,1X,I0)') status, gmin, gmax, amax, bound, surface, n
      case ('close')
         call oblique_curve_free(c)
         call oblique_close(t)
         write (*, '(A)') 'closed'
      case default
         write (*, '(2A)') 'unknown command ', trim(cmd)
      end select
   end do
   call oblique_curve_free(c)
   call oblique_close(t)
   deallocate (path)
   if (allocated(msg)) deallocate (msg)
end program driver
"#;

/// The table with an e_n axis of [`dissipative_table`] and its export, made once per process
/// (the tests that use it run in parallel).
fn dissipative() -> &'static (Table, PathBuf) {
    static T: OnceLock<(Table, PathBuf)> = OnceLock::new();
    T.get_or_init(|| dissipative_table(&dir().join("dissipative")))
}

/// The normal and sanitized builds (made once).
fn builds() -> &'static [(PathBuf, PathBuf); 2] {
    static B: OnceLock<[(PathBuf, PathBuf); 2]> = OnceLock::new();
    B.get_or_init(|| [build("plain", &[]), build("sanitized", &SANITIZE)])
}

fn f(x: f64) -> String {
    format!("{x:?}")
}

fn v3(v: &[f64; 3]) -> String {
    v.iter().map(|x| f(*x)).collect::<Vec<_>>().join(" ")
}

/// Steel: E = 210 GPa, nu = 0.29.
const STEEL: Elastic = Elastic {
    youngs_modulus: 210e9,
    poisson_ratio: 0.29,
};

#[test]
fn example_prints_the_bits_of_the_rust_library_and_links_only_the_runtimes() {
    let start = std::time::Instant::now();
    let t = table();
    let export = path_str(export_file());
    let (plain, sanitized) = (&builds()[0].0, &builds()[1].0);

    // ldd: the C and Fortran runtimes and the loader, nothing from Rust or HDF5.
    let ldd = Command::new("ldd").arg(plain).output().expect("ldd");
    let libs = String::from_utf8_lossy(&ldd.stdout).to_string();
    for line in libs.lines() {
        let lib = line.trim();
        assert!(
            [
                "linux-vdso",
                "libm.so",
                "libc.so",
                "libgfortran.so",
                "libquadmath.so",
                "libgcc_s.so",
                "ld-linux"
            ]
            .iter()
            .any(|ok| lib.starts_with(ok) || lib.contains(&format!("/{ok}"))),
            "example links {lib}:\n{libs}"
        );
    }
    assert!(libs.contains("libgfortran"), "{libs}");

    let out = run_ok(plain, &[&export], "");
    // The sanitized build prints the same text.
    assert_eq!(run_ok(sanitized, &[&export], ""), out, "sanitized build");
    let lines: Vec<&str> = out.lines().collect();
    let after = |head: &str| -> &[&str] {
        let i = lines
            .iter()
            .position(|l| *l == head)
            .unwrap_or_else(|| panic!("no line {head:?} in:\n{out}"));
        &lines[i + 1..]
    };
    let field = |name: &str| -> Vec<f64> {
        let l = lines
            .iter()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("no line {name} in:\n{out}"));
        nums(l.split_once(' ').expect("values").1)
    };

    // P at the three points: the same bits as Table::p.
    let points: [(f64, f64); 3] = [(1.754, 0.3), (2.0, f64::INFINITY), (1.75, 0.1)];
    for ((g, a), line) in points.iter().zip(after("gamma,alpha,P")) {
        let c: Vec<f64> = line.split(',').map(num).collect();
        assert_eq!(c.len(), 3, "{line}");
        assert_eq!((c[0].to_bits(), c[1].to_bits()), (g.to_bits(), a.to_bits()));
        let want = t.p(*g, *a).expect("inside");
        assert_eq!(
            c[2].to_bits(),
            want.to_bits(),
            "P({g}, {a}): Fortran {}, Rust {want:?}",
            c[2]
        );
    }
    // The curve near 1.75: the exported one, the bits of Curve::p.
    let c: Vec<f64> = after("curve gamma,alpha,P")[0]
        .split(',')
        .map(num)
        .collect();
    assert_eq!(c[0].to_bits(), CURVE_GAMMA.to_bits());
    let want = t
        .curve(CURVE_GAMMA, OutOfDomain::Error)
        .expect("curve")
        .p(0.3)
        .expect("valid");
    assert_eq!(c[2].to_bits(), want.to_bits());

    // The rebound of two steel spheres: Table::rebound_3d_prepared to 1e-12.
    let masses = field("masses");
    let rho_volume = |r: f64| 7850.0 * (4.0 / 3.0) * std::f64::consts::PI * r * r * r;
    assert!(close(masses[0], rho_volume(5e-3), 1e-15, 0.0));
    assert!(close(masses[1], rho_volume(3e-3), 1e-15, 0.0));
    let pair = Pair {
        sphere: Body {
            mass: masses[0],
            radius: 5e-3,
            kappa: 0.4,
        },
        other: Some(Body {
            mass: masses[1],
            radius: 3e-3,
            kappa: 0.4,
        }),
    };
    let contact = Contact::with_materials(STEEL, STEEL, 0.3);
    let prepared = Prepared::new(&pair, &contact).expect("valid pair");
    let s = Incident3 {
        sphere: Motion3 {
            velocity: [1.0, 0.2, -2.0],
            spin: [0.0, 50.0, 0.0],
        },
        other: Motion3 {
            velocity: [0.0, 0.0, 1.0],
            spin: [0.0, 0.0, 10.0],
        },
        normal: [0.0, 0.0, -1.0],
    };
    let a = t.rebound_3d(&pair, &contact, &s).expect("valid impact");
    let b = &a.rebound;
    let o = b.other.expect("sphere 2");
    assert!(close(field("gamma")[0], prepared.gamma(), 1e-12, 0.0));
    assert!(close(field("alpha")[0], a.alpha, 1e-12, 0.0));
    for (name, want) in [
        ("v1", b.sphere.velocity),
        ("w1", b.sphere.spin),
        ("v2", o.velocity),
        ("w2", o.spin),
    ] {
        let got = field(name);
        let scale = want.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for k in 0..3 {
            assert!(
                close(got[k], want[k], 1e-12, scale),
                "{name}[{k}]: Fortran {}, Rust {:?}",
                got[k],
                want[k]
            );
        }
    }
    for (name, want) in [("P", b.p), ("e_t", b.e_t), ("energy_lost", b.energy_lost)] {
        let got = field(name)[0];
        assert!(
            close(got, want, 1e-12, 0.0),
            "{name}: Fortran {got}, Rust {want:?}"
        );
    }
    assert!(b.p.abs() < 1.0 && b.energy_lost > 0.0);

    // The error: gamma = -1 with OBLQ_E_GAMMA (7) and its message.
    let codes = header_codes();
    let messages = header_messages(&codes);
    let e = codes["OBLQ_E_GAMMA"];
    assert_eq!(e, 7);
    let want = format!("error at gamma=-1: status {e}: {}", messages[&e]);
    assert!(
        lines.contains(&want.as_str()),
        "no line {want:?} in:\n{out}"
    );

    // A file that cannot be opened: error stop (non-zero), with the message.
    let fifo = dir().join("export.fifo");
    if !fifo.exists() {
        let r = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
        assert!(r.success(), "mkfifo");
    }
    for (build, what) in [(plain, "plain"), (sanitized, "sanitized")] {
        for (file, status, text) in [
            (
                path_str(&dir().join("missing.oblq")),
                101,
                "cannot read the export file",
            ),
            (path_str(&root("tables/full.h5")), 3, "not an export"),
            // Not regular files: refused before they are opened (a FIFO would block, a device
            // be read until memory runs out).
            (
                "/dev/zero".to_string(),
                103,
                "the export path is not a regular file",
            ),
            (
                path_str(&fifo),
                103,
                "the export path is not a regular file",
            ),
            (
                path_str(dir()),
                103,
                "the export path is not a regular file",
            ),
        ] {
            let r = run(build, &[&file], "");
            let err = String::from_utf8_lossy(&r.stderr);
            assert!(!r.status.success(), "{what} {file}: {}", r.status);
            assert!(
                err.contains(&format!("status {status}: {text}")),
                "{what} {file}: {err}"
            );
        }
        let r = run(build, &[], "");
        assert!(!r.status.success() && String::from_utf8_lossy(&r.stderr).contains("usage"));
    }
    eprintln!("example: {:.1} s", start.elapsed().as_secs_f64());
}

#[test]
fn module_status_codes_and_messages_are_the_headers() {
    let codes = header_codes();
    assert!(codes.len() >= 24, "{codes:?}");
    let module = std::fs::read_to_string(root("fortran/oblique_eval.f90")).expect("module");
    let mut declared = BTreeMap::new();
    for line in module.lines() {
        if let Some((_, rest)) = line.split_once("parameter, public :: OBLQ_") {
            let (name, value) = rest.split_once('=').expect("a value");
            let value = value.split('!').next().expect("value").trim();
            declared.insert(
                format!("OBLQ_{}", name.trim()),
                value.parse::<i32>().expect("int"),
            );
        }
    }
    for (name, value) in &codes {
        assert_eq!(declared.get(name), Some(value), "{name} in the module");
    }
    // Deprecated names: `#define OBLQ_E_OLD OBLQ_E_NEW` in the header, the same value here.
    let header = std::fs::read_to_string(root("include/oblique_eval.h")).expect("header");
    let aliases: BTreeMap<&str, &str> = header
        .lines()
        .filter_map(|l| l.strip_prefix("#define OBLQ_E_"))
        .filter_map(|l| l.split_once(' '))
        .filter(|(_, to)| to.trim().starts_with("OBLQ_E_"))
        .map(|(from, to)| (from, to.trim()))
        .collect();
    for (name, value) in &declared {
        let name = match aliases.get(name.trim_start_matches("OBLQ_E_")) {
            Some(to) => to.to_string(),
            None => name.clone(),
        };
        assert_eq!(codes.get(&name), Some(value), "{name} in the header");
    }
    // Every message, copied whole into a Fortran string.
    let messages = header_messages(&codes);
    assert_eq!(messages.len(), codes.len(), "a message per code");
    let mut input: String = messages.keys().map(|c| format!("m {c}\n")).collect();
    input += "m 101\nm 102\nm 999\nm -1\n";
    for (_, driver) in builds() {
        let out = run_ok(driver, &[&path_str(export_file())], &input);
        let lines: Vec<&str> = out.lines().skip(1).collect();
        let mut want: Vec<String> = messages.values().cloned().collect();
        want.push(
            "cannot read the export file: it does not exist, is not readable, or is a directory"
                .into(),
        );
        want.push("out of memory reading the export".into());
        want.push("unknown status code".into());
        want.push("unknown status code".into());
        assert_eq!(lines.len(), want.len(), "{out}");
        for (line, text) in lines.iter().zip(&want) {
            assert_eq!(*line, format!("{}:{text}", text.len()));
        }
    }
}

#[test]
fn module_answers_points_curves_and_rebounds_like_the_rust_library() {
    let start = std::time::Instant::now();
    let t = table();
    let s = t.surface();
    let export = path_str(export_file());
    let mut r = SplitMix(11);
    let mut input = String::from("info\n");
    // P over and beyond the domain, with and without clamping; invalid arguments.
    let mut pts = Vec::new();
    for i in 0..4000 {
        let g = 0.5 * s.gamma_min() + (1.2 * s.gamma_max() - 0.5 * s.gamma_min()) * r.uniform();
        let a = match i % 40 {
            0 => f64::INFINITY,
            1 => 0.0,
            _ => 3.0 * r.uniform() * r.uniform(),
        };
        pts.push((g, a, i % 2));
    }
    pts.extend([
        (f64::NAN, 0.5, 0),
        (-1.0, 0.5, 1),
        (f64::INFINITY, 0.5, 0),
        (0.0, 0.5, 0),
        (1.5, -0.1, 0),
        (1.5, f64::NAN, 1),
    ]);
    for (g, a, c) in &pts {
        input += &format!("p {} {} {c}\n", f(*g), f(*a));
    }
    input += "pv 1.754 0.3 -1 0.3 2 inf\n";
    // The curve: exact, within a tolerance, missing; then P(alpha) of the kept curve.
    input += &format!("curve {} 0\n", f(CURVE_GAMMA));
    input += "curve 1.75 1e-3\ncurve 2.9 1e-3\ncurve 1.75 1e-3\n";
    let alphas: Vec<f64> = (0..2000)
        .map(|k| match k % 50 {
            0 => f64::INFINITY,
            _ => 4.0 * r.uniform() * r.uniform(),
        })
        .collect();
    for a in &alphas {
        input += &format!("cp {} 0\n", f(*a));
    }
    input += "cp -1 0\n";
    // Rebounds: spheres on walls and on spheres, P from the table and from the curve.
    let mut cases = Vec::new();
    while cases.len() < 400 {
        let wall = cases.len() % 3 == 0;
        let b1 = random_body(&mut r);
        let b2 = random_body(&mut r);
        let mu = 0.05 + r.uniform();
        if let Some(inc) = random_impact(&mut r, wall) {
            let gamma = s.gamma_min() + (s.gamma_max() - s.gamma_min()) * r.uniform();
            cases.push((wall, b1, b2, gamma, mu, inc, cases.len() % 2 == 1));
        }
    }
    let motion = |inc: &Incident3| {
        format!(
            "{} {} {} {} {}",
            v3(&inc.sphere.velocity),
            v3(&inc.sphere.spin),
            v3(&inc.other.velocity),
            v3(&inc.other.spin),
            v3(&inc.normal)
        )
    };
    for (wall, b1, b2, gamma, mu, inc, use_curve) in &cases {
        let m2 = if *wall { 0.0 } else { b2.mass };
        let bodies = format!(
            "{} {} {} {} {} {}",
            f(b1.mass),
            f(b1.radius),
            f(b1.kappa),
            f(m2),
            f(b2.radius),
            f(b2.kappa)
        );
        input += &if *use_curve {
            format!("rc {bodies} {} {} 0\n", f(*mu), motion(inc))
        } else {
            format!("r {bodies} {} {} {} 0\n", f(*gamma), f(*mu), motion(inc))
        };
    }
    // Refusals of rebounds: a wall given a motion, a bad mass, a zero normal, no approach, a
    // bad friction, gamma outside the domain (and clamped).
    let steel_sphere = "0.0041 0.005 0.4";
    let still = "0 0 0 0 0 0";
    let refusals = [
        (
            format!("r {steel_sphere} 0 1 1 1.7 0.3 0 0 1 0 0 0 1 0 0 0 0 0 0 0 1 0"),
            22,
        ),
        (
            format!("r -1 0.005 0.4 0 1 1 1.7 0.3 0 0 1 0 0 0 {still} 0 0 1 0"),
            13,
        ),
        (
            format!("r {steel_sphere} 0 1 1 1.7 0.3 0 0 1 0 0 0 {still} 0 0 0 0"),
            20,
        ),
        (
            format!("r {steel_sphere} 0 1 1 1.7 0.3 0 0 -1 0 0 0 {still} 0 0 1 0"),
            21,
        ),
        (
            format!("r {steel_sphere} 0 1 1 1.7 -0.3 0 0 1 0 0 0 {still} 0 0 1 0"),
            16,
        ),
        (
            format!("r {steel_sphere} 0 1 1 9 0.3 1 0 1 0 0 0 {still} 0 0 1 0"),
            9,
        ),
        (
            format!("r {steel_sphere} 0 1 1 9 0.3 1 0 1 0 0 0 {still} 0 0 1 1"),
            0,
        ),
    ];
    for (line, _) in &refusals {
        input += &format!("{line}\n");
    }
    // gamma of materials: steel on steel (spheres) and steel on a rigid wall; a bad ratio.
    input += "g 0.0041 0.005 0.4 2.1e11 0.29 0.00089 0.003 0.4 2.1e11 0.29\n\
               g 0.0041 0.005 0.4 2.1e11 0.29 0 1 1 inf 0\n\
               g 0.0041 0.005 0.4 2.1e11 0.7 0 1 1 inf 0\n";
    input += "close\np 1.5 0.3 0\ninfo\n";

    let mut outputs = Vec::new();
    for (_, driver) in builds() {
        outputs.push(run_ok(driver, &[&export], &input));
    }
    assert_eq!(
        outputs[0], outputs[1],
        "the sanitized driver answers the same"
    );
    let out = &outputs[0];
    let mut lines = out.lines();
    let mut next = || lines.next().expect("an answer per line");
    assert_eq!(next(), "0", "open");
    let info = next();
    let v: Vec<&str> = info.split_whitespace().collect();
    assert_eq!(v[0], "0");
    assert_eq!(num(v[1]).to_bits(), s.gamma_min().to_bits());
    assert_eq!(num(v[2]).to_bits(), s.gamma_max().to_bits());
    assert_eq!(num(v[4]).to_bits(), t.error_bound().to_bits(), "{info}");
    assert_eq!(&v[5..], ["T", "1"], "{info}");
    let mut refused = 0;
    for (g, a, c) in &pts {
        let line = next();
        let (st, p) = line.split_once(' ').expect("status P");
        let outside = if *c == 1 {
            OutOfDomain::Clamp
        } else {
            OutOfDomain::Error
        };
        match t.p_with(*g, *a, outside) {
            Ok(want) => {
                assert_eq!(st, "0", "gamma {g:?} alpha {a:?}: {line}");
                assert_eq!(num(p).to_bits(), want.to_bits(), "gamma {g:?} alpha {a:?}");
            }
            Err(_) => {
                refused += 1;
                assert!(num(p).is_nan(), "{line}");
                let want = if !(g.is_finite() && *g > 0.0) {
                    "7"
                } else if a.is_nan() || *a < 0.0 {
                    "8"
                } else {
                    "9"
                };
                assert_eq!(st, want, "gamma {g:?} alpha {a:?} clamp {c}: {line}");
            }
        }
    }
    assert!(refused > 200, "{refused} refused");
    let pv = nums(next());
    assert_eq!(pv[0], 0.0);
    assert_eq!(pv[1].to_bits(), t.p(1.754, 0.3).expect("inside").to_bits());
    assert_eq!((pv[2], pv[3].is_nan()), (7.0, true));
    assert_eq!(
        pv[5].to_bits(),
        t.p(2.0, f64::INFINITY).expect("inside").to_bits()
    );
    for want in ["0", "0", "12", "0"] {
        let line = next();
        let (st, g) = line.split_once(' ').expect("status gamma");
        assert_eq!(st, want, "{line}");
        if st == "0" {
            assert_eq!(num(g).to_bits(), CURVE_GAMMA.to_bits());
        }
    }
    let curve = t.curve(CURVE_GAMMA, OutOfDomain::Error).expect("curve");
    for a in &alphas {
        let line = next();
        let (st, p) = line.split_once(' ').expect("status P");
        assert_eq!(st, "0", "{line}");
        let want = curve.p(*a).expect("valid");
        assert_eq!(num(p).to_bits(), want.to_bits(), "curve alpha {a:?}");
    }
    assert!(next().starts_with("8 "));
    for (case, (wall, b1, b2, gamma, mu, inc, use_curve)) in cases.iter().enumerate() {
        let line = next();
        let c = nums(line);
        assert_eq!(c[0], 0.0, "case {case}: {line}");
        let pair = Pair {
            sphere: *b1,
            other: (!wall).then_some(*b2),
        };
        let g = if *use_curve { CURVE_GAMMA } else { *gamma };
        let prepared = Prepared::new(&pair, &Contact::with_gamma(g, *mu)).expect("valid pair");
        let a = if *use_curve {
            t.rebound_3d_curve(&prepared, &curve, inc)
        } else {
            t.rebound_3d_prepared(&prepared, inc)
        }
        .expect("valid impact");
        let want = &rebound_fields(&a)[..16]; // the driver prints no |u0|
        for (k, (x, y)) in c[1..].iter().zip(want).enumerate() {
            // Velocities and spins relative to the incident speeds, the rest to themselves.
            let scale = if k < 12 { 1e-3 + y.abs() } else { 0.0 };
            assert!(
                close(*x, *y, 1e-12, scale),
                "case {case} field {k}: Fortran {x:?}, Rust {y:?}"
            );
        }
    }
    for (input, want) in &refusals {
        let line = next();
        let c = nums(line);
        assert_eq!(c[0], f64::from(*want), "{input}: {line}");
        if *want != 0 {
            assert!(c[1..].iter().all(|x| x.is_nan()), "{line}");
        }
    }
    // gamma of materials against Pair::gamma_from_materials.
    let b1 = Body {
        mass: 0.0041,
        radius: 0.005,
        kappa: 0.4,
    };
    let b2 = Body {
        mass: 0.00089,
        radius: 0.003,
        kappa: 0.4,
    };
    let spheres = Pair {
        sphere: b1,
        other: Some(b2),
    };
    let wall = Pair {
        sphere: b1,
        other: None,
    };
    for (pair, other) in [(spheres, STEEL), (wall, Elastic::RIGID)] {
        let want = pair.gamma_from_materials(&STEEL, &other).expect("valid");
        let line = next();
        let (st, g) = line.split_once(' ').expect("status gamma");
        assert_eq!(st, "0");
        assert!(close(num(g), want, 1e-15, 0.0), "{line} vs {want:?}");
    }
    assert!(next().starts_with("18 "), "Poisson ratio 0.7");
    assert_eq!(next(), "closed");
    assert!(next().starts_with("1 "), "a closed table");
    assert!(next().starts_with("1 "), "info of a closed table");
    eprintln!("driver: {:.1} s", start.elapsed().as_secs_f64());
}

/// The driver's answers `STATUS P` to `pe` lines of `pts` (clamping at odd indexes), read by
/// `next`, against `Table::p_e_with`: the bits of `P`, or the status Rust's error maps to with
/// `P` NaN. Returns the number answered and the refusals per status.
fn pe_lines_against_rust<'a>(
    t: &Table,
    pts: &[(f64, f64, f64)],
    next: &mut impl FnMut() -> &'a str,
) -> (usize, [usize; 25]) {
    let (mut answered, mut refused) = (0, [0usize; 25]);
    for (i, (g, a, e)) in pts.iter().enumerate() {
        let line = next();
        let (st, p) = line.split_once(' ').expect("status P");
        let outside = if i % 2 == 1 {
            OutOfDomain::Clamp
        } else {
            OutOfDomain::Error
        };
        match t.p_e_with(*g, *a, *e, outside) {
            Ok(want) => {
                answered += 1;
                assert_eq!(st, "0", "({g:?}, {a:?}, {e:?}): {line}");
                assert_eq!(num(p).to_bits(), want.to_bits(), "({g:?}, {a:?}, {e:?})");
            }
            Err(err) => {
                let code = status_of(&err, *g, *a);
                refused[code as usize] += 1;
                assert!(num(p).is_nan(), "{line}");
                assert_eq!(st, code.to_string(), "({g:?}, {a:?}, {e:?})");
            }
        }
    }
    (answered, refused)
}

/// The module on a table with an `e_n` axis (export layout version 2): `oblique_p_e` (scalar and
/// elemental) gives the bits of `Table::p_e` and its refusals, `oblique_p` the `e_n = 1` slice,
/// `oblique_e_n_range` the range; and an elastic export answers `e_n = 1` only.
#[test]
fn module_answers_p_of_a_table_with_an_e_n_axis() {
    let start = std::time::Instant::now();
    let (t, export) = dissipative();
    let s = t.surface();
    let pts = points_e(
        20_000,
        29,
        (0.8 * s.gamma_min(), 1.1 * s.gamma_max()),
        (0.65, 1.02),
    );
    let mut input = String::from("erange\n");
    for (i, (g, a, e)) in pts.iter().enumerate() {
        input += &format!("pe {} {} {} {}\n", f(*g), f(*a), f(*e), i % 2);
    }
    input += "pev 1.45 0.3 0.8 1.45 0.3 0.5 1.45 inf 1\n";
    input += "pe 1.45 0.3 nan 0\np 1.45 0.3 0\n";
    let plain = &builds()[0].1;
    let out = run_ok(plain, &[&path_str(export)], &input);
    let mut lines = out.lines();
    let mut next = || lines.next().expect("an answer per line");
    assert_eq!(next(), "0", "open");
    let r = nums(next());
    assert_eq!(r, [0.0, 0.7, 1.0]);
    let (_, refused) = pe_lines_against_rust(t, &pts, &mut next);
    let refused: usize = refused.iter().sum();
    assert!(refused > 2000, "{refused} refused");
    let pv = nums(next());
    assert_eq!(pv[0], 0.0);
    assert_eq!(
        pv[1].to_bits(),
        t.p_e(1.45, 0.3, 0.8).expect("inside").to_bits()
    );
    assert_eq!((pv[2], pv[3].is_nan()), (24.0, true));
    assert_eq!(
        pv[5].to_bits(),
        t.p_e(1.45, f64::INFINITY, 1.0).expect("inside").to_bits()
    );
    assert!(next().starts_with("24 "), "e_n = NaN");
    let p = nums(next());
    assert_eq!(p[1].to_bits(), t.p(1.45, 0.3).expect("inside").to_bits());
    // An elastic export: the range 1, 1; e_n = 1 answers oblique_p's bits, e_n < 1 refused.
    let out = run_ok(
        plain,
        &[&path_str(export_file())],
        "erange\npe 1.754 0.3 1 0\npe 1.754 0.3 0.9 0\n",
    );
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[1], "0 1.0000000000000000 1.0000000000000000");
    let p = nums(lines[2]);
    assert_eq!(
        p[1].to_bits(),
        table().p(1.754, 0.3).expect("inside").to_bits()
    );
    assert!(lines[3].starts_with("24 "), "{out}");
    eprintln!(
        "e_n table: {} points through oblique_p_e ({:.1} s)",
        pts.len(),
        start.elapsed().as_secs_f64()
    );
}

/// `oblique_p_at` of the module gives the bits of `Table::p_at_with` (itself those of
/// `oblique_p` / `oblique_p_e`: `Table::p`, `Table::p_e`) on the export with an `e_n` axis and on
/// an elastic one, with its refusals' codes; a point of another size is `OBLQ_E_AXES` (28);
/// `oblique_axis_count` and `oblique_axis_name` list `Table::axes`.
#[test]
fn module_p_at_gives_the_bits_of_the_rust_point_query() {
    let (t, export) = dissipative();
    let elastic = (table(), export_file().to_path_buf());
    for (t, export) in [(t, export), (elastic.0, &elastic.1)] {
        let s = t.surface();
        let e = t.restitution().unwrap_or((1.0, 1.0));
        let pts = points_e(5_000, 52, (0.8 * s.gamma_min(), 1.1 * s.gamma_max()), e);
        let n = t.axes().len();
        let mut input = String::from("axes\n");
        for (i, (g, a, e)) in pts.iter().enumerate() {
            let x = [*g, *a, *e];
            let v: Vec<String> = x[..n].iter().map(|v| f(*v)).collect();
            input += &format!("pat {n} {} {}\n", v.join(" "), i % 2);
        }
        for k in [n + 1, n - 1] {
            let v: Vec<String> = [1.5, 0.3, 0.9, 1.0][..k].iter().map(|v| f(*v)).collect();
            input += &format!("pat {k} {} 0\n", v.join(" "));
        }
        let out = run_ok(&builds()[0].1, &[&path_str(export)], &input);
        let mut lines = out.lines();
        assert_eq!(lines.next(), Some("0"), "open");
        let names: Vec<String> = t.axes().iter().map(|a| format!("0:{a}")).collect();
        assert_eq!(
            lines.next(),
            Some(format!("0 {n} {} 28:", names.join(" ")).as_str())
        );
        for (i, (g, a, e)) in pts.iter().enumerate() {
            let line = lines.next().expect("an answer per line");
            let (st, p) = line.split_once(' ').expect("status P");
            let outside = if i % 2 == 1 {
                OutOfDomain::Clamp
            } else {
                OutOfDomain::Error
            };
            match t.p_at_with(&[*g, *a, *e][..n], outside) {
                Ok(want) => {
                    assert_eq!(st, "0", "({g:?}, {a:?}, {e:?}): {line}");
                    assert_eq!(num(p).to_bits(), want.to_bits(), "({g:?}, {a:?}, {e:?})");
                }
                Err(err) => {
                    assert_eq!(st, status_of(&err, *g, *a).to_string(), "{line}: {err}");
                    assert!(num(p).is_nan(), "{line}");
                }
            }
        }
        for _ in 0..2 {
            let line = lines.next().expect("wrong size");
            assert!(line.starts_with("28 "), "{line}");
        }
    }
}

#[test]
fn module_rebounds_at_e_n_give_the_bits_of_the_rust_library() {
    let (t, export) = dissipative();
    let mut r = SplitMix(43);
    let mut cases = Vec::new();
    for case in 0..12 {
        let wall = case % 3 == 0;
        let pair = Pair {
            sphere: random_body(&mut r),
            other: (!wall).then(|| random_body(&mut r)),
        };
        let (gamma, mu) = (1.0 + 0.55 * r.uniform(), 0.05 + r.uniform());
        let e_n = if case == 0 {
            1.0
        } else {
            0.7 + 0.3 * r.uniform()
        };
        for _ in 0..50 {
            if let Some(s) = random_impact(&mut r, wall) {
                cases.push((pair, gamma, mu, e_n, s));
            }
        }
    }
    let line = |pair: &Pair, gamma: f64, mu: f64, e_n: f64, s: &Incident3| {
        let b2 = pair.other.unwrap_or(pair.sphere);
        let m2 = if pair.other.is_none() { 0.0 } else { b2.mass };
        let b1 = pair.sphere;
        format!(
            "re {} {} {} {} {} {} {} {} {} {} {} {} {} {} 0\n",
            f(b1.mass),
            f(b1.radius),
            f(b1.kappa),
            f(m2),
            f(b2.radius),
            f(b2.kappa),
            f(gamma),
            f(mu),
            f(e_n),
            v3(&s.sphere.velocity),
            v3(&s.sphere.spin),
            v3(&s.other.velocity),
            v3(&s.other.spin),
            v3(&s.normal)
        )
    };
    let mut input: String = cases
        .iter()
        .map(|(p, g, mu, e, s)| line(p, *g, *mu, *e, s))
        .collect();
    // Refusals: e_n outside [0, 1] (the pair) and outside the table's range [0.7, 1].
    let (p0, g0, mu0, _, s0) = cases[1];
    for e_n in [1.5, -0.5, f64::NAN, 0.6] {
        input += &line(&p0, g0, mu0, e_n, &s0);
    }
    let plain = &builds()[0].1;
    let out = run_ok(plain, &[&path_str(export)], &input);
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("0"), "open");
    let (mut compared, mut refused) = (0, 0);
    for case in &cases {
        let c = nums(lines.next().expect("an answer"));
        if rebound_matches(t, &c, case, 10.0) {
            compared += 1;
        } else {
            refused += 1;
        }
    }
    for _ in 0..4 {
        let c = nums(lines.next().expect("an answer"));
        assert_eq!(c[0], 24.0);
        assert!(c[1..].iter().all(|x| x.is_nan()));
    }
    // An elastic export answers e_n = 1 only.
    let out = run_ok(
        plain,
        &[&path_str(export_file())],
        &line(&p0, 1.6, mu0, 0.9, &s0),
    );
    assert!(
        out.lines().nth(1).expect("an answer").starts_with("24 "),
        "{out}"
    );
    assert!(compared > 250, "{compared} compared, {refused} refused");
    eprintln!("Fortran rebounds at e_n: {compared} C == Rust bit for bit, {refused} refused alike");
}

/// γ of the shipped table of one pair, `tables/dissipative-pair.h5`.
const PAIR_GAMMA: f64 = 1.749_785_860_077_429_9;

/// The module on the table of one pair (export layout version 3): `oblique_info` gives its single
/// γ as both ends of the domain, `oblique_p_e` (scalar and elemental) and `oblique_p` the bits of
/// `Table::p_e` at that γ and at γ within 5e-10 (relative), and its refusal of another γ above
/// the line (`OBLQ_E_GAMMA_DOMAIN`, or clamped); rebounds at the pair's γ (`e_n = ...`) the bits
/// of `Table::rebound_3d`, and the same refusals.
#[test]
fn module_answers_the_table_of_one_pair() {
    let start = std::time::Instant::now();
    let t = Table::open(root("tables/dissipative-pair.h5")).expect("shipped table");
    let export = dir().join("pair.oblq");
    std::fs::write(
        &export,
        export::export(t.surface(), t.error_bound(), true, &[]),
    )
    .expect("write export");
    let near = [
        PAIR_GAMMA,
        PAIR_GAMMA,
        PAIR_GAMMA * (1.0 + 5e-10),
        PAIR_GAMMA * (1.0 - 5e-10),
        PAIR_GAMMA * (1.0 + 1e-6),
        PAIR_GAMMA * (1.0 - 2e-9),
        2.5,
    ];
    let pts: Vec<(f64, f64, f64)> = points_e(20_000, 71, (PAIR_GAMMA, PAIR_GAMMA), (0.45, 1.0))
        .into_iter()
        .enumerate()
        .map(|(i, (_, a, e))| (near[i % near.len()], a, e))
        .collect();
    let mut input = String::from("info\nerange\n");
    for (i, (g, a, e)) in pts.iter().enumerate() {
        input += &format!("pe {} {} {} {}\n", f(*g), f(*a), f(*e), i % 2);
    }
    let g2 = PAIR_GAMMA * (1.0 + 1e-6);
    input += &format!("pev {PAIR_GAMMA:?} 0.3 0.8 {g2:?} 0.3 0.8 {PAIR_GAMMA:?} inf 0.5\n");
    input += &format!("p {PAIR_GAMMA:?} 0.3 0\np {g2:?} 0.3 0\n");
    // Rebounds at the pair's γ, at γ within 3e-10 of it and 1e-6 off it.
    let mut r = SplitMix(73);
    let mut cases = Vec::new();
    for case in 0..9 {
        let wall = case % 3 == 0;
        let pair = Pair {
            sphere: random_body(&mut r),
            other: (!wall).then(|| random_body(&mut r)),
        };
        let gamma = match case {
            4 => PAIR_GAMMA * (1.0 + 1e-6),
            7 => PAIR_GAMMA * (1.0 + 3e-10),
            _ => PAIR_GAMMA,
        };
        let (mu, e_n) = (0.05 + r.uniform(), 0.5 + 0.5 * r.uniform());
        for _ in 0..40 {
            if let Some(s) = random_impact(&mut r, wall) {
                cases.push((pair, gamma, mu, e_n, s));
            }
        }
    }
    for (pair, gamma, mu, e_n, s) in &cases {
        let b2 = pair.other.unwrap_or(pair.sphere);
        let m2 = if pair.other.is_none() { 0.0 } else { b2.mass };
        let b1 = pair.sphere;
        input += &format!(
            "re {} {} {} {} {} {} {} {} {} {} {} {} {} {} 0\n",
            f(b1.mass),
            f(b1.radius),
            f(b1.kappa),
            f(m2),
            f(b2.radius),
            f(b2.kappa),
            f(*gamma),
            f(*mu),
            f(*e_n),
            v3(&s.sphere.velocity),
            v3(&s.sphere.spin),
            v3(&s.other.velocity),
            v3(&s.other.spin),
            v3(&s.normal)
        );
    }
    let plain = &builds()[0].1;
    let out = run_ok(plain, &[&path_str(&export)], &input);
    let mut lines = out.lines();
    let mut next = || lines.next().expect("an answer per line");
    assert_eq!(next(), "0", "open");
    let info = nums(next().replace(" T ", " 1 ").as_str());
    assert_eq!(info[0], 0.0);
    assert_eq!(
        (info[1], info[2]),
        (PAIR_GAMMA, PAIR_GAMMA),
        "a single gamma"
    );
    assert_eq!(nums(next()), [0.0, 0.5, 1.0]);
    let (answered, refused) = pe_lines_against_rust(&t, &pts, &mut next);
    assert!(
        answered > 10_000 && refused[9] > 2000 && refused[24] > 500,
        "{refused:?}"
    );
    let pv = nums(next());
    assert_eq!(
        pv[1].to_bits(),
        t.p_e(PAIR_GAMMA, 0.3, 0.8).expect("inside").to_bits()
    );
    assert_eq!((pv[2], pv[3].is_nan()), (9.0, true), "another gamma");
    assert_eq!(
        pv[5].to_bits(),
        t.p_e(PAIR_GAMMA, f64::INFINITY, 0.5)
            .expect("inside")
            .to_bits()
    );
    let p = nums(next());
    assert_eq!(
        p[1].to_bits(),
        t.p(PAIR_GAMMA, 0.3).expect("inside").to_bits()
    );
    assert!(next().starts_with("9 "), "oblique_p at another gamma");
    let (mut compared, mut refused) = (0, 0);
    for case in &cases {
        let c = nums(next());
        if rebound_matches(&t, &c, case, 9.0) {
            compared += 1;
        } else {
            refused += 1;
        }
    }
    assert!(
        compared > 150 && refused >= 5,
        "{compared} compared, {refused} refused"
    );
    eprintln!(
        "table of one pair: {} points through oblique_p_e, {compared} rebounds Fortran == Rust \
         bit for bit, {refused} refused alike ({:.1} s)",
        pts.len(),
        start.elapsed().as_secs_f64()
    );
}

/// The module on an elastic table whose split cells halve only the axes they need (export
/// layout version 6, with a warp): `oblique_p` gives the bits of `Table::p_with` and its
/// refusals at a few hundred points, a curve of the export the bits of `Curve::p`, and a
/// damaged mask (on a leaf) is refused at open with `OBLQ_E_CORRUPT` (6).
#[test]
fn module_answers_an_elastic_table_with_split_masks() {
    let (t, export, _) = anisotropic_table(&dir().join("anisotropic"));
    let s = t.surface();
    let mut r = SplitMix(61);
    let pts: Vec<(f64, f64)> = (0..400)
        .map(|_| {
            let g =
                0.9 * s.gamma_min() + (1.05 * s.gamma_max() - 0.9 * s.gamma_min()) * r.uniform();
            (g, 3.0 * r.uniform() * r.uniform())
        })
        .collect();
    let gamma = ANISOTROPIC_GAMMAS[2];
    let alphas: Vec<f64> = (0..100).map(|_| 4.0 * r.uniform() * r.uniform()).collect();
    let mut input = String::new();
    for (i, (g, a)) in pts.iter().enumerate() {
        input += &format!("p {} {} {}\n", f(*g), f(*a), i % 2);
    }
    input += &format!("curve {} 0\n", f(gamma));
    for a in &alphas {
        input += &format!("cp {} 0\n", f(*a));
    }
    let out = run_ok(&builds()[0].1, &[&path_str(&export)], &input);
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("0"), "open");
    let (mut answered, mut refused) = (0, 0);
    for (i, (g, a)) in pts.iter().enumerate() {
        let line = lines.next().expect("an answer per point");
        let (st, p) = line.split_once(' ').expect("status P");
        let outside = if i % 2 == 1 {
            OutOfDomain::Clamp
        } else {
            OutOfDomain::Error
        };
        match t.p_with(*g, *a, outside) {
            Ok(want) => {
                answered += 1;
                assert_eq!(st, "0", "({g:?}, {a:?}): {line}");
                assert_eq!(num(p).to_bits(), want.to_bits(), "({g:?}, {a:?})");
            }
            Err(err) => {
                refused += 1;
                assert_eq!(st, status_of(&err, *g, *a).to_string(), "{line}: {err}");
            }
        }
    }
    assert!(
        answered > 300 && refused > 5,
        "{answered} answered, {refused} refused"
    );
    assert!(lines.next().expect("curve").starts_with("0 "), "the curve");
    let curve = t.curve(gamma, OutOfDomain::Error).expect("curve");
    for a in &alphas {
        let line = lines.next().expect("an answer per alpha");
        let (st, p) = line.split_once(' ').expect("status P");
        assert_eq!(st, "0", "{line}");
        let want = curve.p(*a).expect("valid");
        assert_eq!(num(p).to_bits(), want.to_bits(), "curve alpha {a:?}");
    }
    // A mask on a leaf of the first patch with masks, resealed: refused at open.
    let mut b = std::fs::read(&export).expect("export");
    let u64_at = |b: &[u8], at: usize| u64::from_le_bytes(b[at..at + 8].try_into().expect("8"));
    let dir_at = u64_at(&b, 72) as usize;
    let r = (0..3)
        .map(|k| dir_at + 160 * k)
        .find(|&r| u64_at(&b, r + 144) != 0)
        .expect("a patch with masks");
    let (tree_at, masks) = (u64_at(&b, r + 48) as usize, u64_at(&b, r + 144) as usize);
    let leaf = (0..)
        .find(|&i: &usize| i32::from_le_bytes(b[tree_at + 4 * i..][..4].try_into().expect("4")) < 0)
        .expect("a leaf");
    b[masks + leaf] = 1;
    let bad = dir().join("anisotropic-bad-mask.oblq");
    std::fs::write(&bad, sealed(b)).expect("write");
    assert_eq!(run_ok(&builds()[0].1, &[&path_str(&bad)], "").trim(), "6");
}
