//! Independent verification of the equations of motion (spec §10) and of the two impulses
//! (spec §5 knee lock, §7 heel strike). Derivation: `docs/dynamics.md`.
//!
//! Nothing here trusts the models' own energy functions: the kinetic and potential energies are
//! rebuilt from the positions and velocities of the centres of mass (`StanceGeo`, `SwingGeo`),
//! with the segment parameters taken from `Body`, and the Lagrange equations are then evaluated
//! by finite differences of that T and V. Expected values are computed, never copied from output.
mod common;

use common::default_body;
use klaw::Body;
use klaw::dynamics::{StanceModel, SwingModel, impact};
use nalgebra::{Matrix2, SMatrix, SVector, Vector2, Vector3};
use ode_solvers::{Dopri5, OutputType, System};

/// Tolerance of the finite-difference Lagrange check, relative to the largest entry of M (or b).
/// The differences are built so that their own error is far below it: T is exactly quadratic in
/// the rates, so central differences in q̇ (step 0.5) are exact up to rounding (~1e-14 relative);
/// the central differences in q (step 1e-5) have truncation error ~h²/6·|T'''| ≈ 2e-11 relative
/// and rounding ~ε|T|/h ≈ 1e-10 relative. 1e-6 leaves a margin of ≳1e3 over that, while a
/// wrong term (a lost factor 2, a flipped sign, a missing mass) is an O(1e-2..1) relative error
/// at some of the ≥ 50 states (checked below by mutating the model's output).
const FD_TOL: f64 = 1e-6;

/// The bodies used: the paper's example and a small body at the other end of the table.
fn bodies() -> [Body; 2] {
    [default_body(), Body::standard(1.55, 52.0).unwrap()]
}

/// Deterministic SplitMix64 generator.
struct Rng(u64);
impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

fn cross(r: [f64; 2], v: [f64; 2]) -> f64 {
    r[0] * v[1] - r[1] * v[0]
}
fn norm2(v: [f64; 2]) -> f64 {
    v[0] * v[0] + v[1] * v[1]
}
fn max_abs<const R: usize, const C: usize>(m: &SMatrix<f64, R, C>) -> f64 {
    m.iter().fold(0.0_f64, |a, x| a.max(x.abs()))
}

// ---------------------------------------------------------------------------------------------
// Independent geometry and energies
// ---------------------------------------------------------------------------------------------

/// Stance model rebuilt from its geometry: ankle pivot P = (0, l9); leg CoM = P + r1 (s1, c1);
/// hip = P + w (s1, c1); trunk CoM = hip + a (s2, c2). Both segments rotate with their angle
/// (angular speeds |θ̇1|, |θ̇2|); I1, I2 about the centres of mass.
struct StanceGeo {
    m1: f64,
    m2: f64,
    r1: f64,
    i1: f64,
    a: f64,
    i2: f64,
    l9: f64,
    g: f64,
}

impl StanceGeo {
    fn new(b: &Body, g: f64) -> Self {
        StanceGeo {
            m1: b.m1,
            m2: b.m2,
            r1: b.r1,
            i1: b.i1,
            a: b.r2,
            i2: b.i2,
            l9: b.l9,
            g,
        }
    }
    /// (leg CoM, hip, trunk CoM).
    fn points(&self, q: &Vector3<f64>) -> [[f64; 2]; 3] {
        let (w, (s1, c1), (s2, c2)) = (q[0], q[1].sin_cos(), q[2].sin_cos());
        let leg = [self.r1 * s1, self.l9 + self.r1 * c1];
        let hip = [w * s1, self.l9 + w * c1];
        let trunk = [hip[0] + self.a * s2, hip[1] + self.a * c2];
        [leg, hip, trunk]
    }
    /// Velocities of (leg CoM, hip, trunk CoM), by the chain rule on `points`.
    fn velocities(&self, q: &Vector3<f64>, qd: &Vector3<f64>) -> [[f64; 2]; 3] {
        let (w, (s1, c1), (s2, c2)) = (q[0], q[1].sin_cos(), q[2].sin_cos());
        let (wd, t1d, t2d) = (qd[0], qd[1], qd[2]);
        let leg = [self.r1 * c1 * t1d, -self.r1 * s1 * t1d];
        let hip = [wd * s1 + w * c1 * t1d, wd * c1 - w * s1 * t1d];
        let trunk = [hip[0] + self.a * c2 * t2d, hip[1] - self.a * s2 * t2d];
        [leg, hip, trunk]
    }
    fn kinetic(&self, q: &Vector3<f64>, qd: &Vector3<f64>) -> f64 {
        let [vl, _, vt] = self.velocities(q, qd);
        0.5 * (self.m1 * norm2(vl)
            + self.i1 * qd[1] * qd[1]
            + self.m2 * norm2(vt)
            + self.i2 * qd[2] * qd[2])
    }
    fn potential(&self, q: &Vector3<f64>) -> f64 {
        let [leg, _, trunk] = self.points(q);
        self.g * (self.m1 * leg[1] + self.m2 * trunk[1])
    }
}

/// Swing leg rebuilt from its geometry, hip at `hip` moving at `hip_vel`: knee = hip +
/// l3 (−s3, −c3); thigh CoM = hip + r3 (−s3, −c3); shank CoM = knee + r4 (−sφ, −cφ),
/// φ = θ3 + θ4. I3, I4 about the centres of mass.
struct SwingGeo {
    m3: f64,
    m4: f64,
    l3: f64,
    r3: f64,
    r4: f64,
    i3: f64,
    i4: f64,
    g: f64,
}

