//! The fitted series of the Kelvin–Voigt law's normal impact, nothing integrated: the
//! relaxation time `τ̂(e_n)` of a restitution, and the contact time and restitution of a
//! relaxation time (`cargo run --release -p oblique-tools --bin taufit`, `contactfit`). Their
//! references, the integrated restitution and contact, are in [`super::normal`] and
//! [`super::restitution`].

/// Chebyshev coefficients of `τ̂(e_n)/x` in `u = x/0.35 − 1`, `x = 1 − e_n ∈ [0, 0.7]`: the
/// least-squares fit of degree 28 to the root search from the series at 600 Chebyshev-spread
/// points, each weighed as the error in `τ̂` it gives, and to the exact limit `1/(C1 b₁)` at
/// `x = 0` (`cargo run --release -p oblique-tools --bin taufit`). Its residuals are 5.8e-15
/// of `τ̂` for `e_n ≤ 0.9`, 3.7e-14 for `0.9 < e_n ≤ 0.99` and 1.4e-10 nearer 1, all below
/// the search's own resolution (a few ulps of `e_n` over `1 − e_n`).
const TAU_FIT: [f64; 29] = [
    8.174367809627743e-1,
    3.774336328919117e-1,
    9.468123757493672e-2,
    2.474229870665735e-2,
    6.6218908928035196e-3,
    1.8000362408721864e-3,
    4.946775090525393e-4,
    1.3704694457156687e-4,
    3.8204325659985004e-5,
    1.0702671767251201e-5,
    3.010274673155798e-6,
    8.494847393862056e-7,
    2.4038796287988863e-7,
    6.818673993449707e-8,
    1.9380975453575352e-8,
    5.518575494065826e-9,
    1.573823479503945e-9,
    4.4947016240008847e-10,
    1.2851165413698164e-10,
    3.679632909038257e-11,
    1.0535659654443624e-11,
    3.028712526441891e-12,
    8.634650494147622e-13,
    2.5279890577593616e-13,
    6.910110476759705e-14,
    2.2471980364851982e-14,
    4.967998730133029e-15,
    2.2191750388926598e-15,
    5.712339521534509e-16,
];

/// The fitted `τ̂(e_n)` ([`TAU_FIT`], Clenshaw), `e_n ∈ [0.3, 1]` (unchecked): within 1e-13
/// of the root search ([`super::tau_for_restitution_search`]) for `e_n ≤ 0.9` (2.7e-15 measured),
/// and within 1e-13 plus the search's own resolution above
/// (`crates/solver/tests/kelvin_voigt.rs`); [`super::tau_for_restitution`] takes the series' inverse
/// instead next to `e_n = 1`.
pub fn tau_fit(e_n: f64) -> f64 {
    let x = 1.0 - e_n;
    x * clenshaw(&TAU_FIT, x / 0.35 - 1.0)
}

/// The Chebyshev series `Σ c_k T_k(u)` at `u` (Clenshaw's recurrence).
fn clenshaw(c: &[f64], u: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &ck in c.iter().skip(1).rev() {
        (b1, b2) = (2.0 * u * b1 - b2 + ck, b1);
    }
    u * b1 - b2 + c.first().copied().unwrap_or(0.0)
}

/// Chebyshev coefficients of `t̂_c/t̂_H` in `u = 2 τ̂/`[`TAU_HAT_MAX`]` − 1`: the contact time of
/// the dimensionless impact ([`super::unit_bodies`]) over the Hertz one. The least-squares fit of
/// degree 24 to the contact time integrated on 16 384 steps
/// ([`super::normal::ViscoelasticBodies::contact_integrated`]) at 600 Chebyshev-spread `τ̂`, pinned
/// to 1 at `τ̂ = 0` (`cargo run --release -p oblique-tools --bin contactfit -- 24`): residuals
/// 7.3e-15 relative, the integration's own roundoff (degree 30 and 36: 6.7e-15).
const CONTACT_TIME_FIT: [f64; 25] = [
    9.456955079773816e-1,
    -4.841417307761599e-2,
    5.064699437698535e-3,
    -6.957389835766467e-4,
    1.0806382262846029e-4,
    -1.7993092329115174e-5,
    3.1331235866778097e-6,
    -5.629720155832805e-7,
    1.0354993886120279e-7,
    -1.9395957460607183e-8,
    3.68656866256468e-9,
    -7.092007977521355e-10,
    1.3782252890090594e-10,
    -2.7016731869112476e-11,
    5.3359030109135686e-12,
    -1.0607159361924074e-12,
    2.121540114218231e-13,
    -4.2723238600743123e-14,
    8.535908353112827e-15,
    -1.7425548003010688e-15,
    3.7921062305499884e-16,
    6.72909078051687e-17,
    2.034898944137204e-16,
    1.242128979162492e-16,
    7.31843741822138e-17,
];

/// Chebyshev coefficients of `(1 − e_n)/τ̂` in the same `u`: the same fit to [`super::restitution`],
/// each point weighed as the error in `e_n` it gives, pinned to the small-damping limit
/// `C1 b₁` at `τ̂ = 0` (`b₁` the damping number of `τ̂ = 1`): residuals 1.9e-15 in `e_n`.
const DEFICIT_FIT: [f64; 25] = [
    1.1895250385301963e0,
    -5.7950350917179e-1,
    1.3371690112720072e-1,
    -2.9983755506290576e-2,
    6.60938995615148e-3,
    -1.440969382350637e-3,
    3.1182321270626317e-4,
    -6.71256484430318e-5,
    1.4395694907949235e-5,
    -3.078784303798393e-6,
    6.571123360574996e-7,
    -1.4003625910575178e-7,
    2.9809231980185425e-8,
    -6.340137830222263e-9,
    1.3476714153221103e-9,
    -2.8634499468344396e-10,
    6.082783383579784e-11,
    -1.2923466809421589e-11,
    2.7490462271190486e-12,
    -5.87609875768781e-13,
    1.277223407940134e-13,
    -2.9178289353020405e-14,
    7.430479703669573e-15,
    -2.13637593400035e-15,
    5.419895417068395e-16,
];

/// The fitted contact of the dimensionless impact with relaxation time `τ̂ ∈ (0,`
/// [`TAU_HAT_MAX`]`]` ([`super::unit_bodies`]): its contact time over the Hertz one, `t̂_c/t̂_H`, and its
/// normal restitution `e_n`, from Chebyshev series ([`CONTACT_TIME_FIT`], [`DEFICIT_FIT`]);
/// `None` for any other `τ̂`. Within 1e-14 of the integrated ones
/// ([`super::normal::ViscoelasticBodies::contact_integrated`], [`super::restitution`]) and nothing
/// integrated: the end of every Kelvin–Voigt normal motion ([`super::normal::ViscoelasticBodies`]
/// scales it to its bodies) and the `e_n` of physical bodies.
pub fn contact_fit(tau: f64) -> Option<(f64, f64)> {
    if !(tau > 0.0 && tau <= TAU_HAT_MAX) {
        return None;
    }
    let u = 2.0 * tau / TAU_HAT_MAX - 1.0;
    Some((
        clenshaw(&CONTACT_TIME_FIT, u),
        1.0 - tau * clenshaw(&DEFICIT_FIT, u),
    ))
}

/// The largest relaxation time `τ̂` of [`contact_fit`] (`e_n` ≈ 0.27 there, below the laws'
/// range): every `τ̂` of an `e_n ∈ [0.3, 1]` lies inside.
pub const TAU_HAT_MAX: f64 = 1.0;
