//! The coefficients of klaw's two Runge–Kutta pairs: Dormand–Prince 5(4) (Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, Table II.5.2, dense output II.6) and Dormand–Prince 8(5,3) (II.10,
//! and Hairer's DOP853 code).
//!
//! klaw keeps its own DOP853 because ode_solvers 0.6.2's DOP853 tableau has c12 = 0 instead of 1:
//! it evaluates the 12th stage at t instead of t + h, so in the walk's time-dependent phases it
//! took tiny steps and reported stiffness. ode_solvers stays a dev-dependency: its Dopri5 checks
//! the models and the integration across the forces' breaks (`tests/dynamics.rs`,
//! `tests/breaks.rs`), and the test below checks both pairs' orders on a non-autonomous problem.

/// Dormand–Prince 5(4): the stages, the error estimator and the dense output's r4 (Hairer,
/// Nørsett & Wanner, Table II.5.2 and II.6).
pub mod dopri5 {
    pub const C2: f64 = 1.0 / 5.0;
    pub const C3: f64 = 3.0 / 10.0;
    pub const C4: f64 = 4.0 / 5.0;
    pub const C5: f64 = 8.0 / 9.0;
    pub const A21: f64 = 1.0 / 5.0;
    pub const A31: f64 = 3.0 / 40.0;
    pub const A32: f64 = 9.0 / 40.0;
    pub const A41: f64 = 44.0 / 45.0;
    pub const A42: f64 = -56.0 / 15.0;
    pub const A43: f64 = 32.0 / 9.0;
    pub const A51: f64 = 19372.0 / 6561.0;
    pub const A52: f64 = -25360.0 / 2187.0;
    pub const A53: f64 = 64448.0 / 6561.0;
    pub const A54: f64 = -212.0 / 729.0;
    pub const A61: f64 = 9017.0 / 3168.0;
    pub const A62: f64 = -355.0 / 33.0;
    pub const A63: f64 = 46732.0 / 5247.0;
    pub const A64: f64 = 49.0 / 176.0;
    pub const A65: f64 = -5103.0 / 18656.0;
    pub const A71: f64 = 35.0 / 384.0;
    pub const A73: f64 = 500.0 / 1113.0;
    pub const A74: f64 = 125.0 / 192.0;
    pub const A75: f64 = -2187.0 / 6784.0;
    pub const A76: f64 = 11.0 / 84.0;
    pub const E1: f64 = 71.0 / 57600.0;
    pub const E3: f64 = -71.0 / 16695.0;
    pub const E4: f64 = 71.0 / 1920.0;
    pub const E5: f64 = -17253.0 / 339200.0;
    pub const E6: f64 = 22.0 / 525.0;
    pub const E7: f64 = -1.0 / 40.0;
    pub const D1: f64 = -12715105075.0 / 11282082432.0;
    pub const D3: f64 = 87487479700.0 / 32700410799.0;
    pub const D4: f64 = -10690763975.0 / 1880347072.0;
    pub const D5: f64 = 701980252875.0 / 199316789632.0;
    pub const D6: f64 = -1453857185.0 / 822651844.0;
    pub const D7: f64 = 69997945.0 / 29380423.0;
}

