//! Tests of the elliptic integrals and Jacobi functions against tabulated values (computed with
//! mpmath at 50 digits, agreeing with A&S tables 17.1/17.5 and DLMF 19/22 where those overlap)
//! and against identities.

use super::*;
use proptest::prelude::*;
use std::f64::consts::FRAC_PI_2;

/// `|a − b| ≤ tol · max(1, |b|)`.
fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn complete_first_kind_table() {
    let table = [
        (-2.0, 1.17142008414677),
        (0.0, FRAC_PI_2),
        (0.1, 1.6124413487202194),
        (0.5, 1.8540746773013719),
        (0.9, 2.5780921133481733),
        (0.99, 3.695637362989874),
        (0.999999, 8.294051463601063),
        (0.999999999999, 15.201815980070121),
    ];
    for (m, k) in table {
        let got = ellip_k(m).unwrap();
        assert!(close(got, k, 4e-16), "K({m}) = {got}, expected {k}");
    }
    assert_eq!(ellip_k(0.0).unwrap(), FRAC_PI_2);
}

#[test]
fn complete_second_kind_table() {
    let table = [
        (-2.0, 2.184438142746201),
        (0.0, FRAC_PI_2),
        (0.1, 1.5307576368977631),
        (0.5, 1.3506438810476755),
        (0.9, 1.1047747327040733),
        (0.99, 1.015993545025224),
        (0.999999, 1.0000038970261722),
        (1.0, 1.0),
    ];
    for (m, e) in table {
        let got = ellip_e(m).unwrap();
        assert!(close(got, e, 2e-15), "E({m}) = {got}, expected {e}");
    }
}

#[test]
fn legendre_relation() {
    // E K' + E' K − K K' = π/2 (DLMF 19.7.1).
    for m in [0.1, 0.3, 0.5, 0.77, 0.95] {
        let (k, e) = (ellip_k(m).unwrap(), ellip_e(m).unwrap());
        let (kp, ep) = (ellip_k(1.0 - m).unwrap(), ellip_e(1.0 - m).unwrap());
        assert!(close(e * kp + ep * k - k * kp, FRAC_PI_2, 4e-15));
    }
}

#[test]
fn carlson_rf_reference_values() {
    // Carlson (1995) test values, to full precision (mpmath `elliprf`).
    let rf = |x, y, z| carlson_rf(x, y, z).unwrap();
    assert!(close(rf(1.0, 2.0, 0.0), 1.3110287771460599, 4e-16));
    assert!(close(rf(2.0, 3.0, 4.0), 0.5840828416771517, 4e-16));
    assert!(close(
        carlson_rf(0.5, 0.5, 0.5).unwrap(),
        2.0_f64.sqrt(),
        2e-16
    ));
    // R_F(0, 1, 1) = π/2.
    assert!(close(carlson_rf(0.0, 1.0, 1.0).unwrap(), FRAC_PI_2, 2e-16));
}

#[test]
fn incomplete_first_kind_table() {
    let table = [
        (0.3, 0.2, 0.3008909959134638),
        (1.2, 0.9, 1.5648981345066715),
        (-2.5, 0.5, -3.0444084774872615),
        (7.0, 0.8, 9.799014417204505),
        (1.5, 1.0, 3.340677542798311),
        (1.0, -1.5, 0.8600008142369597),
        (100.0, 0.3, 109.15062486019868),
        (1.57, 0.999999, 7.564254009606073),
    ];
    for (phi, m, f) in table {
        let got = ellip_f(phi, m).unwrap();
        assert!(close(got, f, 1e-15), "F({phi}|{m}) = {got}, expected {f}");
    }
}

#[test]
fn incomplete_is_quasi_periodic_and_odd() {
    let m = 0.64;
    let k = ellip_k(m).unwrap();
    for phi in [0.0, 0.4, 1.3, -0.9] {
        let f = ellip_f(phi, m).unwrap();
        assert!(close(ellip_f(-phi, m).unwrap(), -f, 1e-16));
        for n in [-3.0, -1.0, 1.0, 5.0] {
            let shifted = ellip_f(phi + n * std::f64::consts::PI, m).unwrap();
            assert!(close(shifted, f + 2.0 * n * k, 4e-16), "phi={phi}, n={n}");
        }
    }
}

