//! Certificates on request (`[analysis] certify = true`): what `summary.json` reports as
//! `certificate` — the symplecticity defect of the computed step map at the start and at the
//! end of the run, and the equivariance defect of `L_d` for every declared symmetry.
//!
//! **Symplecticity.** The core's [`DifferentiableStep`] gives the exact Jacobian `DF` of one
//! step `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of the run's own integrator (same rule, same discrete
//! forces), by the implicit function theorem through the converged step; the certificate is
//! the relative defect `‖DFᵀ J DF − J‖_max / ‖DF‖²_max` ([HLW06] Def. VI.2.2;
//! [`marsden::analysis::certificate`]), at round-off for every variational integrator of an
//! unforced system ([MW01] §1.3.2). A forced map is not symplectic: its defect is reported
//! all the same, marked "not expected symplectic (forced)". A constrained step (SHAKE + RATTLE)
//! is symplectic on `T*N` only: its defect is measured on a basis of the tangent space of
//! `T*N` ([`marsden::sensitivity::cotangent`]) and named so (`restricted_to`). The certified steps
//! take the general Newton path (the fast paths compute the same map and leave no control
//! points).
//!
//! **Equivariance.** A symmetry of the discrete action leaves it invariant, to first order
//! `Σ_j ⟨∂A/∂Q_j, ξ_Q(Q_j)⟩ = 0` over the control points `Q₀ = q_k, …, Q_s = q_{k+1}` of a
//! step (for a two-point rule `⟨D₁L_d, ξ_Q(q₀)⟩ + ⟨D₂L_d, ξ_Q(q₁)⟩ = 0`, the core's
//! [`marsden::symmetry::check::check_discrete`]); this is what makes the discrete momentum
//! map conserved ([MW01] Thm 1.3.3). The defect is computed by AD at the step from the initial
//! state and the step from the final state (`Q_j = q + (j/s) h v`), relative to
//! `Σ_j Σ_i |∂A/∂Q_{j,i} ξ_i(Q_j)|`, so a true symmetry shows round-off and a false one (a
//! rotation under gravity) a defect of order one.
//!
//! [HLW06]: marsden#references
//! [MW01]: marsden#references

use marsden::analysis::certificate::{DifferentiableStep, symplectic_defect};
use marsden::discrete::rules::Method as ChosenRule;
use marsden::numerics::ad::{self, MultiFunction};
use marsden::symmetry::GroupAction;
use marsden::symmetry::check::{Sample, relative_defect};
use marsden::{
    Constraint, DiscreteAction, Force, Lagrangian, NewtonOptions, Problem, Rule as _, Scalar,
    State, mechanics,
};
use serde::Serialize;

use marsden::sensitivity::cotangent::step_defect_on_cotangent_bundle;

/// `certificate { … }` of `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Certificate {
    /// The symplecticity defect of the step map.
    pub symplecticity: Symplecticity,
    /// The equivariance defect of `L_d`, by symmetry name (in the file's order).
    #[serde(serialize_with = "crate::serialize::as_object")]
    pub equivariance: Vec<(String, Equivariance)>,
}

/// `certificate.symplecticity { … }`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Symplecticity {
    /// `‖DFᵀJDF − J‖ / ‖DF‖²` of the first step (null when not available).
    pub start: Option<f64>,
    /// The same for one step from the final state.
    pub end: Option<f64>,
    /// `‖DFᵀJDF − J‖_max` of the first step.
    pub start_absolute: Option<f64>,
    /// The same from the final state.
    pub end_absolute: Option<f64>,
    /// Whether the map should be symplectic (no forces act).
    pub expected_symplectic: bool,
    /// Why there is no number, or why it need not be small (null otherwise).
    pub note: Option<String>,
    /// The space the defect is measured on when it is not all of `T*Q`: [`ON_T_STAR_N`] for a
    /// constrained run (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restricted_to: Option<&'static str>,
}

/// What a constrained run's symplecticity defect is measured on.
pub const ON_T_STAR_N: &str = "T*N: max |ω(DF u, DF w) − ω(u, w)| / max |DF u|² over a basis \
     of the tangent space of the constraint manifold's cotangent bundle";

/// `certificate.equivariance { <name>: { … } }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Equivariance {
    /// `max |Σ_j ⟨∂A/∂Q_j, ξ_Q(Q_j)⟩|` over the sampled steps.
    pub max_abs_defect: f64,
    /// The same relative to `Σ |∂A/∂Q_{j,i} ξ_i|` (round-off for a symmetry of `L_d`).
    pub max_rel_defect: f64,
    /// Sampled steps: from the initial state and from the final state.
    pub samples: usize,
}

/// The states a certificate looks at: the initial one (with its velocity) and the final one.
pub struct Ends<'a> {
    /// The initial state.
    pub start: &'a State,
    /// Its velocity.
    pub v0: &'a [f64],
    /// The last good state of the run (empty `q` if none).
    pub end: &'a State,
}

