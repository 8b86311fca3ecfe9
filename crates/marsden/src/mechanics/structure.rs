//! Declared structure at scale: checks and shortcuts for separable Lagrangians with many degrees
//! of freedom.
//!
//! [`crate::mechanics::jet`] works with the full AD jet of `L` (second derivatives in `v` against
//! `(t, q, v)`): `O(n)` evaluations of `L` per jet, hopeless for an N-body problem whose `L`
//! alone costs `O(n²)`. For a Lagrangian that declares `L = ½ vᵀ M v − V(t, q)` and has more than
//! [`LARGE`] degrees of freedom, the momenta are `p = M v`, the inverse Legendre transform is
//! `v = M⁻¹ p` and regularity is the invertibility of `M`; the declaration itself is checked by
//! random probes of the three Hessian blocks — `wᵀ(∂²L/∂v²)u = wᵀMu`, `wᵀ(∂²L/∂v∂q)u = 0`,
//! `wᵀ ∂²L/∂v∂t = 0` — each one hyper-dual evaluation ([`crate::numerics::ad::directional_second`]). A
//! block that is wrong fails a probe with probability one; the directions are fixed
//! pseudo-random vectors, so the check is deterministic.

use crate::error::Error;
use crate::error::SetupError;
use crate::mechanics::lagrangian::times_dof;
use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::numerics::ad::{self, MultiFunction};
use crate::numerics::dense::{Lu, PIVOT_TOLERANCE, max_norm};
use crate::scalar::Scalar;

/// Systems with more degrees of freedom than this use the shortcuts of this module.
pub const LARGE: usize = 32;

/// The mass matrix if `l` declares itself separable and is large.
pub fn large_separable<L: Lagrangian + ?Sized>(l: &L) -> Option<MassMatrix> {
    if l.dof() <= LARGE {
        return None;
    }
    separable_mass(l)
}

/// The mass matrix if `l` declares itself separable, whatever its size: the inverse Legendre
/// transform `v = M⁻¹ p` ([`velocity`]) replaces a Newton iteration on AD jets even for one
/// degree of freedom (the energy report of an ensemble member spent 13 % of its time there).
pub fn separable_mass<L: Lagrangian + ?Sized>(l: &L) -> Option<MassMatrix> {
    let Structure::Separable { mass } = l.structure() else {
        return None;
    };
    Some(mass)
}

/// `p = M v`.
pub fn momentum(mass: &MassMatrix, v: &[f64], p: &mut [f64]) {
    match mass {
        MassMatrix::Diagonal(d) => {
            for ((pi, m), vi) in p.iter_mut().zip(d).zip(v) {
                *pi = m * vi;
            }
        }
        MassMatrix::Dense(m) => {
            let n = v.len();
            for (i, pi) in p.iter_mut().enumerate() {
                *pi = m[i * n..(i + 1) * n]
                    .iter()
                    .zip(v)
                    .map(|(a, b)| a * b)
                    .sum();
            }
        }
    }
}

/// `v = M⁻¹ p`, or the singular mass matrix as [`crate::error::SetupError::SingularLagrangian`]
/// (a diagonal entry or an elimination pivot at most `1e-13` of the largest entry, as in
/// [`Lu`]).
pub fn velocity(
    mass: &MassMatrix,
    t: f64,
    q: &[f64],
    p: &[f64],
    v: &mut [f64],
) -> Result<(), Error> {
    let singular = |pivot: f64, scale: f64| {
        Error::Setup(SetupError::SingularLagrangian {
            t,
            q: q.to_vec(),
            v: v.to_vec(),
            pivot,
            scale,
        })
    };
    match mass {
        MassMatrix::Diagonal(d) => {
            let scale = max_norm(d);
            let tiny = |m: &&f64| m.is_nan() || m.abs() <= PIVOT_TOLERANCE * scale;
            if let Some(&m) = d.iter().find(tiny) {
                return Err(singular(m, scale));
            }
            for ((vi, m), pi) in v.iter_mut().zip(d).zip(p) {
                *vi = pi / m;
            }
        }
        MassMatrix::Dense(dense) => {
            let n = p.len();
            let mut lu = Lu::new();
            lu.factor(dense, n)
                .map_err(|e| singular(e.pivot, max_norm(dense)))?;
            v.copy_from_slice(p);
            lu.solve(v, &mut Vec::with_capacity(n));
        }
    }
    Ok(())
}

/// `L` as a function of `z = (t, q, v)`.
struct OnTangentBundle<'a, L: ?Sized>(&'a L);

impl<L: Lagrangian + ?Sized> MultiFunction for OnTangentBundle<'_, L> {
    const MAX_INPUTS: Option<usize> = times_dof(L::FIXED_DOF, 2, 1);
    fn inputs(&self) -> usize {
        2 * self.0.dof() + 1
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let n = self.0.dof();
        out[0] = self.0.lagrangian(z[0], &z[1..=n], &z[n + 1..]);
    }
}