/// Dormand–Prince 8(5,3) (Hairer, Nørsett & Wanner, II.10, and Hairer's DOP853 code): the
/// stages, the 5th- and 3rd-order error estimators, the dense output of order 7 with three more
/// stages. The 12th stage is at t + h (c12 = 1).
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
pub mod dop853 {
    pub const A2_1: f64 = 0.05260015195876773;
    pub const A3_1: f64 = 0.0197250569845379;
    pub const A3_2: f64 = 0.0591751709536137;
    pub const A4_1: f64 = 0.02958758547680685;
    pub const A4_3: f64 = 0.08876275643042054;
    pub const A5_1: f64 = 0.2413651341592667;
    pub const A5_3: f64 = -0.8845494793282861;
    pub const A5_4: f64 = 0.924834003261792;
    pub const A6_1: f64 = 0.037037037037037035;
    pub const A6_4: f64 = 0.17082860872947386;
    pub const A6_5: f64 = 0.12546768756682242;
    pub const A7_1: f64 = 0.037109375;
    pub const A7_4: f64 = 0.17025221101954405;
    pub const A7_5: f64 = 0.06021653898045596;
    pub const A7_6: f64 = -0.017578125;
    pub const A8_1: f64 = 0.03709200011850479;
    pub const A8_4: f64 = 0.17038392571223998;
    pub const A8_5: f64 = 0.10726203044637328;
    pub const A8_6: f64 = -0.015319437748624402;
    pub const A8_7: f64 = 0.008273789163814023;
    pub const A9_1: f64 = 0.6241109587160757;
    pub const A9_4: f64 = -3.3608926294469414;
    pub const A9_5: f64 = -0.868219346841726;
    pub const A9_6: f64 = 27.59209969944671;
    pub const A9_7: f64 = 20.154067550477894;
    pub const A9_8: f64 = -43.48988418106996;
    pub const A10_1: f64 = 0.47766253643826434;
    pub const A10_4: f64 = -2.4881146199716677;
    pub const A10_5: f64 = -0.590290826836843;
    pub const A10_6: f64 = 21.230051448181193;
    pub const A10_7: f64 = 15.279233632882423;
    pub const A10_8: f64 = -33.28821096898486;
    pub const A10_9: f64 = -0.020331201708508627;
    pub const A11_1: f64 = -0.9371424300859873;
    pub const A11_4: f64 = 5.186372428844064;
    pub const A11_5: f64 = 1.0914373489967295;
    pub const A11_6: f64 = -8.149787010746927;
    pub const A11_7: f64 = -18.52006565999696;
    pub const A11_8: f64 = 22.739487099350505;
    pub const A11_9: f64 = 2.4936055526796523;
    pub const A11_10: f64 = -3.0467644718982196;
    pub const A12_1: f64 = 2.273310147516538;
    pub const A12_4: f64 = -10.53449546673725;
    pub const A12_5: f64 = -2.0008720582248625;
    pub const A12_6: f64 = -17.9589318631188;
    pub const A12_7: f64 = 27.94888452941996;
    pub const A12_8: f64 = -2.8589982771350235;
    pub const A12_9: f64 = -8.87285693353063;
    pub const A12_10: f64 = 12.360567175794303;
    pub const A12_11: f64 = 0.6433927460157636;
    pub const A14_1: f64 = 0.056167502283047954;
    pub const A14_7: f64 = 0.25350021021662483;
    pub const A14_8: f64 = -0.2462390374708025;
    pub const A14_9: f64 = -0.12419142326381637;
    pub const A14_10: f64 = 0.15329179827876568;
    pub const A14_11: f64 = 0.00820105229563469;
    pub const A14_12: f64 = 0.007567897660545699;
    pub const A14_13: f64 = -0.008298;
    pub const A15_1: f64 = 0.03183464816350214;
    pub const A15_6: f64 = 0.028300909672366776;
    pub const A15_7: f64 = 0.053541988307438566;
    pub const A15_8: f64 = -0.05492374857139099;
    pub const A15_11: f64 = -0.00010834732869724932;
    pub const A15_12: f64 = 0.0003825710908356584;
    pub const A15_13: f64 = -0.00034046500868740456;
    pub const A15_14: f64 = 0.1413124436746325;
    pub const A16_1: f64 = -0.42889630158379194;
    pub const A16_6: f64 = -4.697621415361164;
    pub const A16_7: f64 = 7.683421196062599;
    pub const A16_8: f64 = 4.06898981839711;
    pub const A16_9: f64 = 0.3567271874552811;
    pub const A16_13: f64 = -0.0013990241651590145;
    pub const A16_14: f64 = 2.9475147891527724;
    pub const A16_15: f64 = -9.15095847217987;
    pub const C2: f64 = 0.05260015195876773;
    pub const C3: f64 = 0.0789002279381516;
    pub const C4: f64 = 0.1183503419072274;
    pub const C5: f64 = 0.2816496580927726;
    pub const C6: f64 = 0.3333333333333333;
    pub const C7: f64 = 0.25;
    pub const C8: f64 = 0.3076923076923077;
    pub const C9: f64 = 0.6512820512820513;
    pub const C10: f64 = 0.6;
    pub const C11: f64 = 0.8571428571428571;
    pub const C14: f64 = 0.1;
    pub const C15: f64 = 0.2;
    pub const C16: f64 = 0.7777777777777778;
    pub const B1: f64 = 0.054293734116568765;
    pub const B6: f64 = 4.450312892752409;
    pub const B7: f64 = 1.8915178993145003;
    pub const B8: f64 = -5.801203960010585;
    pub const B9: f64 = 0.3111643669578199;
    pub const B10: f64 = -0.1521609496625161;
    pub const B11: f64 = 0.20136540080403034;
    pub const B12: f64 = 0.04471061572777259;
    pub const BHH1: f64 = 0.2440944881889764;
    pub const BHH2: f64 = 0.7338466882816118;
    pub const BHH3: f64 = 0.022058823529411766;
    pub const ER1: f64 = 0.01312004499419488;
    pub const ER6: f64 = -1.2251564463762044;
    pub const ER7: f64 = -0.4957589496572502;
    pub const ER8: f64 = 1.6643771824549864;
    pub const ER9: f64 = -0.35032884874997366;
    pub const ER10: f64 = 0.3341791187130175;
    pub const ER11: f64 = 0.08192320648511571;
    pub const ER12: f64 = -0.022355307863886294;
    pub const D4: [f64; 16] = [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ];
    pub const D5: [f64; 16] = [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ];
    pub const D6: [f64; 16] = [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ];
    pub const D7: [f64; 16] = [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ];
}

