//! Direct summation of softened gravity, written for the compiler to vectorise.
//!
//! `∇ᵢV = −G mᵢ Σⱼ mⱼ (xⱼ − xᵢ) / (|xⱼ − xᵢ|² + ε²)^{3/2}` for all ordered pairs (the "full"
//! kernel of `verlet.c`): positions are copied once per call into structure-of-arrays form
//! (`x`, `y`, `z`, `m`, each padded with massless bodies to a multiple of [`LANES`]), and the
//! inner loop over `j` runs on fixed-size chunks with one accumulator per lane, so it has no
//! branches, no loop-carried dependency across lanes and vectorises with plain safe Rust
//! (packed `sqrt` and `div`). With `ε > 0` the self term is exactly zero (`dx = 0`); with
//! `ε = 0` a branch-free select drops it (and coincident bodies). The summation order differs
//! from the pairwise AD form only by round-off (test `nbody_hand_gradient_matches_ad`).

use super::NBody;

/// Bodies per chunk of the inner loop (two AVX registers of `f64`, four SSE2 registers).
pub const LANES: usize = 8;

/// Writes `∇V` (layout `x₁ y₁ z₁ x₂ …`) of the bodies of `system` (its masses, `G` and `ε`) at
/// `q` into `grad`; `scratch` holds the structure-of-arrays copy between calls. Inlinable:
/// compiled with the run that calls it, in the crate that names the system.
#[inline]
pub fn gradient(system: &NBody, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
    let (masses, g, softening) = (system.masses.as_slice(), system.g, system.softening);
    let n = masses.len();
    let padded = n.div_ceil(LANES) * LANES;
    scratch.clear();
    scratch.resize(4 * padded, 0.0);
    let (x, rest) = scratch.split_at_mut(padded);
    let (y, rest) = rest.split_at_mut(padded);
    let (z, m) = rest.split_at_mut(padded);
    for (i, body) in q.chunks_exact(3).enumerate() {
        (x[i], y[i], z[i], m[i]) = (body[0], body[1], body[2], masses[i]);
    }
    let soa = Soa { x, y, z, m };
    let eps2 = softening * softening;
    for (i, out) in grad.chunks_exact_mut(3).enumerate() {
        let a = if eps2 > 0.0 {
            soa.field_softened(i, eps2)
        } else {
            soa.field_unsoftened(i)
        };
        let c = -g * masses[i];
        (out[0], out[1], out[2]) = (c * a[0], c * a[1], c * a[2]);
    }
}

/// Positions and masses, structure of arrays, padded to a multiple of [`LANES`].
struct Soa<'a> {
    x: &'a [f64],
    y: &'a [f64],
    z: &'a [f64],
    m: &'a [f64],
}

impl Soa<'_> {
    /// `Σⱼ mⱼ (xⱼ − xᵢ) / (r² + ε²)^{3/2}` for `ε² > 0`.
    #[inline]
    fn field_softened(&self, i: usize, eps2: f64) -> [f64; 3] {
        self.field(i, |r2| {
            let r2 = r2 + eps2;
            1.0 / (r2 * r2.sqrt())
        })
    }

    /// The same without softening; `r = 0` (the body itself) contributes nothing.
    #[inline]
    fn field_unsoftened(&self, i: usize) -> [f64; 3] {
        self.field(i, |r2| {
            let w = 1.0 / (r2 * r2.sqrt());
            if r2 > 0.0 { w } else { 0.0 }
        })
    }

    /// The lane-parallel sum with weight `w(r²)`.
    #[inline(always)]
    fn field(&self, i: usize, weight: impl Fn(f64) -> f64) -> [f64; 3] {
        let (xi, yi, zi) = (self.x[i], self.y[i], self.z[i]);
        let (xs, _) = self.x.as_chunks::<LANES>();
        let (ys, _) = self.y.as_chunks::<LANES>();
        let (zs, _) = self.z.as_chunks::<LANES>();
        let (ms, _) = self.m.as_chunks::<LANES>();
        let mut acc = [[0.0; LANES]; 3];
        for (((xc, yc), zc), mc) in xs.iter().zip(ys).zip(zs).zip(ms) {
            for l in 0..LANES {
                let (dx, dy, dz) = (xc[l] - xi, yc[l] - yi, zc[l] - zi);
                let w = mc[l] * weight(dx * dx + dy * dy + dz * dz);
                acc[0][l] += w * dx;
                acc[1][l] += w * dy;
                acc[2][l] += w * dz;
            }
        }
        acc.map(|lanes| lanes.iter().sum())
    }
}