/// The step a certificate measures: the run's own rule, Newton options and step size.
pub struct StepRule<'a> {
    /// The file's rule.
    pub rule: &'a ChosenRule,
    /// The Newton options of each step.
    pub newton: NewtonOptions,
    /// The step size `h`.
    pub h: f64,
}

/// The certificate of a run of `problem` (its Lagrangian, forces and constraints) with the
/// file's rule and step `h` (`step`), for the declared `symmetries` (named by `names`); a run
/// with `method = "exact"` has [`without_step_jacobian`] instead.
///
/// The step map is that of `problem`'s own integrator type, the one the run compiled, so a
/// certificate adds no integrator code to the build.
pub fn certify<L: Lagrangian, F: Force, C: Constraint, G: GroupAction>(
    problem: &Problem<L, F, C>,
    names: &[String],
    symmetries: &[G],
    step: StepRule<'_>,
    ends: &Ends<'_>,
) -> Certificate {
    let StepRule { rule, newton, h } = step;
    Certify {
        problem,
        names,
        symmetries,
        newton,
        h,
        ends,
    }
    .call(rule)
}

/// The certificate of a run with `method = "exact"`, which has no step Jacobian to measure
/// (`forced`: a force acts, so the map need not be symplectic).
pub fn without_step_jacobian(forced: bool) -> Certificate {
    Certificate {
        symplecticity: Symplecticity {
            start: None,
            end: None,
            start_absolute: None,
            end_absolute: None,
            expected_symplectic: !forced,
            note: Some("not available for method = \"exact\" (no step Jacobian)".to_owned()),
            restricted_to: None,
        },
        equivariance: Vec::new(),
    }
}

struct Certify<'a, L, F, C, G> {
    problem: &'a Problem<L, F, C>,
    names: &'a [String],
    symmetries: &'a [G],
    newton: NewtonOptions,
    h: f64,
    ends: &'a Ends<'a>,
}

impl<L: Lagrangian, F: Force, C: Constraint, G: GroupAction> Certify<'_, L, F, C, G> {
    fn call(self, rule: &ChosenRule) -> Certificate {
        let symplecticity = self.symplecticity(rule);
        let action = rule.discretize(self.problem.lagrangian());
        let samples = self.samples();
        let equivariance = self
            .names
            .iter()
            .zip(self.symmetries)
            .map(|(name, g)| (name.clone(), equivariance(&action, g, self.h, &samples)))
            .collect();
        Certificate {
            symplecticity,
            equivariance,
        }
    }

    fn symplecticity(&self, rule: &ChosenRule) -> Symplecticity {
        let forced = self.problem.force().is_active();
        let constrained = self.problem.constraint().count() > 0;
        let mut out = Symplecticity {
            start: None,
            end: None,
            start_absolute: None,
            end_absolute: None,
            expected_symplectic: !forced,
            note: forced.then(|| "not expected symplectic (forced)".to_owned()),
            restricted_to: constrained.then_some(ON_T_STAR_N),
        };
        let n = self.problem.lagrangian().dof();
        let built = (self.problem.integrator(rule, self.newton)).map(|i| i.with_fast_paths(false));
        let mut integrator = match built {
            Ok(i) => i,
            Err(e) => {
                out.note = Some(format!("not available: {e}"));
                return out;
            }
        };
        let mut failures = Vec::new();
        let (v0, start) = (self.ends.v0, self.ends.start);
        integrator.set_velocity_hint(v0);
        let (lagrangian, constraint) = (self.problem.lagrangian(), self.problem.constraint());
        let defect = |integrator: &mut _, state: &State, v: &[f64]| match constrained {
            true => step_defect_on_cotangent_bundle(
                integrator, lagrangian, constraint, state, v, self.h,
            ),
            false => step_defect(integrator, state, self.h),
        };
        match defect(&mut integrator, start, v0) {
            Ok((abs, rel)) => (out.start_absolute, out.start) = (Some(abs), Some(rel)),
            Err(e) => failures.push(format!("the first step: {e}")),
        }
        let end = self.ends.end;
        if end.q.len() == n {
            integrator.reset();
            let v = self.velocity(end).unwrap_or_else(|| v0.to_vec());
            integrator.set_velocity_hint(&v);
            match defect(&mut integrator, end, &v) {
                Ok((abs, rel)) => (out.end_absolute, out.end) = (Some(abs), Some(rel)),
                Err(e) => failures.push(format!("the step from the final state: {e}")),
            }
        }
        if !failures.is_empty() {
            let failed = format!("no Jacobian for {}", failures.join("; "));
            out.note = Some(match out.note.take() {
                Some(note) => format!("{note}; {failed}"),
                None => failed,
            });
        }
        out
    }

    /// The velocity at `state` (inverse Legendre transform), if it can be found.
    fn velocity(&self, state: &State) -> Option<Vec<f64>> {
        let mut v = self.ends.v0.to_vec();
        let (l, (t, q, p)) = (self.problem.lagrangian(), (state.t, &state.q, &state.p));
        mechanics::energy_from_momentum(l, t, q, p, &mut v)
            .ok()
            .map(|_| v)
    }

    /// `(t, q, v)` at the start and, if its velocity is known, at the end.
    fn samples(&self) -> Vec<Sample> {
        let start = self.ends.start;
        let mut samples = vec![Sample {
            t: start.t,
            q: start.q.clone(),
            v: self.ends.v0.to_vec(),
        }];
        let end = self.ends.end;
        if end.q.len() == start.q.len()
            && let Some(v) = self.velocity(end)
        {
            samples.push(Sample {
                t: end.t,
                q: end.q.clone(),
                v,
            });
        }
        samples
    }
}

