//! Measured points the suites publish as numbers: Kharaz, Gorham & Salman (2001), alumina
//! spheres (d = 5 mm) on a soda-lime glass anvil at 3.9 m/s, as digitised by the projects that
//! ship them. Every list names its file; the angles are the incidence from the normal (°).

/// One measured quantity against the incidence angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Series {
    /// The CSV column of the test it compares with (`e_t`, `omega_rad_s`, …).
    pub column: &'static str,
    /// `(incidence angle from the normal in °, value)`.
    pub points: &'static [(f64, f64)],
    /// Where these numbers are published.
    pub source: &'static str,
}

/// The measured points of one experiment, in one suite's conventions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The experiment.
    pub experiment: &'static str,
    /// The measured quantities.
    pub series: &'static [Series],
}

const KHARAZ: &str = "Kharaz, Gorham & Salman (2001), Powder Technol. 120:281-291";

/// Kharaz et al. as shipped by MFIX (tests/dem/DEM05/AUTOTEST/POST_COEFF.dat, POST_OMEGA.dat,
/// POST_ALPHA.dat, the "Experiment" blocks; MFIX 21.3): `e_t`, `|ω'|`, the centre's rebound
/// angle.
pub const KHARAZ_MFIX: Measured = Measured {
    experiment: KHARAZ,
    series: &[
        Series {
            column: "e_t",
            points: &[
                (2.0275, 0.7938),
                (3.9282, 0.7450),
                (9.6304, 0.6728),
                (20.0845, 0.5964),
                (30.2218, 0.6883),
                (39.3031, 0.7719),
                (49.5459, 0.8469),
                (59.8416, 0.9019),
            ],
            source: "MFIX tests/dem/DEM05/AUTOTEST/POST_COEFF.dat (Experiment)",
        },
        Series {
            column: "omega_abs_rad_s",
            points: &[
                (6.0025, 135.5703),
                (10.9840, 264.5493),
                (21.1931, 577.0096),
                (31.0947, 612.6481),
                (39.0283, 595.4843),
                (50.2214, 452.9444),
                (60.2460, 381.3185),
            ],
            source: "MFIX tests/dem/DEM05/AUTOTEST/POST_OMEGA.dat (Experiment; |omega|)",
        },
        Series {
            column: "rebound_angle_deg",
            points: &[
                (0.2397, 0.1194),
                (2.2945, 1.7630),
                (4.2922, 2.9577),
                (9.9429, 6.6917),
                (20.5594, 12.3645),
                (30.3767, 21.7809),
                (39.6233, 32.5455),
                (49.7831, 45.1051),
                (60.0571, 57.3652),
            ],
            source: "MFIX tests/dem/DEM05/AUTOTEST/POST_ALPHA.dat (Experiment)",
        },
    ],
};

/// Kharaz et al. as reproduced in Chung & Ooi's test 4 figures and digitised by Kratos
/// (applications/DEMApplication: test_examples/basic_benchmarks/paper_data/benchmark4_graph1.dat
/// and benchmark4_graph2.dat, tests/DEM3D_chung_ooi_tests/test4_data/paper_data/
/// benchmark4_graph3.dat, the "Experiment" blocks): `e_t`, `ω'` (negative for `v_x > 0`, as
/// in this project), the contact point's rebound angle.
pub const KHARAZ_KRATOS: Measured = Measured {
    experiment: KHARAZ,
    series: &[
        Series {
        column: "e_t",
        points: &[
            (2.238, 0.7965),
            (4.218, 0.7463),
            (9.842, 0.6755),
            (20.218, 0.5988),
            (30.356, 0.6903),
            (39.545, 0.7743),
            (49.604, 0.8476),
            (71.069, 0.9366),
            (79.228, 0.9695),
            (85.168, 0.9794),
        ],
        source: "Kratos DEMApplication test_examples/basic_benchmarks/paper_data/benchmark4_graph1.dat (Experiment)",
        },
        Series {
        column: "omega_rad_s",
        points: &[
            (5.897, -134.86),
            (10.868, -261.16),
            (21.124, -573.70),
            (31.144, -612.23),
            (38.955, -595.11),
            (50.237, -449.54),
            (60.099, -375.69),
            (69.961, -242.97),
            (78.560, -142.35),
            (84.320, -70.64),
        ],
        source: "Kratos DEMApplication test_examples/basic_benchmarks/paper_data/benchmark4_graph2.dat (Experiment)",
        },
        Series {
        column: "rebound_angle_contact_deg",
        points: &[
            (2.100, 0.770),
            (3.943, 0.770),
            (9.718, -1.057),
            (20.310, -8.535),
            (30.161, -2.553),
            (39.120, 9.909),
            (49.512, 30.015),
            (59.904, 49.955),
            (70.460, 66.903),
            (78.860, 78.867),
            (84.782, 85.680),
        ],
        source: "Kratos DEMApplication tests/DEM3D_chung_ooi_tests/test4_data/paper_data/benchmark4_graph3.dat (Experiment)",
        },
    ],
};