impl SwingGeo {
    fn new(b: &Body, g: f64) -> Self {
        SwingGeo {
            m3: b.m3,
            m4: b.m4,
            l3: b.l3,
            r3: b.r3,
            r4: b.r4,
            i3: b.i3,
            i4: b.i4,
            g,
        }
    }
    /// (thigh CoM, shank CoM) relative to the hip.
    fn points(&self, q: &Vector2<f64>) -> [[f64; 2]; 2] {
        let ((s3, c3), (sp, cp)) = (q[0].sin_cos(), (q[0] + q[1]).sin_cos());
        let thigh = [-self.r3 * s3, -self.r3 * c3];
        let shank = [-self.l3 * s3 - self.r4 * sp, -self.l3 * c3 - self.r4 * cp];
        [thigh, shank]
    }
    /// Velocities of (thigh CoM, shank CoM) relative to the hip.
    fn velocities(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> [[f64; 2]; 2] {
        let ((s3, c3), (sp, cp)) = (q[0].sin_cos(), (q[0] + q[1]).sin_cos());
        let (t3d, pd) = (qd[0], qd[0] + qd[1]);
        let thigh = [-self.r3 * c3 * t3d, self.r3 * s3 * t3d];
        let shank = [
            -self.l3 * c3 * t3d - self.r4 * cp * pd,
            self.l3 * s3 * t3d + self.r4 * sp * pd,
        ];
        [thigh, shank]
    }
    /// T with the hip moving at `hip_vel` (absolute velocities = hip_vel + relative ones).
    fn kinetic_moving(&self, q: &Vector2<f64>, qd: &Vector2<f64>, hip_vel: [f64; 2]) -> f64 {
        let [v3, v4] = self.velocities(q, qd);
        let abs = |v: [f64; 2]| [v[0] + hip_vel[0], v[1] + hip_vel[1]];
        let pd = qd[0] + qd[1];
        0.5 * (self.m3 * norm2(abs(v3))
            + self.i3 * qd[0] * qd[0]
            + self.m4 * norm2(abs(v4))
            + self.i4 * pd * pd)
    }
    fn kinetic(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        self.kinetic_moving(q, qd, [0.0, 0.0])
    }
    /// Gravity potential, hip at height 0.
    fn potential(&self, q: &Vector2<f64>) -> f64 {
        let [p3, p4] = self.points(q);
        self.g * (self.m3 * p3[1] + self.m4 * p4[1])
    }
    /// z-component (counter-clockwise +) of the leg's angular momentum about the hip, in the
    /// hip's frame: Σ m r × v + I ω; a segment at angle θ from the downward vertical, with its
    /// far end at (−sin θ, −cos θ), turns clockwise as θ grows, so ω_z = −θ̇.
    fn angular_momentum_about_hip(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        let [p3, p4] = self.points(q);
        let [v3, v4] = self.velocities(q, qd);
        self.m3 * cross(p3, v3) - self.i3 * qd[0] + self.m4 * cross(p4, v4)
            - self.i4 * (qd[0] + qd[1])
    }
}

// ---------------------------------------------------------------------------------------------
// Lagrange equations by finite differences
// ---------------------------------------------------------------------------------------------

/// Step in the rates: T is quadratic in q̇ (and in the hip velocity), so central differences
/// are exact there for any step; a large one keeps rounding small.
const H_RATE: f64 = 0.5;
/// Step in the coordinates.
const H_COORD: f64 = 1e-5;

/// Kinetic energy T(q, q̇, s) as the finite-difference helper takes it.
type Kinetic<'a, const N: usize> = dyn Fn(&SVector<f64, N>, &SVector<f64, N>, f64) -> f64 + 'a;

fn unit<const N: usize>(i: usize) -> SVector<f64, N> {
    let mut e = SVector::<f64, N>::zeros();
    e[i] = 1.0;
    e
}

/// M_ij = ∂²T/∂q̇i∂q̇j and b_i = Σ_j ∂²T/∂q̇i∂qj q̇j + ∂²T/∂q̇i∂s − ∂T/∂qi + ∂V/∂qi, where
/// `t(q, q̇, s)` is the kinetic energy with the explicit time dependence (the hip's velocity,
/// swing model) advanced by s seconds at the hip acceleration (s is ignored for stance).
fn lagrange_fd<const N: usize>(
    t: &Kinetic<N>,
    v: &dyn Fn(&SVector<f64, N>) -> f64,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
    let (hr, hc) = (H_RATE, H_COORD);
    let mut m = SMatrix::<f64, N, N>::zeros();
    for i in 0..N {
        for j in 0..N {
            let (ei, ej) = (unit::<N>(i) * hr, unit::<N>(j) * hr);
            m[(i, j)] = (t(q, &(qd + ei + ej), 0.0)
                - t(q, &(qd + ei - ej), 0.0)
                - t(q, &(qd - ei + ej), 0.0)
                + t(q, &(qd - ei - ej), 0.0))
                / (4.0 * hr * hr);
        }
    }
    // generalized momentum p_i = ∂T/∂q̇i at (q, q̇, s)
    let p = |i: usize, q: &SVector<f64, N>, s: f64| {
        let ei = unit::<N>(i) * hr;
        (t(q, &(qd + ei), s) - t(q, &(qd - ei), s)) / (2.0 * hr)
    };
    let mut b = SVector::<f64, N>::zeros();
    for i in 0..N {
        // d/dt p_i − M q̈ = Σ_j ∂p_i/∂q_j q̇_j + ∂p_i/∂s
        let mut dp = 0.0;
        for j in 0..N {
            let ej = unit::<N>(j) * hc;
            dp += (p(i, &(q + ej), 0.0) - p(i, &(q - ej), 0.0)) / (2.0 * hc) * qd[j];
        }
        dp += (p(i, q, hr) - p(i, q, -hr)) / (2.0 * hr);
        let ei = unit::<N>(i) * hc;
        let dt_dq = (t(&(q + ei), qd, 0.0) - t(&(q - ei), qd, 0.0)) / (2.0 * hc);
        let dv_dq = (v(&(q + ei)) - v(&(q - ei))) / (2.0 * hc);
        b[i] = dp - dt_dq + dv_dq;
    }
    (m, b)
}

fn random_stance_state(rng: &mut Rng) -> (Vector3<f64>, Vector3<f64>) {
    let q = Vector3::new(
        rng.uniform(0.7, 1.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-1.0, 1.0),
    );
    let qd = Vector3::new(
        rng.uniform(-3.0, 3.0),
        rng.uniform(-3.0, 3.0),
        rng.uniform(-3.0, 3.0),
    );
    (q, qd)
}

fn random_swing_state(rng: &mut Rng) -> (Vector2<f64>, Vector2<f64>) {
    let q = Vector2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    let qd = Vector2::new(rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0));
    (q, qd)
}

/// Relative discrepancy of M and b against the finite-difference values.
fn rel_errors<const N: usize>(
    m: &SMatrix<f64, N, N>,
    b: &SVector<f64, N>,
    m_fd: &SMatrix<f64, N, N>,
    b_fd: &SVector<f64, N>,
) -> (f64, f64) {
    (
        max_abs(&(m - m_fd)) / max_abs(m_fd),
        max_abs(&(b - b_fd)) / max_abs(b_fd),
    )
}

/// The point velocities used for T are the time derivatives of the points used for V.
#[test]
fn independent_velocities_differentiate_the_positions() {
    let mut rng = Rng(7);
    let h = 1e-6;
    for body in bodies() {
        let st = StanceGeo::new(&body, 9.81);
        let sw = SwingGeo::new(&body, 9.81);
        for _ in 0..20 {
            let (q, qd) = random_stance_state(&mut rng);
            let (pp, pm) = (st.points(&(q + qd * h)), st.points(&(q - qd * h)));
            for (k, v) in st.velocities(&q, &qd).iter().enumerate() {
                for c in 0..2 {
                    assert!(
                        ((pp[k][c] - pm[k][c]) / (2.0 * h) - v[c]).abs() < 1e-7,
                        "stance point {k}"
                    );
                }
            }
            let (q, qd) = random_swing_state(&mut rng);
            let (pp, pm) = (sw.points(&(q + qd * h)), sw.points(&(q - qd * h)));
            for (k, v) in sw.velocities(&q, &qd).iter().enumerate() {
                for c in 0..2 {
                    assert!(
                        ((pp[k][c] - pm[k][c]) / (2.0 * h) - v[c]).abs() < 1e-7,
                        "swing point {k}"
                    );
                }
            }
        }
    }
}

