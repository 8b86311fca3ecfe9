//! Distance constraints between point masses: rods, links and pendulum suspensions.
//!
//! For particles with positions `x_a ∈ ℝ^D` stacked in `q = (x₀, x₁, …)`, a rod of length `l`
//! between `a` and `b` (or between `a` and a fixed point) is the holonomic constraint
//!
//! ```text
//!     φ_r(q) = ½ (|x_a − x_b|² − l²) = 0,      Dφ_r = (x_a − x_b)ᵀ on x_a, −(x_a − x_b)ᵀ on x_b,
//! ```
//!
//! so the multiplier `λ_r` is the rod tension divided by its length. These are the constraints of
//! SHAKE/RATTLE in molecular dynamics (Ryckaert, Ciccotti & Berendsen 1977; Andersen 1983) and of
//! pendulums and chains in Cartesian coordinates.

use crate::error::Error;
use crate::error::InputError;
use crate::mechanics::Constraint;
use crate::scalar::Scalar;

/// The other end of a rod.
#[derive(Debug, Clone, PartialEq)]
enum End {
    Particle(usize),
    Point(Vec<f64>),
}

#[derive(Debug, Clone, PartialEq)]
struct Rod {
    a: usize,
    b: End,
    length: f64,
}

/// A set of rods between particles in `D` dimensions (and fixed suspension points).
///
/// ```
/// use marsden::{Constraint, holonomic::DistanceConstraints};
///
/// // A planar double pendulum: bob 0 hangs from the origin, bob 1 from bob 0.
/// let rods = DistanceConstraints::new(2)
///     .anchor(0, &[0.0, 0.0], 1.0).unwrap()
///     .link(0, 1, 1.0).unwrap();
/// let mut phi = [0.0; 2];
/// rods.constraint(&[0.0, -1.0, 1.0, -1.0], &mut phi);
/// assert_eq!(phi, [0.0, 0.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct DistanceConstraints {
    dim: usize,
    rods: Vec<Rod>,
}

impl DistanceConstraints {
    /// No rods yet, for particles in `dim` dimensions.
    pub fn new(dim: usize) -> Self {
        Self {
            dim,
            rods: Vec::new(),
        }
    }

    /// Adds a rod of `length` from particle `a` to the fixed `point` (length `dim`).
    pub fn anchor(mut self, a: usize, point: &[f64], length: f64) -> Result<Self, Error> {
        Error::check_len("anchor point", point, self.dim)?;
        Error::check_finite("anchor point", point)?;
        Self::check_length(length)?;
        self.rods.push(Rod {
            a,
            b: End::Point(point.to_vec()),
            length,
        });
        Ok(self)
    }

    /// Adds a rod of `length` between particles `a` and `b`.
    pub fn link(mut self, a: usize, b: usize, length: f64) -> Result<Self, Error> {
        Self::check_length(length)?;
        self.rods.push(Rod {
            a,
            b: End::Particle(b),
            length,
        });
        Ok(self)
    }

    fn check_length(length: f64) -> Result<(), Error> {
        if length.is_finite() && length > 0.0 {
            Ok(())
        } else {
            Err(Error::Input(InputError::InvalidOption {
                name: "rod length",
                value: length,
                reason: "must be positive and finite",
            }))
        }
    }

    /// Dimension `D` of the space the particles move in.
    pub fn dim(&self) -> usize {
        self.dim
    }

    fn particles_used(&self) -> usize {
        self.rods
            .iter()
            .map(|r| match r.b {
                End::Particle(b) => r.a.max(b) + 1,
                End::Point(_) => r.a + 1,
            })
            .max()
            .unwrap_or(0)
    }
}

impl Constraint for DistanceConstraints {
    fn count(&self) -> usize {
        self.rods.len()
    }

    #[inline]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let nan = S::from(f64::NAN);
        let dim = self.dim;
        for (o, rod) in out.iter_mut().zip(&self.rods) {
            let mut sq = S::from(0.0);
            for k in 0..dim {
                let xa = q.get(rod.a * dim + k).copied().unwrap_or(nan);
                let xb = match &rod.b {
                    End::Particle(b) => q.get(b * dim + k).copied().unwrap_or(nan),
                    End::Point(p) => S::from(p[k]),
                };
                let d = xa - xb;
                sq += d * d;
            }
            *o = (sq - rod.length * rod.length) * 0.5;
        }
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        let needed = self.particles_used() * self.dim;
        if self.dim == 0 || !dof.is_multiple_of(self.dim) || needed > dof {
            return Err(Error::Input(InputError::DimensionMismatch {
                what: "q for the distance constraints (particles × dimension)",
                expected: needed.max(self.dim),
                found: dof,
            }));
        }
        Ok(())
    }
}