#[test]
fn jacobi_table() {
    #[rustfmt::skip]
    let table = [
        (0.3, 0.1, 0.2950981243043688, 0.9554669523495009, 0.9956363340613903, 0.2995582147897118),
        (0.3, 0.5, 0.2934127331684554, 0.9559858618277871, 0.9782405041743613, 0.2977947491298303),
        (0.3, 0.9, 0.2917320478186185, 0.9565000848277826, 0.9609386926583817, 0.2960371572164137),
        (0.3, 0.999999, 0.2913126166444719, 0.9566279106234309, 0.9566279549787323, 0.29559868036758413),
        (1.7, 0.1, 0.9965511708864191, -0.08298050255877609, 0.949046140280066, 1.6538723563401991),
        (1.7, 0.5, 0.9940477007408606, 0.10894571424250053, 0.7112907874603075, 1.461633937413691),
        (1.7, 0.9, 0.9522305421080186, 0.30538008231819724, 0.42887211987841084, 1.2604587735776778),
        (1.7, 0.999999, 0.9354092513260476, 0.35356687137462867, 0.3535681087486691, 1.2094147912874704),
        (-2.9, 0.1, -0.31866752714944346, -0.9478665555554002, 0.9949095942416305, -2.8172692590622868),
        (-2.9, 0.5, -0.6960517139200397, -0.7179916514479643, 0.8704918183271383, -2.371708991179054),
        (-2.9, 0.9, -0.9946607832063695, -0.10319848037297624, 0.331036151675557, -1.6741788666745294),
        (-2.9, 0.999999, -0.9939634071119683, 0.10971210198682552, 0.10971660442076353, -1.4608629279325744),
        (12.5, 0.1, -0.3880381633762028, 0.9216433061459425, 0.9924427632747203, 12.167868606928295),
        (12.5, 0.5, -0.9411735393366553, -0.3379236139314823, 0.7463887622588223, 10.65086443335855),
        (12.5, 0.9, 0.9920336525975754, 0.12597314044633953, 0.33805666522422223, 7.727672908663259),
        (12.5, 0.999999, 0.999437872687519, -0.0335251940761949, 0.033540088161898504, 1.6043278040929847),
    ];
    for (u, m, s, c, d, a) in table {
        let j = jacobi(u, m).unwrap();
        let tol = 2e-15;
        assert!(close(j.sn, s, tol), "sn({u}|{m}) = {}, expected {s}", j.sn);
        assert!(close(j.cn, c, tol), "cn({u}|{m}) = {}, expected {c}", j.cn);
        assert!(close(j.dn, d, tol), "dn({u}|{m}) = {}, expected {d}", j.dn);
        assert!(close(j.am, a, tol), "am({u}|{m}) = {}, expected {a}", j.am);
    }
}

#[test]
fn jacobi_large_argument() {
    // u = 100: reduction modulo 2K keeps ~ε·|u| accuracy.
    #[rustfmt::skip]
    let table = [
        (0.1, -0.02863207450906621, -0.9995900181120795, 0.9999590093753498, 97.41800824931177),
        (0.5, 0.11960192815774341, -0.9928219270246553, 0.9964174272815962, 84.70311272411382),
        (0.9, -0.9837917445685971, -0.17931481622742795, 0.35907996739836184, 61.08076681039805),
        (0.999999, 0.43931563576590493, 0.8983327736265658, 0.8983328810467902, 19.304392636950475),
    ];
    for (m, s, c, d, a) in table {
        let j = jacobi(100.0, m).unwrap();
        let tol = 1e-13;
        assert!(close(j.sn, s, tol) && close(j.cn, c, tol), "m={m}: {j:?}");
        assert!(close(j.dn, d, tol) && close(j.am, a, tol), "m={m}: {j:?}");
    }
}

#[test]
fn limits_m_zero_and_one() {
    for u in [-7.3, -1.0, 0.0, 0.25, 2.0, 31.0] {
        let j = jacobi(u, 0.0).unwrap();
        assert_eq!((j.sn, j.cn, j.dn, j.am), (u.sin(), u.cos(), 1.0, u));
        let h = jacobi(u, 1.0).unwrap();
        assert!(close(h.sn, u.tanh(), 1e-16) && close(h.dn, 1.0 / u.cosh(), 1e-16));
        // m → 1 from below: sn → tanh with error O(m₁ sinh² u) while |u| ≪ K ≈ 17.6.
        if u.abs() < 8.0 {
            let near = jacobi(u, 1.0 - 1e-14).unwrap();
            assert!(close(near.sn, u.tanh(), 1e-12), "u={u}: {near:?}");
        }
        // small m: sn → sin.
        let small = jacobi(u, 1e-20).unwrap();
        assert!(close(small.sn, u.sin(), 1e-14), "u={u}: {small:?}");
    }
}