/// §10: stance M(q) and b(q, q̇) against finite differences of the independent Lagrangian at
/// 60 random states per body (w ∈ [0.7, 1.0] m, angles ∈ ±1 rad, rates ∈ ±3).
#[test]
fn stance_mass_matrix_and_bias_match_the_lagrangian() {
    let mut rng = Rng(1);
    let (mut worst_m, mut worst_b, mut mutant_b, mut mutant_m) =
        (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for body in bodies() {
        let model = StanceModel::new(&body);
        let geo = StanceGeo::new(&body, model.g);
        let t = |q: &Vector3<f64>, qd: &Vector3<f64>, _s: f64| geo.kinetic(q, qd);
        let v = |q: &Vector3<f64>| geo.potential(q);
        for _ in 0..60 {
            let (q, qd) = random_stance_state(&mut rng);
            let (m_fd, b_fd) = lagrange_fd(&t, &v, &q, &qd);
            let (m, b) = (model.mass_matrix(&q), model.bias(&q, &qd));
            let (em, eb) = rel_errors(&m, &b, &m_fd, &b_fd);
            assert!(
                em < FD_TOL,
                "stance M off by {em:e} at q={q:?}\nM={m}\nM_fd={m_fd}"
            );
            assert!(
                eb < FD_TOL,
                "stance b off by {eb:e} at q={q:?} q̇={qd:?}\nb={b}\nb_fd={b_fd}"
            );
            worst_m = worst_m.max(em);
            worst_b = worst_b.max(eb);
            // The check has power: a Coriolis term with its factor 2 lost (2 m2 w ẇ θ̇1 → m2 w ẇ θ̇1)
            // and a mass matrix without the trunk coupling's w factor must both be rejected.
            let mut b_bad = b;
            b_bad[1] -= model.m2 * q[0] * qd[0] * qd[1];
            mutant_b = mutant_b.max(rel_errors(&m, &b_bad, &m_fd, &b_fd).1);
            let mut m_bad = m;
            m_bad[(1, 2)] /= q[0];
            m_bad[(2, 1)] /= q[0];
            mutant_m = mutant_m.max(rel_errors(&m_bad, &b, &m_fd, &b_fd).0);
        }
    }
    eprintln!(
        "stance FD check: worst rel. error M {worst_m:.2e}, b {worst_b:.2e}; mutants {mutant_m:.2e}, {mutant_b:.2e}"
    );
    assert!(mutant_b > 1e3 * FD_TOL && mutant_m > 1e3 * FD_TOL);
}

/// §10: swing M(q) and b(q, q̇) with the hip at rest against finite differences of the
/// independent Lagrangian at 60 random states per body.
#[test]
fn swing_mass_matrix_and_bias_match_the_lagrangian() {
    let mut rng = Rng(2);
    let (mut worst_m, mut worst_b, mut mutant) = (0.0_f64, 0.0_f64, 0.0_f64);
    for body in bodies() {
        let model = SwingModel::new(&body);
        let geo = SwingGeo::new(&body, model.g);
        let t = |q: &Vector2<f64>, qd: &Vector2<f64>, _s: f64| geo.kinetic(q, qd);
        let v = |q: &Vector2<f64>| geo.potential(q);
        for _ in 0..60 {
            let (q, qd) = random_swing_state(&mut rng);
            let (m_fd, b_fd) = lagrange_fd(&t, &v, &q, &qd);
            let (m, b) = (model.mass_matrix(&q), model.bias(&q, &qd, [0.0, 0.0]));
            let (em, eb) = rel_errors(&m, &b, &m_fd, &b_fd);
            assert!(
                em < FD_TOL,
                "swing M off by {em:e} at q={q:?}\nM={m}\nM_fd={m_fd}"
            );
            assert!(
                eb < FD_TOL,
                "swing b off by {eb:e} at q={q:?} q̇={qd:?}\nb={b}\nb_fd={b_fd}"
            );
            worst_m = worst_m.max(em);
            worst_b = worst_b.max(eb);
            // power: b1 with the 2 θ̇3 θ̇4 Coriolis term dropped
            let mut b_bad = b;
            b_bad[0] -= model.m4 * model.l3 * model.r4 * q[1].sin() * 2.0 * qd[0] * qd[1];
            mutant = mutant.max(rel_errors(&m, &b_bad, &m_fd, &b_fd).1);
        }
    }
    eprintln!(
        "swing FD check (hip at rest): worst rel. error M {worst_m:.2e}, b {worst_b:.2e}; mutant {mutant:.2e}"
    );
    assert!(mutant > 1e3 * FD_TOL);
}

/// The hip forcing of the swing model from the time-dependent Lagrangian: T is written with
/// absolute velocities (hip velocity v_h + relative ones), and d/dt ∂T/∂q̇ picks up
/// ∂²T/∂q̇∂v_h · a_h. Random hip velocities (the result must not depend on them) and
/// accelerations up to ±15 m/s².
#[test]
fn swing_hip_forcing_matches_the_moving_hip_lagrangian() {
    let mut rng = Rng(3);
    let mut worst = 0.0_f64;
    for body in bodies() {
        let model = SwingModel::new(&body);
        let geo = SwingGeo::new(&body, model.g);
        for _ in 0..60 {
            let (q, qd) = random_swing_state(&mut rng);
            let vh = [rng.uniform(-2.0, 2.0), rng.uniform(-1.0, 1.0)];
            let ah = [rng.uniform(-15.0, 15.0), rng.uniform(-15.0, 15.0)];
            let t = |q: &Vector2<f64>, qd: &Vector2<f64>, s: f64| {
                geo.kinetic_moving(q, qd, [vh[0] + ah[0] * s, vh[1] + ah[1] * s])
            };
            let v = |q: &Vector2<f64>| geo.potential(q);
            let (_, b_fd) = lagrange_fd(&t, &v, &q, &qd);
            let b = model.bias(&q, &qd, ah);
            let e = max_abs(&(b - b_fd)) / max_abs(&b_fd);
            assert!(
                e < FD_TOL,
                "swing b with hip acc {ah:?} off by {e:e}: b={b} b_fd={b_fd}"
            );
            worst = worst.max(e);
        }
    }
    eprintln!("swing FD check (moving hip): worst rel. error b {worst:.2e}");
}

// ---------------------------------------------------------------------------------------------
// Swing hip forcing: closed-form cases
// ---------------------------------------------------------------------------------------------

/// A hip accelerating forward at a: in the hip's frame gravity is (−a, −g), so the hanging
/// straight leg trails at θ3 = atan(a/g) (positive: knee behind the hip), θ4 = 0, and there
/// b = 0 (static equilibrium, Q = 0).
#[test]
fn swing_straight_leg_trails_a_horizontally_accelerating_hip() {
    for body in bodies() {
        let model = SwingModel::new(&body);
        let g = model.g;
        let scale = (model.m3 * model.r3 + model.m4 * (model.l3 + model.r4)) * g;
        for a in [-4.0, -1.5, 0.0, 0.7, 2.0, 6.0] {
            let theta3 = f64::atan(a / g);
            let zero = Vector2::zeros();
            let b = model.bias(&Vector2::new(theta3, 0.0), &zero, [a, 0.0]);
            assert!(b.amax() < 1e-13 * scale, "a = {a}: b = {b}");
            if a != 0.0 {
                // the mirrored angle is not an equilibrium: the sign convention is tested
                let b = model.bias(&Vector2::new(-theta3, 0.0), &zero, [a, 0.0]);
                assert!(
                    b.amax() > 1e-3 * scale,
                    "a = {a}: mirrored leg also balanced, b = {b}"
                );
            }
            // a bent knee is not an equilibrium either (the shank is pulled straight)
            let b = model.bias(&Vector2::new(theta3, 0.3), &zero, [a, 0.0]);
            assert!(b[1].abs() > 1e-3 * scale);
        }
    }
}

/// A hip accelerating upward at ÿ: effective gravity g + ÿ. At rest the bias scales by
/// (g + ÿ)/g; with rates, the change of b is ÿ/g times the gravity terms ∂V/∂q (from the
/// independent V). The scan's forcing (m3 r3 + m4 l3)(ẍ cos θ3 − ÿ sin θ3) plus the shank's
/// m4 r4 (ẍ cos φ − ÿ sin φ) is the generalized inertial force on θ3.
#[test]
fn swing_vertical_hip_acceleration_is_extra_gravity() {
    let mut rng = Rng(4);
    for body in bodies() {
        let model = SwingModel::new(&body);
        let geo = SwingGeo::new(&body, model.g);
        let g = model.g;
        for _ in 0..50 {
            let (q, qd) = random_swing_state(&mut rng);
            let ydd = rng.uniform(-8.0, 8.0);
            let zero = Vector2::zeros();
            let b0 = model.bias(&q, &zero, [0.0, 0.0]);
            let b1 = model.bias(&q, &zero, [0.0, ydd]);
            assert!(
                (b1 - b0 * ((g + ydd) / g)).amax() < 1e-12 * b0.amax().max(1.0),
                "{b0} {b1}"
            );
            let h = 1e-6;
            let dv = Vector2::new(
                (geo.potential(&(q + Vector2::new(h, 0.0)))
                    - geo.potential(&(q - Vector2::new(h, 0.0))))
                    / (2.0 * h),
                (geo.potential(&(q + Vector2::new(0.0, h)))
                    - geo.potential(&(q - Vector2::new(0.0, h))))
                    / (2.0 * h),
            );
            let diff = model.bias(&q, &qd, [0.0, ydd]) - model.bias(&q, &qd, [0.0, 0.0]);
            assert!(
                (diff - dv * (ydd / g)).amax() < 1e-8 * dv.amax(),
                "{diff} vs {}",
                dv * (ydd / g)
            );
            // the scan's forcing term, on the right-hand side
            let xdd = rng.uniform(-8.0, 8.0);
            let (s3, c3) = q[0].sin_cos();
            let (sp, cp) = (q[0] + q[1]).sin_cos();
            let k = body.m3 * body.r3 + body.m4 * body.l3;
            let f1 = k * (xdd * c3 - ydd * s3) + body.m4 * body.r4 * (xdd * cp - ydd * sp);
            let f2 = body.m4 * body.r4 * (xdd * cp - ydd * sp);
            let forcing = model.bias(&q, &qd, [0.0, 0.0]) - model.bias(&q, &qd, [xdd, ydd]);
            assert!((forcing - Vector2::new(f1, f2)).amax() < 1e-12 * k * 20.0);
        }
    }
}

/// Appendix A.2 as the scan prints it: a11 = I3 + m3 r3² + m4 l3² + I4 + m4 r4² + 2 m4 l3 r4 cos θ4,
/// i.e. at θ4 = 0 the (straight) leg's moment of inertia about the hip.
#[test]
fn swing_a11_is_the_scanned_appendix_value() {
    for body in bodies() {
        let model = SwingModel::new(&body);
        let (m3, m4, l3, r3, r4, i3, i4) = (
            body.m3, body.m4, body.l3, body.r3, body.r4, body.i3, body.i4,
        );
        let straight = i3 + m3 * r3 * r3 + m4 * l3 * l3 + i4 + m4 * r4 * r4 + 2.0 * m4 * l3 * r4;
        for t3 in [-0.6, 0.0, 0.4] {
            let a11 = model.mass_matrix(&Vector2::new(t3, 0.0))[(0, 0)];
            assert!(
                (a11 - straight).abs() < 1e-12 * straight,
                "{a11} vs {straight}"
            );
        }
        // a straight leg is one rigid body: its inertia about the hip from the parallel axis theorem
        let com = (m3 * r3 + m4 * (l3 + r4)) / (m3 + m4);
        let about_com = i3 + m3 * (r3 - com).powi(2) + i4 + m4 * (l3 + r4 - com).powi(2);
        assert!((about_com + (m3 + m4) * com * com - straight).abs() < 1e-12 * straight);
        for t4 in [-0.2, 0.5, 1.2] {
            let a11 = model.mass_matrix(&Vector2::new(0.1, t4))[(0, 0)];
            let scan = i3
                + m3 * r3 * r3
                + m4 * l3 * l3
                + i4
                + m4 * r4 * r4
                + 2.0 * m4 * l3 * r4 * f64::cos(t4);
            assert!((a11 - scan).abs() < 1e-12 * scan);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Energy conservation (spec §10)
// ---------------------------------------------------------------------------------------------

const RTOL: f64 = 1e-12;
const T_END: f64 = 5.0;
const ENERGY_TOL: f64 = 1e-6;

type State6 = SVector<f64, 6>;
type State4 = SVector<f64, 4>;

/// Stance with only the (unclamped, undamped) leg spring F_w = k_w (l1 − w), or locked.
struct StanceSpring {
    model: StanceModel,
    kw: f64,
    l1: f64,
    locked: bool,
}

impl System<f64, State6> for StanceSpring {
    fn system(&self, _t: f64, y: &State6, dy: &mut State6) {
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let fw = if self.locked {
            0.0
        } else {
            self.kw * (self.l1 - q[0])
        };
        let acc = self
            .model
            .accelerations(&q, &qd, &Vector3::new(fw, 0.0, 0.0), self.locked);
        dy.fixed_rows_mut::<3>(0).copy_from(&qd);
        dy.fixed_rows_mut::<3>(3).copy_from(&acc);
    }
}

/// Swing with the hip fixed and no torques (optionally the knee locked).
struct SwingFree {
    model: SwingModel,
    locked: bool,
}

impl System<f64, State4> for SwingFree {
    fn system(&self, _t: f64, y: &State4, dy: &mut State4) {
        let (q, qd) = (Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]));
        let acc = self
            .model
            .accelerations(&q, &qd, &Vector2::zeros(), [0.0, 0.0], self.locked);
        dy[0] = qd[0];
        dy[1] = qd[1];
        dy[2] = acc[0];
        dy[3] = acc[1];
    }
}

/// Integrate with Dopri5 (rtol = atol = 1e-12) and return the state after every accepted step.
/// Sparse output on purpose: ode_solvers 0.6.2's `OutputType::Dense` fills its last point
/// (x_end) by extrapolating the step that produced the point before it (`solution_output`,
/// "Ensure the last point is added ..."), an error of ~1e-4 that is not the model's.
fn integrate<const N: usize, S: System<f64, SVector<f64, N>>>(
    sys: S,
    y0: SVector<f64, N>,
) -> Vec<SVector<f64, N>> {
    let mut solver = Dopri5::from_param(
        sys,
        0.0,
        T_END,
        T_END,
        y0,
        RTOL,
        RTOL,
        0.9,
        0.04,
        0.2,
        10.0,
        T_END,
        0.0,
        2_000_000,
        1000,
        OutputType::Sparse,
    );
    let stats = solver.integrate().expect("integration succeeds");
    eprintln!("  dopri5: {} accepted steps", stats.accepted_steps);
    solver.y_out().clone()
}

/// §10: stance with the leg spring only (τ1 = pa = d_w = k_2 = d_2 = 0, no clamp) conserves
/// E = T + V_g + ½ k_w (l1 − w)²; k_w = m2 (2π·5 Hz)².
#[test]
fn stance_with_leg_spring_conserves_energy() {
    let body = default_body();
    let model = StanceModel::new(&body);
    let geo = StanceGeo::new(&body, model.g);
    let (l1, m2, g) = (body.l1, body.m2, model.g);
    let kw = m2 * (2.0 * std::f64::consts::PI * 5.0).powi(2);
    let energy = |y: &State6| {
        let (q, qd) = (
            Vector3::new(y[0], y[1], y[2]),
            Vector3::new(y[3], y[4], y[5]),
        );
        geo.kinetic(&q, &qd) + geo.potential(&q) + 0.5 * kw * (l1 - q[0]).powi(2)
    };
    let starts = [
        [l1, -0.3, 0.05, 0.0, 1.5, 0.0],
        [l1 - 0.02, 0.2, -0.1, 0.1, -0.8, 0.5],
        [l1 + 0.01, 0.0, 0.3, -0.2, 0.5, -1.0],
    ];
    for s in starts {
        let y0 = State6::from_row_slice(&s);
        let (q0, qd0) = (
            Vector3::new(s[0], s[1], s[2]),
            Vector3::new(s[3], s[4], s[5]),
        );
        // the model's own energy functions agree with the independent ones
        assert!(
            (model.kinetic_energy(&q0, &qd0) - geo.kinetic(&q0, &qd0)).abs()
                < 1e-12 * geo.kinetic(&q0, &qd0)
        );
        assert!(
            (model.potential_energy(&q0) - geo.potential(&q0)).abs() < 1e-12 * geo.potential(&q0)
        );
        let norm = geo.kinetic(&q0, &qd0) + m2 * g * l1;
        let e0 = energy(&y0);
        let ys = integrate(
            StanceSpring {
                model,
                kw,
                l1,
                locked: false,
            },
            y0,
        );
        let drift = ys
            .iter()
            .map(|y| (energy(y) - e0).abs())
            .fold(0.0, f64::max)
            / norm;
        let moved = ys.iter().map(|y| (y[1] - s[1]).abs()).fold(0.0, f64::max);
        eprintln!(
            "stance spring from {s:?}: max |ΔE|/(T0 + m2 g l1) = {drift:.2e} over {T_END} s (θ1 moved {moved:.2} rad)"
        );
        assert!(drift <= ENERGY_TOL, "energy drift {drift:e}");
        assert!(moved > 0.1, "the test must exercise the dynamics");
    }
}

/// The locked stance (w fixed, 2 DOF) conserves T + V_g.
#[test]
fn locked_stance_conserves_energy() {
    let body = default_body();
    let model = StanceModel::new(&body);
    let geo = StanceGeo::new(&body, model.g);
    let (l1, m2, g) = (body.l1, body.m2, model.g);
    let energy = |y: &State6| {
        let (q, qd) = (
            Vector3::new(y[0], y[1], y[2]),
            Vector3::new(y[3], y[4], y[5]),
        );
        geo.kinetic(&q, &qd) + geo.potential(&q)
    };
    for s in [
        [l1, -0.3, 0.05, 0.0, 1.5, 0.0],
        [l1, 0.1, -0.2, 0.0, -0.5, 2.0],
    ] {
        let y0 = State6::from_row_slice(&s);
        let norm = geo.kinetic(
            &Vector3::new(s[0], s[1], s[2]),
            &Vector3::new(0.0, s[4], s[5]),
        ) + m2 * g * l1;
        let e0 = energy(&y0);
        let ys = integrate(
            StanceSpring {
                model,
                kw: 0.0,
                l1,
                locked: true,
            },
            y0,
        );
        let drift = ys
            .iter()
            .map(|y| (energy(y) - e0).abs())
            .fold(0.0, f64::max)
            / norm;
        let w_moved = ys
            .iter()
            .map(|y| (y[0] - l1).abs().max(y[3].abs()))
            .fold(0.0, f64::max);
        eprintln!("locked stance from {s:?}: max |ΔE|/(T0 + m2 g l1) = {drift:.2e}");
        assert!(drift <= ENERGY_TOL, "energy drift {drift:e}");
        assert_eq!(w_moved, 0.0, "the locked leg changed length");
    }
}

/// §10: swing with the hip fixed and no torques conserves T + V (also with the knee locked).
#[test]
fn free_swing_conserves_energy() {
    let body = default_body();
    let model = SwingModel::new(&body);
    let geo = SwingGeo::new(&body, model.g);
    let (l1, m2, g) = (body.l1, body.m2, model.g);
    let energy = |y: &State4| {
        let (q, qd) = (Vector2::new(y[0], y[1]), Vector2::new(y[2], y[3]));
        geo.kinetic(&q, &qd) + geo.potential(&q)
    };
    for (s, locked) in [
        ([-0.5, 0.8, 0.0, 0.0], false),
        ([0.3, 0.2, -2.0, 4.0], false),
        ([-0.5, 0.07, 1.0, 0.0], true),
    ] {
        let y0 = State4::from_row_slice(&s);
        let (q0, qd0) = (Vector2::new(s[0], s[1]), Vector2::new(s[2], s[3]));
        assert!(
            (model.kinetic_energy(&q0, &qd0) - geo.kinetic(&q0, &qd0)).abs()
                < 1e-12 * (1.0 + geo.kinetic(&q0, &qd0))
        );
        assert!(
            (model.potential_energy(&q0) - geo.potential(&q0)).abs()
                < 1e-12 * geo.potential(&q0).abs()
        );
        let norm = geo.kinetic(&q0, &qd0) + m2 * g * l1;
        let e0 = energy(&y0);
        let ys = integrate(SwingFree { model, locked }, y0);
        let drift = ys
            .iter()
            .map(|y| (energy(y) - e0).abs())
            .fold(0.0, f64::max)
            / norm;
        // relative to the leg's own energy scale too (m2 g l1 is the trunk's, spec §10)
        let leg_scale = geo.kinetic(&q0, &qd0) + (body.m3 + body.m4) * g * l1;
        let drift_leg = drift * norm / leg_scale;
        eprintln!(
            "free swing from {s:?} (knee locked: {locked}): max |ΔE|/(T0 + m2 g l1) = {drift:.2e}, /(T0 + m1 g l1) = {drift_leg:.2e}"
        );
        assert!(
            drift <= ENERGY_TOL && drift_leg <= ENERGY_TOL,
            "energy drift {drift:e}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Heel strike (spec §7)
// ---------------------------------------------------------------------------------------------

/// Generalized momenta p = ∂T/∂q̇ of the independent stance T (exact central difference).
fn stance_momenta(geo: &StanceGeo, q: &Vector3<f64>, qd: &Vector3<f64>) -> Vector3<f64> {
    Vector3::from_fn(|i, _| {
        let e = unit::<3>(i) * H_RATE;
        (geo.kinetic(q, &(qd + e)) - geo.kinetic(q, &(qd - e))) / (2.0 * H_RATE)
    })
}

fn speed(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

/// At random pre-impact states and impulse fractions ρ (1, the plastic impulse, the default 0.4,
/// and 0): ẇ⁺ = (1 − ρ) ẇ⁻, p_θ1 and p_θ2 unchanged, energy lost = T⁻ − T⁺ ≥ 0 (from the
/// independent geometry's kinetic energy) and equal to the report's, the report's speed ratio
/// equal to the hip speeds' ratio.
#[test]
fn heel_strike_stops_the_leg_axis_and_keeps_the_angular_momenta() {
    let mut rng = Rng(5);
    let (mut worst_p, mut worst_e, mut min_lost) = (0.0_f64, 0.0_f64, f64::INFINITY);
    for body in bodies() {
        let model = StanceModel::new(&body);
        let geo = StanceGeo::new(&body, model.g);
        for k in 0..60 {
            let (q, qd_minus) = random_stance_state(&mut rng);
            let fraction = [1.0, 0.4, 0.0][k % 3];
            let (qd_plus, report) = impact::heel_strike(&model, &q, &qd_minus, fraction);
            let expected = (1.0 - fraction) * qd_minus[0];
            assert!(
                (qd_plus[0] - expected).abs() <= 1e-12 * (1.0 + qd_minus[0].abs()),
                "ẇ⁺ = {} for ρ {fraction}",
                qd_plus[0]
            );
            let (p0, p1) = (
                stance_momenta(&geo, &q, &qd_minus),
                stance_momenta(&geo, &q, &qd_plus),
            );
            let scale = p0.amax();
            for i in 1..3 {
                let e = (p1[i] - p0[i]).abs() / scale;
                assert!(e <= 1e-10, "p[{i}] changed by {e:e}");
                worst_p = worst_p.max(e);
            }
            let (t0, t1) = (geo.kinetic(&q, &qd_minus), geo.kinetic(&q, &qd_plus));
            let lost = t0 - t1;
            assert!(lost >= -1e-12 * t0, "heel strike created energy: {lost}");
            let e = (lost - report.energy_lost).abs() / t0;
            assert!(
                e <= 1e-10,
                "energy lost {lost} vs reported {}",
                report.energy_lost
            );
            worst_e = worst_e.max(e);
            if fraction == 1.0 {
                min_lost = min_lost.min(lost / t0);
            }
            let [_, vh0, _] = geo.velocities(&q, &qd_minus);
            let [_, vh1, _] = geo.velocities(&q, &qd_plus);
            assert!((report.speed_ratio - speed(vh1) / speed(vh0)).abs() < 1e-12);
        }
    }
    eprintln!(
        "heel strike: worst rel. change of p_θ1, p_θ2 {worst_p:.2e}; worst energy mismatch {worst_e:.2e}; min fraction lost {min_lost:.2e}"
    );
}

/// `rates_about_pivot` reproduces the given hip velocity through the independent geometry.
#[test]
fn rates_about_pivot_reproduce_the_hip_velocity() {
    let mut rng = Rng(6);
    let body = default_body();
    let geo = StanceGeo::new(&body, 9.81);
    for _ in 0..50 {
        let (q, _) = random_stance_state(&mut rng);
        let v = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
        let trunk = rng.uniform(-3.0, 3.0);
        let qd = impact::rates_about_pivot(&q, v, trunk);
        let [_, vh, _] = geo.velocities(&q, &qd);
        assert!(
            (vh[0] - v[0]).abs() < 1e-13 && (vh[1] - v[1]).abs() < 1e-13,
            "{vh:?} vs {v:?}"
        );
        assert_eq!(qd[2], trunk);
    }
}

/// Newton–Euler solution of the heel-strike impulse, independent of M: the trunk (m2, J_c = I2)
/// receives the impulse P at the hip from the leg; the leg (J1 about the pivot; its telescopic
/// part massless) receives −P at the hip, whose axial part goes straight to the ground; after
/// the impact the hip moves as the leg's tip, v_h⁺ = ω1⁺ × r_h (no velocity along the leg).
/// Unknowns (Px, Py, ω1⁺, Δω2, Δv_cx, Δv_cy), angular rates counter-clockwise (ω = −θ̇).
/// Returns (hip velocity after, trunk rate θ̇2 after).
fn heel_strike_newton_euler(
    body: &Body,
    q: &Vector3<f64>,
    hip_vel: [f64; 2],
    trunk_rate: f64,
) -> ([f64; 2], f64) {
    let geo = StanceGeo::new(body, 9.81);
    let [_, hip, trunk] = geo.points(q);
    let rh = [hip[0], hip[1] - body.l9]; // hip from the pivot
    let d = [hip[0] - trunk[0], hip[1] - trunk[1]]; // hip from the trunk CoM
    let (w, u) = (q[0], [q[1].sin(), q[1].cos()]);
    // pre-impact leg rate: the transverse part of the hip velocity
    let omega1_minus = cross(rh, hip_vel) / (w * w);
    let j1 = body.m1 * body.r1 * body.r1 + body.i1;
    let mut a = SMatrix::<f64, 6, 6>::zeros();
    let mut rhs = SVector::<f64, 6>::zeros();
    // m2 Δv_c − P = 0
    a[(0, 4)] = body.m2;
    a[(0, 0)] = -1.0;
    a[(1, 5)] = body.m2;
    a[(1, 1)] = -1.0;
    // I2 Δω2 − d × P = 0
    a[(2, 3)] = body.i2;
    a[(2, 0)] = d[1];
    a[(2, 1)] = -d[0];
    // J1 (ω1⁺ − ω1⁻) + r_h × P = 0
    a[(3, 2)] = j1;
    a[(3, 0)] = -rh[1];
    a[(3, 1)] = rh[0];
    rhs[3] = j1 * omega1_minus;
    // v_h⁻ + Δv_c + Δω2 × d − ω1⁺ × r_h = 0  (ω × r = ω (−r_y, r_x))
    a[(4, 4)] = 1.0;
    a[(4, 3)] = -d[1];
    a[(4, 2)] = rh[1];
    rhs[4] = -hip_vel[0];
    a[(5, 5)] = 1.0;
    a[(5, 3)] = d[0];
    a[(5, 2)] = -rh[0];
    rhs[5] = -hip_vel[1];
    let x = a.lu().solve(&rhs).expect("regular impulse system");
    let v_after = [-x[2] * rh[1], x[2] * rh[0]];
    assert!((v_after[0] * u[0] + v_after[1] * u[1]).abs() < 1e-12);
    (v_after, trunk_rate - x[3])
}

/// The impulse agrees with the Newton–Euler solution at random states (hip velocity and trunk
/// rate after the impact).
#[test]
fn heel_strike_matches_newton_euler() {
    let mut rng = Rng(11);
    let mut worst = 0.0_f64;
    for body in bodies() {
        let model = StanceModel::new(&body);
        let geo = StanceGeo::new(&body, model.g);
        for _ in 0..50 {
            let (q, _) = random_stance_state(&mut rng);
            let v = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
            let trunk = rng.uniform(-3.0, 3.0);
            let (qd_plus, _) =
                impact::heel_strike(&model, &q, &impact::rates_about_pivot(&q, v, trunk), 1.0);
            let [_, vh, _] = geo.velocities(&q, &qd_plus);
            let (vh_ne, trunk_ne) = heel_strike_newton_euler(&body, &q, v, trunk);
            let e = (vh[0] - vh_ne[0])
                .abs()
                .max((vh[1] - vh_ne[1]).abs())
                .max((qd_plus[2] - trunk_ne).abs());
            assert!(
                e < 1e-10,
                "impulse vs Newton–Euler: {vh:?} {} vs {vh_ne:?} {trunk_ne}",
                qd_plus[2]
            );
            worst = worst.max(e);
        }
    }
    eprintln!("heel strike vs Newton–Euler: worst abs. error {worst:.2e}");
}

/// Compass-gait-like collision (θ = 0.45 rad): the body moves with the hip velocity
/// V (cos θ, −sin θ) of the old leg (perpendicular to it), trunk upright, trunk rate 0; the new
/// leg is at −θ. Checked: `rates_about_pivot` (ẇ⁻ = −V sin 2θ, w θ̇1⁻ = V cos 2θ), the surviving
/// hip-speed ratio against Newton–Euler and against the closed form
///   ratio = cos 2θ + w sin 2θ · C D / (B E − D²),
/// B = J1 + m2 w², C = m2 a sin(θ1 − θ2), D = m2 a w cos(θ1 − θ2), E = J2 (docs/dynamics.md),
/// and its point-mass-trunk limit cos 2θ (a = 0). With the new leg ahead of an upright trunk
/// C D < 0, so the ratio is below cos 2θ: see `heel_strike_speed_ratio_in_the_spec_band`.
#[test]
fn heel_strike_compass_gait_speed_ratio() {
    let theta: f64 = 0.45;
    for body in bodies() {
        let model = StanceModel::new(&body);
        let geo = StanceGeo::new(&body, model.g);
        let big_v = 1.3;
        let v = [big_v * theta.cos(), -big_v * theta.sin()];
        let q = Vector3::new(body.l1, -theta, 0.0);
        let qd_minus = impact::rates_about_pivot(&q, v, 0.0);
        assert!((qd_minus[0] + big_v * (2.0 * theta).sin()).abs() < 1e-14);
        assert!((qd_minus[1] * body.l1 - big_v * (2.0 * theta).cos()).abs() < 1e-14);
        let [_, vh, _] = geo.velocities(&q, &qd_minus);
        assert!((vh[0] - v[0]).abs() < 1e-14 && (vh[1] - v[1]).abs() < 1e-14);
        let (qd_plus, report) = impact::heel_strike(&model, &q, &qd_minus, 1.0);
        let [_, vh_plus, _] = geo.velocities(&q, &qd_plus);
        let ratio = speed(vh_plus) / big_v;
        assert!((report.speed_ratio - ratio).abs() < 1e-12);
        let (vh_ne, _) = heel_strike_newton_euler(&body, &q, v, 0.0);
        assert!((speed(vh_ne) / big_v - ratio).abs() < 1e-12);
        let (w, a) = (body.l1, body.r2);
        let b = body.m1 * body.r1 * body.r1 + body.i1 + body.m2 * w * w;
        let c = body.m2 * a * (-theta).sin();
        let d = body.m2 * a * w * theta.cos();
        let e = body.m2 * a * a + body.i2;
        let closed = (2.0 * theta).cos() + w * (2.0 * theta).sin() * c * d / (b * e - d * d);
        assert!((closed - ratio).abs() < 1e-12, "{closed} vs {ratio}");
        // point-mass trunk at the hip: only the velocity across the new leg survives
        let mut point = model;
        point.a = 0.0;
        let (_, r) = impact::heel_strike(&point, &q, &impact::rates_about_pivot(&q, v, 0.0), 1.0);
        assert!((r.speed_ratio - (2.0 * theta).cos()).abs() < 1e-12);
        eprintln!(
            "compass gait θ = {theta}: H = {} m, hip speed ratio {ratio:.4} (cos 2θ = {:.4}, cos θ = {:.4}), trunk rate after {:.3} rad/s",
            body.height,
            (2.0 * theta).cos(),
            theta.cos(),
            qd_plus[2]
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Knee lock (spec §5)
// ---------------------------------------------------------------------------------------------

/// θ̇4⁺ = 0, the leg's angular momentum about the hip is conserved, and the lock loses energy.
#[test]
fn knee_lock_keeps_the_angular_momentum_about_the_hip() {
    let mut rng = Rng(8);
    let mut worst = 0.0_f64;
    for body in bodies() {
        let model = SwingModel::new(&body);
        let geo = SwingGeo::new(&body, model.g);
        for _ in 0..60 {
            let (q, qd) = random_swing_state(&mut rng);
            let after = impact::knee_lock(&model, &q, &qd);
            let l0 = geo.angular_momentum_about_hip(&q, &qd);
            // the first row of M q̇ is this momentum (clockwise +, as θ3 turns)
            let row = (model.mass_matrix(&q) * qd)[0];
            assert!(
                (row + l0).abs() < 1e-12 * row.abs().max(1.0),
                "row {row} vs L {l0}"
            );
            assert_eq!(after[1], 0.0);
            let l1 = geo.angular_momentum_about_hip(&q, &after);
            let e = (l1 - l0).abs() / l0.abs().max(1e-3);
            assert!(e < 1e-12, "angular momentum about the hip changed by {e:e}");
            worst = worst.max(e);
            let (t0, t1) = (geo.kinetic(&q, &qd), geo.kinetic(&q, &after));
            assert!(
                t1 <= t0 * (1.0 + 1e-12),
                "knee lock created energy: {t0} → {t1}"
            );
        }
    }
    eprintln!("knee lock: worst rel. change of the angular momentum about the hip {worst:.2e}");
}

// ---------------------------------------------------------------------------------------------
// Stance hip kinematics
// ---------------------------------------------------------------------------------------------

/// Along q(t) = q0 + q̇0 t + ½ q̈0 t²: `hip` is the independent hip point, `hip_velocity` its
/// time derivative and `hip_acceleration` its second derivative (central differences of the
/// velocity, step 1e-5: truncation ~1e-10, rounding ~1e-11 m/s²; and second differences of the
/// independent position, step 1e-4: ~1e-7).
#[test]
fn stance_hip_acceleration_is_the_second_derivative_of_the_hip() {
    let mut rng = Rng(9);
    let body = default_body();
    let model = StanceModel::new(&body);
    let geo = StanceGeo::new(&body, model.g);
    let (mut worst_v, mut worst_a, mut worst_a2) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..60 {
        let (q0, qd0) = random_stance_state(&mut rng);
        let qdd0 = Vector3::new(
            rng.uniform(-10.0, 10.0),
            rng.uniform(-10.0, 10.0),
            rng.uniform(-10.0, 10.0),
        );
        let q = |t: f64| q0 + qd0 * t + qdd0 * (0.5 * t * t);
        let qd = |t: f64| qd0 + qdd0 * t;
        let [_, hip, _] = geo.points(&q0);
        let mh = model.hip(&q0);
        assert!((mh[0] - hip[0]).abs() < 1e-15 && (mh[1] - hip[1]).abs() < 1e-15);
        let h = 1e-5;
        let v = model.hip_velocity(&q0, &qd0);
        let (pp, pm) = (geo.points(&q(h))[1], geo.points(&q(-h))[1]);
        let a = model.hip_acceleration(&q0, &qd0, &qdd0);
        let (vp, vm) = (
            model.hip_velocity(&q(h), &qd(h)),
            model.hip_velocity(&q(-h), &qd(-h)),
        );
        let h2 = 1e-4;
        let (pp2, pm2) = (geo.points(&q(h2))[1], geo.points(&q(-h2))[1]);
        let a_scale = speed(a).max(1.0);
        for c in 0..2 {
            let ev = ((pp[c] - pm[c]) / (2.0 * h) - v[c]).abs() / speed(v).max(1.0);
            let ea = ((vp[c] - vm[c]) / (2.0 * h) - a[c]).abs() / a_scale;
            let ea2 = ((pp2[c] - 2.0 * hip[c] + pm2[c]) / (h2 * h2) - a[c]).abs() / a_scale;
            worst_v = worst_v.max(ev);
            worst_a = worst_a.max(ea);
            worst_a2 = worst_a2.max(ea2);
        }
    }
    eprintln!(
        "hip kinematics: worst rel. error velocity {worst_v:.2e}, acceleration (FD of velocity) {worst_a:.2e}, (2nd FD of position) {worst_a2:.2e}"
    );
    assert!(worst_v < 1e-8 && worst_a < 1e-8 && worst_a2 < 1e-5);
}

/// Along a simulated stance trajectory (leg spring, as in the energy test) the hip acceleration
/// computed from the model's q̈ equals the finite difference of the hip velocity between two
/// nearby integrated states.
#[test]
fn stance_hip_acceleration_along_a_trajectory() {
    let body = default_body();
    let model = StanceModel::new(&body);
    let l1 = body.l1;
    let kw = body.m2 * (2.0 * std::f64::consts::PI * 5.0).powi(2);
    let sys = StanceSpring {
        model,
        kw,
        l1,
        locked: false,
    };
    let y0 = State6::from_row_slice(&[l1, -0.3, 0.05, 0.0, 1.5, 0.0]);
    let h = 1e-4;
    // three states t − h, t, t + h, from the same start (tight tolerance: FD of the solution)
    let states: Vec<State6> = [0.2 - h, 0.2, 0.2 + h]
        .iter()
        .map(|&t_end| {
            let sys = StanceSpring {
                model,
                kw,
                l1,
                locked: false,
            };
            let mut s = Dopri5::from_param(
                sys,
                0.0,
                t_end,
                t_end,
                y0,
                1e-13,
                1e-13,
                0.9,
                0.04,
                0.2,
                10.0,
                t_end,
                0.0,
                100_000,
                1000,
                OutputType::Sparse,
            );
            s.integrate().unwrap();
            assert_eq!(*s.x_out().last().unwrap(), t_end);
            *s.y_out().last().unwrap()
        })
        .collect();
    let split = |y: &State6| {
        (
            Vector3::new(y[0], y[1], y[2]),
            Vector3::new(y[3], y[4], y[5]),
        )
    };
    let (q, qd) = split(&states[1]);
    let mut dy = State6::zeros();
    sys.system(0.2, &states[1], &mut dy);
    let qdd = Vector3::new(dy[3], dy[4], dy[5]);
    let a = model.hip_acceleration(&q, &qd, &qdd);
    let (qp, qdp) = split(&states[2]);
    let (qm, qdm) = split(&states[0]);
    let (vp, vm) = (model.hip_velocity(&qp, &qdp), model.hip_velocity(&qm, &qdm));
    let fd = [(vp[0] - vm[0]) / (2.0 * h), (vp[1] - vm[1]) / (2.0 * h)];
    let e = ((fd[0] - a[0]).abs()).max((fd[1] - a[1]).abs()) / speed(a).max(1.0);
    eprintln!("hip acceleration along a trajectory: {a:?} vs FD {fd:?}, rel. error {e:.2e}");
    assert!(e < 1e-5, "{a:?} vs {fd:?}");
}

/// The swing model's joints and ankle Jacobian follow the geometry (knee = hip + l3 (−s3, −c3),
/// ankle = knee + l4 (−sφ, −cφ)).
#[test]
fn swing_joints_and_ankle_jacobian() {
    let mut rng = Rng(10);
    let body = default_body();
    let model = SwingModel::new(&body);
    for _ in 0..50 {
        let (q, qd) = random_swing_state(&mut rng);
        let hip = [rng.uniform(-1.0, 1.0), rng.uniform(0.5, 1.0)];
        let (knee, ankle) = model.joints(hip, &q);
        let ((s3, c3), (sp, cp)) = (q[0].sin_cos(), (q[0] + q[1]).sin_cos());
        let k = [hip[0] - body.l3 * s3, hip[1] - body.l3 * c3];
        let an = [k[0] - body.l4 * sp, k[1] - body.l4 * cp];
        for c in 0..2 {
            assert!((knee[c] - k[c]).abs() < 1e-15 && (ankle[c] - an[c]).abs() < 1e-15);
        }
        let h = 1e-6;
        let (_, ap) = model.joints(hip, &(q + qd * h));
        let (_, am) = model.joints(hip, &(q - qd * h));
        let v = model.ankle_velocity(&q, &qd);
        for c in 0..2 {
            assert!(((ap[c] - am[c]) / (2.0 * h) - v[c]).abs() < 1e-8);
        }
        let j: Matrix2<f64> = model.ankle_jacobian(&q);
        assert!((j * qd - Vector2::new(v[0], v[1])).amax() < 1e-15);
    }
}