#[cfg(test)]
mod tests {
    use super::super::dense::DenseStep;
    use super::super::problems::{Exponentials, exact};
    use super::super::{Mesh, Method, Segment, integrate_by};
    use nalgebra::SVector;

    /// `method` on `n` equal steps over [0, 2] (a frozen mesh with a tolerance it never leaves):
    /// the end state's error and the dense output's largest error (10 points a step).
    fn fixed_steps(method: Method, n: usize) -> (f64, f64) {
        let h = 2.0 / n as f64;
        let zero = SVector::<f64, 2>::zeros();
        let mesh = Segment {
            t0: 0.0,
            t1: 2.0,
            y0: zero,
            y1: zero,
            steps: (0..n)
                .map(|i| DenseStep {
                    t: i as f64 * h,
                    h,
                    r: [zero; 8],
                    ready: true,
                })
                .collect(),
            pending: Vec::new(),
        };
        let out = integrate_by(
            method,
            &Exponentials,
            0.0,
            exact(0.0),
            2.0,
            1.0,
            Mesh::Aligned(&mesh),
        )
        .unwrap();
        assert!(!out.adapted);
        assert_eq!(out.segment.steps.len(), n);
        let end = (out.segment.y1 - exact(2.0)).amax();
        let dense = (0..=10 * n)
            .map(|i| {
                let t = i as f64 * h / 10.0;
                (out.segment.state(t) - exact(t)).amax()
            })
            .fold(0.0, f64::max);
        (end, dense)
    }

    /// On a non-autonomous problem (a wrong stage time, as ode_solvers' c12, shows there).
    #[test]
    fn both_methods_converge_at_their_orders() {
        // halving the step divides the error by 2^p: DOP853 p = 8 (dense output of order 7:
        // its error per step is O(h^8) too), Dopri5 p = 5 (dense output of order 4: O(h^5))
        for (method, n, p, dense_p) in [
            (Method::Dop853, 8, 8.0, 7.0),
            (Method::Dopri5, 32, 5.0, 4.0),
        ] {
            let (e1, d1) = fixed_steps(method, n);
            let (e2, d2) = fixed_steps(method, 2 * n);
            let order = (e1 / e2).log2();
            assert!(
                (order - p).abs() < 0.6,
                "{method:?}: end-state order {order} ({e1:e}, {e2:e})"
            );
            let dense = (d1 / d2).log2();
            assert!(
                dense > dense_p + 0.5,
                "{method:?}: dense order {dense} ({d1:e}, {d2:e})"
            );
        }
    }
}
