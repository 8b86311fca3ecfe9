//! # marsden: discrete mechanics and variational integrators
//!
//! Write a Lagrangian once, generic over a dual-number [`Scalar`], and simulate it with a
//! variational integrator that preserves its geometry (Marsden & West, *Discrete mechanics and
//! variational integrators*, Acta Numerica 2001).
//!
//! ```
//! use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, systems::Pendulum};
//! use marsden::analysis::diagnostics::EnergyReport;
//!
//! let pendulum = Pendulum::default();
//! let problem = Problem::new(pendulum, Initial::velocity(&[1.5], &[0.0]), TimeGrid::new(0.0, 0.05, 2000)?)?;
//! let trajectory = problem.solve(&Midpoint, &SolveOptions::default())?;
//! let energy = EnergyReport::of(&pendulum, &trajectory)?;
//! assert!(energy.max_rel_error < 2e-3); // R8: 8.99e-5 / 0.0707 for h = 0.05
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Map of the crate
//!
//! Data flows down; each module uses only those above it (`special` and `systems` stand beside).
//!
//! | stage | module | seed concept |
//! |---|---|---|
//! | errors, scalar | [`error`], [`scalar`] | input / set-up / step errors; one generic axis: `f64` or dual numbers |
//! | numerics | [`numerics`] | automatic differentiation, dual numbers, Newton's method and its one stopping rule, dense and banded LU |
//! | continuous mechanics | [`mechanics`] | `L(t, q, v)`, `f_L`, `φ(q)`, states, Legendre transform `FL`, energy, Euler–Lagrange, `FH`, the potential of a separable `L` |
//! | fast path 1 | [`separable`] | `L = ½vᵀMv − V`: explicit Störmer–Verlet, the α-rule Newton with Jacobian `M/h + hα(1−α)∇²V` |
//! | discrete mechanics | [`discrete`] | `L_d`, `f_d^±`, `D₁L_d`, `D₂L_d`, `F^±L_d`, DEL; rules (midpoint, trapezoid, α, Galerkin, compositions); `L_d^E` by shooting |
//! | forces, constraints | [`forces`], [`holonomic`] | damping, driving, controls, `f_H ∘ FL`; RATTLE, initial data on `T*N` |
//! | catalog | [`systems`], [`special`] | canonical systems; elliptic functions, exact pendulum, Kepler and oscillator solutions |
//! | integrator | [`integrator`] | the discrete Hamiltonian map `F̃_{L_d}` solved by Newton (the path chosen once), compensated summation, checkpoints, `F_{L_d}` |
//! | run | [`run`] | problem → one run loop over a [`run::Stepper`] → trajectory; stride, observers, events located inside the step, failures |
//! | Hamiltonian side | [`hamiltonian`] | `H(q, p)`, `X_H`, implicit midpoint, Störmer–Verlet, Legendre adapters |
//! | symmetry | [`symmetry`] | group actions, generators and lifts, `J_L`, `J_H`, `J^±_{L_d}`, symmetry checks |
//! | analysis | [`analysis`] | energy error and drift, Noether and force balances, energy balance, constraint residuals; symplecticity certificate |
//! | studies | [`studies`] | ensembles in parallel, empirical orders of convergence |
//! | sensitivity | [`sensitivity`] | tangent sensitivities `∂(q, p)/∂(q₀, p₀, θ)` along a run; adjoint gradients with checkpoints |
//! | rigid bodies | [`lie`] | SO(3) (× ℝ³): so(3), Cayley map, inertia, the Lie group variational integrator (LGVI) and its compositions, body moment by AD, invariants |
//!
//! ## Conventions
//!
//! * `q` positions, `v` velocities (`q̇`), `p` momenta, `h` the time step, `t` time, `n` degrees of
//!   freedom, `d` constraints.
//! * The step is the discrete Hamiltonian map in position–momentum form, with discrete forces
//!   (the discrete Lagrange–d'Alembert principle, [MW01] §3.2):
//!   `p_k = −D₁L_d(q_k, q_{k+1}) − f_d⁻(q_k, q_{k+1})` is solved for `q_{k+1}`, then
//!   `p_{k+1} = D₂L_d(q_k, q_{k+1}) + f_d⁺(q_k, q_{k+1})`.
//! * Midpoint: `L_d = h L(t + h/2, (q₀+q₁)/2, (q₁−q₀)/h)`, forces `f_d^± = (h/2) f(midpoint)`.
//!   Trapezoid: `L_d = (h/2)[L(t, q₀, v) + L(t+h, q₁, v)]`, `v = (q₁−q₀)/h`, forces at the ends.
//!   Generalised midpoint: `L_d^α = h L(t + αh, (1−α)q₀ + αq₁, v)`, forces
//!   `(f_d⁻, f_d⁺) = (h(1−α) f, hα f)` at that point; symmetrised: `½(L_d^α + L_d^{1−α})`.
//!   Midpoint is α = ½, trapezoid the symmetrised α = 0.
//! * Discrete Legendre transforms ([MW01] §1.3): `F⁻L_d(q₀, q₁) = (q₀, −D₁L_d(q₀, q₁))`,
//!   `F⁺L_d(q₀, q₁) = (q₁, D₂L_d(q₀, q₁))`; without forces the step is `F⁺L_d ∘ (F⁻L_d)⁻¹`, and
//!   eliminating the momenta gives the DEL `D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0`; forces
//!   add `f_d⁺(q_{k−1}, q_k) + f_d⁻(q_k, q_{k+1})` to its left-hand side.
//! * Constraints (SHAKE, [LMO08]): `p_k + D₁L_d(q_k, q_{k+1}) − h Dφ(q_k)ᵀλ_k = 0`,
//!   `φ(q_{k+1}) = 0`; RATTLE adds the momentum projection so that `(q_{k+1}, p_{k+1})` lies on
//!   the cotangent bundle of the constraint manifold (`Dφ(q) · FH(q, p) = 0`). Rules of higher
//!   order impose `φ = 0` at their stages too (constrained Lobatto IIIA–IIIB; compositions of
//!   RATTLE steps), so they keep their order; Gauss rules are refused with constraints.
//! * The discrete momenta are the `p_k` above: for the midpoint rule `p_k ≠ M (q_{k+1} − q_k)/h`.
//! * Equivalences, for `L = ½vᵀMv − V(q)` ([MW01]; [HLW06] §VI.6): the midpoint rule *is* the
//!   implicit midpoint rule on `H = ½pᵀM⁻¹p + V` (`q₁ = q₀ + hM⁻¹(p₀ + p₁)/2`,
//!   `p₁ = p₀ − h∇V((q₀ + q₁)/2)`), and the trapezoid rule *is* velocity Störmer–Verlet
//!   (`p_½ = p₀ − (h/2)∇V(q₀)`, `q₁ = q₀ + hM⁻¹p_½`, `p₁ = p_½ − (h/2)∇V(q₁)`).
//! * Rigid bodies ([`lie`], [LLM07]): the attitude `R ∈ SO(3)` maps body to space, `Ṙ = R Ω^`,
//!   `Π = JΩ` the body angular momentum, `J` the inertia about the fixed point (the centre of mass
//!   for a free body), `J_d = ½ tr(J) I − J`; the body moment `M` is the left-trivialised
//!   derivative of `−U` (`M^ = (∂U/∂R)ᵀR − Rᵀ∂U/∂R`); `(hΠ_k + (h²/2)M_k)^ = F_kJ_d − J_dF_kᵀ`,
//!   `R_{k+1} = R_kF_k`, `Π_{k+1} = F_kᵀΠ_k + (h/2)F_kᵀM_k + (h/2)M_{k+1}`. Spatial rotations act
//!   on the left (momentum map `RΠ`), body rotations on the right (`Π`).
//! * Discrete Noether: for an `L_d` invariant under a group action, `J_k = ⟨p_k, ξ_Q(q_k)⟩` is
//!   exactly constant (to the Newton tolerance: over `N` steps at most `N · tol · |ξ_Q|`), with the
//!   discrete momenta `p_k`. The midpoint, trapezoid and Galerkin `L_d` of an invariant `L` are
//!   invariant under linear actions (translations, rotations). Tests of conservation run Newton to
//!   round-off or let their bound grow with `N`.
//!
//! ## Reference cases
//!
//! The tests check the library against known answers (`tests/reference/`, a file per case named
//! after it; the constrained cases R7, R13 and R14 in `tests/constraints/`). The tolerances asserted are at least as tight as these:
//!
//! | case | system, method | checked | tolerance |
//! |---|---|---|---|
//! | R1 | oscillator, midpoint | closed-form discrete solution; energy (a quadratic invariant); one-step matrix `[[399, 40], [−40, 399]]/401` at `h = 0.1` | 1e-12 (N ≤ 1000), 1e-9 (N = 10⁶); energy 1e-13 |
//! | R2 | oscillator, trapezoid = Störmer–Verlet | closed form; modified energy `H̃` exact; `max |H − H₀| = h²/8` | 1e-12; `H̃` 1e-11 over 10⁶ steps; 1e-9 relative |
//! | R3 | oscillator, exact `L_d^E` | `L_d^E` values; local error `O(h³)` of the midpoint `L_d` | 1e-12; 1e-15 |
//! | R4 | pendulum | unit values of `L_d`, `F^±L_d`, the DEL residual | 1e-15 |
//! | R5 | pendulum, generalised midpoint α | order 1 for α ≠ ½, 2 at α = ½ and symmetrised | ±0.05 on the slope |
//! | R6 | pendulum, Galerkin Gauss / Lobatto | order 2s (Gauss), 2s − 2 (Lobatto); second-order regression values | slopes; 1e-11 |
//! | R7 | Cartesian pendulum on the circle of radius `l`, SHAKE + RATTLE (derived here: the exact solution from the pendulum's elliptic-function solution) | order 2 (two-point rules), `2s − 2` (constrained Lobatto IIIA–IIIB, [Jay96]), the scheme's order (compositions of RATTLE steps, [Rei96]); multipliers of the stored states at the method's order | ±0.2 on the slope |
//! | R8 | pendulum, 10⁶ steps | energy error bounded, no drift; shadow Hamiltonian | as in the case |
//! | R9 | free fall | every variational integrator exact | 1e-13 relative |
//! | R10 | Kepler e = 0.6 | angular momentum (discrete Noether); energy bounded; one-period regression | 1e-12 over 10⁵ steps; 2e-4; 1e-10 |
//! | R12 | damped oscillator, midpoint forces | discrete energy balance `E_{k+1} − E_k = −c(q_{k+1} − q_k)²/h`; closed form | 1e-14 per step; 1e-12 |
//! | R13 | spherical pendulum in Cartesian coordinates, stage constraints (against the angle flow, extrapolated to round-off) | `φ = 0` at every stage point; `L_z` (discrete Noether); order 4 with order-4 rules | 1e-14; 1e-12 over 2000 steps; ±0.2 on the slope |
//! | R14 | planar double pendulum, angles against Cartesian coordinates with two distance constraints | both converge to the same motion; their difference `O(h²)` (midpoint), `O(h⁴)` (`lobatto-3`) | ±0.05 and ±0.2 on the slope |
//! | R17 | symmetric rules | time reversibility; `det DF = 1`, `DFᵀJDF = J` | 1e-12 / 1e-11; 1e-8 |
//! | R19 | free rigid body, LGVI (Moser–Veselov) | energy, `|Π|²` and `RΠ` over 10⁴ steps of `h = 0.1`; orders 2, 4, 6 against the elliptic-function solution | 1e-12; ±0.1 on the slope |
//! | R20 | heavy symmetric top, LGVI | `e₃·RΠ`, `Π₃` to round-off; energy error bounded and `O(h²)`; `|RᵀR − I|` after 10⁶ steps | 1e-12 relative; 1e-13 |
//! | R21 | compound double pendulum, constrained LGVI (two rods on hinges, 10 joint rows) | final hinge angles against the reduced-coordinate Lagrangian (gauss-4 at a tiny step): orders 2 and 4 (triple jump); joints closed at every step | ±0.1 / ±0.2 on the slope; 1e-13 |
//! | R22 | 3D pendulum ([CLLM11]), constrained LGVI | vertical angular momentum about the pivot; joint residual | 1e-12 relative; 1e-13 |
//!
//! ## References
//!
//! The works the documentation cites, by the key it cites them with:
//!
//! * **MW01**: J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta
//!   Numerica 10 (2001).
//! * **MR99**: Marsden & Ratiu, *Introduction to Mechanics and Symmetry*, 2nd ed. (1999).
//! * **HLW03**: Hairer, Lubich, Wanner, Acta Numerica 12 (2003).
//! * **HLW06**: Hairer, Lubich, Wanner, *Geometric Numerical Integration*, 2nd ed. (2006).
//! * **LR04**: Leimkuhler, Reich, *Simulating Hamiltonian Dynamics* (2004).
//! * **LMO08**: Leyendecker, Marsden, Ortiz, *Variational integrators for constrained dynamical
//!   systems*, ZAMM 88 (2008).
//! * **Jay96**: L. Jay, *Symplectic partitioned Runge–Kutta methods for constrained Hamiltonian
//!   systems*, SIAM J. Numer. Anal. 33 (1996).
//! * **Rei96**: S. Reich, *Symplectic integration of constrained Hamiltonian systems by composition
//!   methods*, SIAM J. Numer. Anal. 33 (1996).
//! * **OBS15**: Ober-Blöbaum & Saake, Adv. Comput. Math. 41 (2015).
//! * **OB17**: Ober-Blöbaum, IMA J. Numer. Anal. 37 (2017).
//! * **FGG21**: Fernández, Graiff Zurita, Grillo, *Error analysis of forced discrete mechanical
//!   systems*, J. Geom. Mech. (2021).
//! * **LLM05**: T. Lee, M. Leok, N. H. McClamroch, *A Lie group variational integrator for the
//!   attitude dynamics of a rigid body with applications to the 3D pendulum*, Proc. IEEE
//!   Conference on Control Applications (2005) 962–967.
//! * **LLM07**: T. Lee, M. Leok, N. H. McClamroch, *Lie group variational integrators for the full
//!   body problem*, Comput. Methods Appl. Mech. Engrg. 196 (2007) 2907–2924.
//! * **CLLM11**: N. A. Chaturvedi, T. Lee, M. Leok, N. H. McClamroch, *Nonlinear dynamics of the
//!   3D pendulum*, J. Nonlinear Sci. 21 (2011) 3–32 (a rigid body on a spherical joint: its
//!   vertical angular momentum is conserved).
//! * **LL76**: L. D. Landau, E. M. Lifshitz, *Mechanics*, 3rd ed. (1976), §37 (the free
//!   asymmetric top by Jacobi elliptic functions).
//! * **GW08**: Griewank & Walther, *Evaluating Derivatives*, 2nd ed. (2008).
//! * **GVL13**: G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed. (2013), §3.2 (LU
//!   factorisation, `2n³/3` flops).
//! * **Sanz-Serna 2016**: J. M. Sanz-Serna, *Symplectic Runge–Kutta schemes for adjoint equations,
//!   automatic differentiation, optimal control and more*, SIAM Review 58 (2016).
//! * **Bre73**: R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall
//!   (1973), chapter 4 (the root finder `zeroin`).
//! * **OJM11**: S. Ober-Blöbaum, O. Junge, J. E. Marsden, *Discrete mechanics and optimal
//!   control: an analysis*, ESAIM: COCV 17 (2011) 322–352 (DMOC: `marsden-control`,
//!   `marsden optimize`).
//! * **BH75**: A. E. Bryson, Y.-C. Ho, *Applied Optimal Control* (1975) (the double
//!   integrator's closed-form optimum, the reference of the optimal control tests).
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references
//! [LLM07]: crate#references
//! [CLLM11]: crate#references
//! [Jay96]: crate#references
//! [Rei96]: crate#references
//! [HLW06]: crate#references

pub mod analysis;
pub mod discrete;
pub mod error;
pub mod forces;
pub mod hamiltonian;
pub mod holonomic;
pub mod integrator;
pub mod lie;
pub mod mechanics;
pub mod numerics;
pub mod run;
pub mod scalar;
pub mod sensitivity;
pub mod separable;
pub mod special;
pub mod studies;
pub mod symmetry;
pub mod systems;

pub use discrete::rules::{GeneralizedMidpoint, Midpoint, Rule, SymmetrizedMidpoint, Trapezoid};
pub use discrete::{DiscreteAction, DiscreteForce, DiscreteLagrangian};
pub use error::Error;
pub use integrator::{Integrator, Statistics, StepReport};
pub use mechanics::{
    Constraint, Force, Initial, Lagrangian, MassMatrix, NoForce, State, Structure, Unconstrained,
};
pub use numerics::newton::NewtonOptions;
pub use run::{
    Observer, Problem, RunFailure, RunOptions, SolveOptions, StepView, Termination, TimeGrid,
    Trajectory, simulate,
};
pub use scalar::Scalar;