#[test]
fn quarter_periods() {
    for m in [0.05, 0.5, 0.9, 0.999] {
        let k = ellip_k(m).unwrap();
        let at_k = jacobi(k, m).unwrap();
        assert!(close(at_k.sn, 1.0, 1e-15) && at_k.cn.abs() < 1e-15);
        assert!(close(at_k.dn, (1.0 - m).sqrt(), 1e-15) && close(at_k.am, FRAC_PI_2, 1e-15));
        let at_2k = jacobi(2.0 * k, m).unwrap();
        assert!(at_2k.sn.abs() < 1e-15 && close(at_2k.cn, -1.0, 1e-15));
        for u in [0.2, 1.1, -2.4] {
            let (a, b) = (jacobi(u, m).unwrap(), jacobi(u + 4.0 * k, m).unwrap());
            assert!(close(a.sn, b.sn, 1e-14) && close(a.cn, b.cn, 1e-14));
            let c = jacobi(u + 2.0 * k, m).unwrap();
            assert!(close(c.sn, -a.sn, 1e-14) && close(c.dn, a.dn, 1e-14));
            assert!(close(c.am, a.am + std::f64::consts::PI, 1e-14));
        }
    }
}

#[test]
fn derivatives_by_finite_differences() {
    // Fourth-order central differences: d sn = cn dn, d cn = −sn dn, d dn = −m sn cn, d am = dn.
    let h = 1e-3;
    for m in [0.2, 0.75, 0.99] {
        for u in [-3.1, 0.4, 1.9, 6.5] {
            let at = |x: f64| jacobi(x, m).unwrap();
            let d = |f: &dyn Fn(Jacobi) -> f64| {
                (8.0 * (f(at(u + h)) - f(at(u - h))) - (f(at(u + 2.0 * h)) - f(at(u - 2.0 * h))))
                    / (12.0 * h)
            };
            let j = at(u);
            assert!(close(d(&|j| j.sn), j.cn * j.dn, 1e-10), "m={m}, u={u}");
            assert!(close(d(&|j| j.cn), -j.sn * j.dn, 1e-10), "m={m}, u={u}");
            assert!(close(d(&|j| j.dn), -m * j.sn * j.cn, 1e-10), "m={m}, u={u}");
            assert!(close(d(&|j| j.am), j.dn, 1e-10), "m={m}, u={u}");
        }
    }
}

#[test]
fn invalid_input_is_an_error() {
    assert!(matches!(ellip_k(1.0), Err(SpecialError::Domain { .. })));
    assert!(matches!(
        ellip_k(f64::NAN),
        Err(SpecialError::NotFinite { .. })
    ));
    assert!(ellip_e(1.5).is_err());
    assert!(ellip_f(f64::INFINITY, 0.5).is_err());
    assert!(ellip_f(2.0, 1.0).is_err());
    assert!(ellip_f(0.5, 1.2).is_err());
    assert!(carlson_rf(-1.0, 1.0, 1.0).is_err());
    assert!(carlson_rf(0.0, 0.0, 1.0).is_err());
    assert!(jacobi(0.5, -0.1).is_err());
    assert!(jacobi(0.5, 1.1).is_err());
    assert!(jacobi(f64::NAN, 0.5).is_err());
}

proptest! {
    #[test]
    fn jacobi_identities(u in -50.0_f64..50.0, m in 0.0_f64..1.0) {
        let j = jacobi(u, m).unwrap();
        prop_assert!((j.sn * j.sn + j.cn * j.cn - 1.0).abs() < 4e-16);
        prop_assert!((j.dn * j.dn + m * j.sn * j.sn - 1.0).abs() < 4e-16);
        // am carries an absolute rounding error ~ε|am|.
        let tol = 4e-16 * j.am.abs().max(1.0);
        prop_assert!((j.am.sin() - j.sn).abs() < tol && (j.am.cos() - j.cn).abs() < tol);
    }

    #[test]
    fn am_and_f_are_inverse(u in -40.0_f64..40.0, m in 0.0_f64..0.999) {
        let phi = am(u, m).unwrap();
        let back = ellip_f(phi, m).unwrap();
        prop_assert!(close(back, u, 1e-14), "u={} phi={} back={}", u, phi, back);
    }

    #[test]
    fn sn_is_odd_dn_even(u in -20.0_f64..20.0, m in 0.0_f64..1.0) {
        let (a, b) = (jacobi(u, m).unwrap(), jacobi(-u, m).unwrap());
        prop_assert!(a.sn == -b.sn || (a.sn + b.sn).abs() < 1e-15);
        prop_assert!((a.cn - b.cn).abs() < 1e-15 && (a.dn - b.dn).abs() < 1e-15);
    }
}