/// The `(absolute, relative)` symplecticity defect of one step from `state`.
fn step_defect<D: DifferentiableStep>(
    stepper: &mut D,
    state: &State,
    h: f64,
) -> Result<(f64, f64), marsden::Error> {
    let n = stepper.dof();
    let mut jac = vec![0.0; 4 * n * n];
    let mut s = state.clone();
    stepper.step_with_jacobian(&mut s, h, &mut jac)?;
    Ok(symplectic_defect(&jac, n))
}

/// The discrete action of one step as a function of `x = (Q₀, Δ₁, …, Δ_s)`.
struct ActionFn<'a, A> {
    action: &'a A,
    t0: f64,
    h: f64,
}

impl<A: DiscreteAction> MultiFunction for ActionFn<'_, A> {
    fn inputs(&self) -> usize {
        (self.action.internal_stages() + 2) * self.action.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, offsets) = x.split_at(self.action.dof());
        out[0] = self.action.action(self.t0, self.h, q0, offsets);
    }
}

/// The worst equivariance defect of `g` over the steps of `samples`.
fn equivariance<A: DiscreteAction, G: GroupAction>(
    action: &A,
    g: &G,
    h: f64,
    samples: &[Sample],
) -> Equivariance {
    let mut out = Equivariance {
        max_abs_defect: 0.0,
        max_rel_defect: 0.0,
        samples: samples.len(),
    };
    for sample in samples {
        for a in 0..g.algebra_dim() {
            let (defect, scale) = step_invariance(action, g, a, h, sample);
            let d = defect.abs();
            let relative = relative_defect(d, scale);
            // NaN sticks: an action that cannot be evaluated is no certified symmetry.
            if d > out.max_abs_defect || d.is_nan() {
                out.max_abs_defect = d;
            }
            out.max_rel_defect = out.max_rel_defect.max(relative);
        }
    }
    out
}

/// `(Σ_j ⟨∂A/∂Q_j, ξ_a(Q_j)⟩, Σ_j Σ_i |∂A/∂Q_{j,i} ξ_{a,i}(Q_j)|)` for generator `a` of `g`
/// and the step of size `h` from `(t, q)` of `sample`, with control points
/// `Q_j = q + (j/s) h v`.
fn step_invariance<A: DiscreteAction, G: GroupAction>(
    action: &A,
    g: &G,
    a: usize,
    h: f64,
    sample: &Sample,
) -> (f64, f64) {
    let (t, q, v) = (sample.t, sample.q.as_slice(), sample.v.as_slice());
    let (n, s) = (q.len(), action.internal_stages() + 1);
    let mut x = q.to_vec();
    for j in 1..=s {
        let c = j as f64 / s as f64;
        x.extend(v.iter().map(|vi| c * h * vi));
    }
    let mut grad = vec![0.0; x.len()];
    let f = ActionFn { action, t0: t, h };
    ad::jacobian(&f, &x, 0..x.len(), &mut [0.0], &mut grad);
    // ∂A/∂Q_j = ∂A/∂Δ_j (j ≥ 1); ∂A/∂Q₀ = ∂A/∂x₀ − Σ_j ∂A/∂Δ_j.
    let mut d_q0 = grad[..n].to_vec();
    for j in 1..=s {
        for i in 0..n {
            d_q0[i] -= grad[j * n + i];
        }
    }
    let (mut point, mut xi) = (vec![0.0; n], vec![0.0; n]);
    let (mut sum, mut scale) = (0.0, 0.0);
    for j in 0..=s {
        for i in 0..n {
            point[i] = q[i] + if j == 0 { 0.0 } else { x[j * n + i] };
        }
        g.generator(a, &point, &mut xi);
        let d = if j == 0 {
            &d_q0[..]
        } else {
            &grad[j * n..(j + 1) * n]
        };
        for (di, xii) in d.iter().zip(&xi) {
            sum += di * xii;
            scale += (di * xii).abs();
        }
    }
    (sum, scale)
}