/// A fixed pseudo-random direction with entries in `[−1, 1]` (xorshift, seeded by `seed`).
fn direction(len: usize, seed: u64) -> Vec<f64> {
    let mut s = seed | 1;
    (0..len)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

/// Checks `L = ½ vᵀ M v − V(t, q)` at `(t, q, v)` by probes of the Hessian blocks (relative
/// 1e-10, as [`crate::mechanics::check_structure`]).
pub fn check_by_probes<L: Lagrangian + ?Sized>(
    l: &L,
    mass: &MassMatrix,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> Result<(), Error> {
    let n = q.len();
    let mut z = Vec::with_capacity(2 * n + 1);
    z.push(t);
    z.extend_from_slice(q);
    z.extend_from_slice(v);
    let f = OnTangentBundle(l);
    let scale = match mass {
        MassMatrix::Diagonal(d) => max_norm(d),
        MassMatrix::Dense(m) => max_norm(m),
    }
    .max(1.0);
    for probe in 0..2u64 {
        let (w, u) = (direction(n, 17 + probe), direction(n, 91 + probe));
        let mut mu = vec![0.0; n];
        momentum(mass, &u, &mut mu);
        let wmu: f64 = w.iter().zip(&mu).map(|(a, b)| a * b).sum();
        let seed_v = |x: &[f64]| -> Vec<f64> {
            std::iter::once(0.0)
                .chain(vec![0.0; n])
                .chain(x.iter().copied())
                .collect()
        };
        let seed_q: Vec<f64> = std::iter::once(0.0)
            .chain(u.iter().copied())
            .chain(vec![0.0; n])
            .collect();
        let mut seed_t = vec![0.0; 2 * n + 1];
        seed_t[0] = 1.0;
        let wv = seed_v(&w);
        let blocks = [
            (
                "∂²L/∂v² against the mass matrix",
                ad::directional_second(&f, &z, &wv, &seed_v(&u)) - wmu,
            ),
            ("∂²L/∂v∂q", ad::directional_second(&f, &z, &wv, &seed_q)),
            ("∂²L/∂v∂t", ad::directional_second(&f, &z, &wv, &seed_t)),
        ];
        if let Some((what, defect)) = blocks
            .iter()
            .find(|(_, d)| d.is_nan() || d.abs() > 1e-10 * scale * n as f64)
        {
            return Err(Error::Setup(SetupError::StructureMismatch {
                q: q.to_vec(),
                v: v.to_vec(),
                what,
                defect: *defect,
            }));
        }
    }
    Ok(())
}

/// `M⁻¹` of a separable Lagrangian, ready to apply.
#[derive(Debug, Clone)]
pub enum InverseMass {
    /// Reciprocals of a diagonal mass matrix.
    Diagonal(Vec<f64>),
    /// LU factors of a dense mass matrix.
    Dense(Lu),
}

impl InverseMass {
    /// `M⁻¹` if `structure` is separable with an invertible mass matrix.
    pub fn of(structure: &Structure) -> Option<Self> {
        let Structure::Separable { mass } = structure else {
            return None;
        };
        match mass {
            MassMatrix::Diagonal(d) if d.iter().all(|m| *m != 0.0 && m.is_finite()) => {
                Some(Self::Diagonal(d.iter().map(|m| 1.0 / m).collect()))
            }
            MassMatrix::Diagonal(_) => None,
            MassMatrix::Dense(m) => {
                let n = (m.len() as f64).sqrt().round() as usize;
                let mut lu = Lu::new();
                lu.factor(m, n).ok().map(|_| Self::Dense(lu))
            }
        }
    }

    /// `x ← M⁻¹ x` (`scratch` for the dense solve).
    #[inline]
    pub fn apply(&self, x: &mut [f64], scratch: &mut Vec<f64>) {
        match self {
            Self::Diagonal(d) => x.iter_mut().zip(d).for_each(|(v, di)| *v *= di),
            Self::Dense(lu) => lu.solve(x, scratch),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics;
    use crate::systems::DoublePendulum;

    /// `L = ½ vᵀ M v − V(q)` with the dense mass matrix `M = [[2, 0.5], [0.5, 1]]` and
    /// `V = cos q₀ + q₁²`, declared separable or not.
    struct Coupled {
        declared: bool,
    }

    impl Lagrangian for Coupled {
        fn dof(&self) -> usize {
            2
        }
        fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
            let kinetic = v[0] * v[0] + v[0] * v[1] * 0.5 + v[1] * v[1] * 0.5;
            kinetic - q[0].cos() - q[1] * q[1]
        }
        fn structure(&self) -> Structure {
            if self.declared {
                Structure::Separable {
                    mass: MassMatrix::Dense(vec![2.0, 0.5, 0.5, 1.0]),
                }
            } else {
                Structure::General
            }
        }
    }

    /// The shortcut `v = M⁻¹ p` of a small separable system agrees with the Newton inverse of
    /// the AD Legendre transform (its tolerance is 1e-14 relative).
    #[test]
    fn separable_inverse_legendre_matches_the_newton_inverse() {
        let (q, p) = ([0.3, -0.2], [1.5, -0.7]);
        let mut shortcut = [0.0; 2];
        let mut newton = [0.0; 2];
        mechanics::velocity(&Coupled { declared: true }, 0.0, &q, &p, &mut shortcut).unwrap();
        mechanics::velocity(&Coupled { declared: false }, 0.0, &q, &p, &mut newton).unwrap();
        // M⁻¹ = [[1, −0.5], [−0.5, 2]] / 1.75.
        let exact = [(1.5 + 0.35) / 1.75, (-0.75 - 1.4) / 1.75];
        for i in 0..2 {
            assert!((shortcut[i] - exact[i]).abs() < 1e-15, "{shortcut:?}");
            assert!((newton[i] - exact[i]).abs() < 1e-14, "{newton:?}");
        }
    }

    /// A zero diagonal mass is reported with its pivot, without a dense factorisation.
    #[test]
    fn singular_diagonal_mass_is_an_error() {
        let mass = MassMatrix::Diagonal(vec![1.0, 0.0, 2.0]);
        let mut v = [0.0; 3];
        let err = velocity(&mass, 0.5, &[0.0; 3], &[1.0; 3], &mut v).unwrap_err();
        assert!(
            matches!(err, Error::Setup(SetupError::SingularLagrangian { pivot, scale, .. }) if pivot == 0.0 && scale == 2.0),
            "{err:?}"
        );
        // The double pendulum is not separable: no shortcut.
        assert!(separable_mass(&DoublePendulum::default()).is_none());
    }
}
