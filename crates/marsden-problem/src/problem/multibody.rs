//! `[[system.body]]` and `[[system.joint]]`: rigid bodies joined by joints, stepped by the
//! constrained Lie group variational integrator of the core (`marsden::lie::multibody`).
//!
//! ```toml
//! [system]
//! name = "compound_double_pendulum"
//! gravity = [0.0, 0.0, -9.81]            # a uniform field acting on every body's mass
//! [[system.body]]
//! name = "a"
//! mass = 1.0
//! inertia = [0.0833, 0.0833, 0.001]      # principal moments about the centre of mass
//! [[system.joint]]
//! kind = "revolute"                      # spherical | revolute | prismatic | fixed | distance
//! bodies = ["ground", "a"]
//! at = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]      # the joint point in each frame
//! axis = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]    # revolute/prismatic: the axis in each frame
//! ```
//!
//! `[[system.particle]]` (`name`, `mass`) adds point masses: the configuration is
//! `(SO(3) × ℝ³)ᵐ × (ℝ³)ⁿ`, one attitude and centre of mass per body and a position per particle;
//! a particle takes spherical and distance joints, springs and dampers at its position
//! (`at = [0, 0, 0]` on its side). The columns are `<body>_R11 … <body>_R33`, `<body>_Pi1 …` of
//! the bodies, `<name>_x … <name>_z`, `<name>_p_x …` of the bodies then the particles, then
//! `energy`, `constraint_residual` (the joints'), the multipliers `lambda_<joint>_<i>` and
//! `constraint_velocity_residual`.

use std::ops::Range;

use marsden::lie::body::Inertia;
use marsden::lie::state::BodyInitial;
use marsden_expr::Program;
use toml::Spanned;

use super::check::Checker;
use super::multibody_bodies::{body, particle};
use super::multibody_particles::{Sides, check_sides, span_or};
use super::multibody_potential::{Written, potential};
use super::multibody_springs::{DamperSpec, SpringSpec};
use super::raw::RawSystem;
use super::raw_multibody::RawJoint;
use crate::error::Diagnostic;

/// The name of the fixed space frame in `bodies = [...]`.
pub const GROUND: &str = "ground";

/// The joint kinds, as files write them.
pub const JOINT_KINDS: [&str; 5] = ["spherical", "revolute", "prismatic", "fixed", "distance"];

/// One body or particle.
#[derive(Debug, Clone, PartialEq)]
pub struct BodySpec {
    /// Its name (the prefix of its columns).
    pub name: String,
    /// Its mass.
    pub mass: f64,
    /// Its inertia about the centre of mass ([`Inertia::point`] for a particle).
    pub inertia: Inertia,
    /// A particle (`[[system.particle]]`): a point mass without attitude.
    pub particle: bool,
}

/// What a joint needs beyond its points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointKindSpec {
    /// A ball joint.
    Spherical,
    /// A hinge about `axes[0]` (side 0's frame) = `axes[1]` (side 1's).
    Revolute {
        /// The axis in each side's frame.
        axes: [[f64; 3]; 2],
    },
    /// A slider along `axis` (side 0's frame), the relative attitude locked as it starts.
    Prismatic {
        /// The sliding axis.
        axis: [f64; 3],
    },
    /// A weld, the relative attitude locked as it starts.
    Fixed,
    /// A rod between the points; its length as written, or as the bodies start.
    Distance {
        /// `length = ℓ`, if written.
        length: Option<f64>,
    },
}

/// One joint.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSpec {
    /// Its name (columns `lambda_<name>_<i>`).
    pub name: String,
    /// The kind.
    pub kind: JointKindSpec,
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The joint point in each side's frame.
    pub points: [[f64; 3]; 2],
}

/// `[system]` of a multibody file, validated, with the bodies' initial data
/// ([`super::multibody_initial`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MultibodySpec {
    /// The bodies in the file's order, then the particles in theirs.
    pub bodies: Vec<BodySpec>,
    /// The uniform field `g`.
    pub gravity: [f64; 3],
    /// The joints, in the file's order (list them along a chain: the joint solve is then
    /// banded).
    pub joints: Vec<JointSpec>,
    /// The springs between body points ([`super::multibody_springs`]).
    pub springs: Vec<SpringSpec>,
    /// The dampers between body points.
    pub dampers: Vec<DamperSpec>,
    /// Each body's initial attitude, body momentum, centre and momentum.
    pub initial: Vec<BodyInitial>,
    /// `potential = "…"`: `U` over the bodies' entries
    /// ([`crate::model::multibody_potential::inputs`]) and the parameters.
    pub potential: Option<Program>,
    /// The parameters with their values, in the file's order.
    pub parameters: Vec<(String, f64)>,
}

/// Whether the file describes a multibody system.
pub fn is_multibody(system: &RawSystem) -> bool {
    system.body.is_some()
        || system.particle.is_some()
        || system.joint.is_some()
        || system.spring.is_some()
        || system.damper.is_some()
}

/// The bodies, the field and the joints of `system` (the initial data are read next).
///
/// # Errors
/// A body without a name, mass or inertia, two bodies of one name, a joint naming an unknown
/// body, an unknown kind, points or axes of the wrong shape, keys of other kinds of systems.
pub(super) fn system(ck: &Checker<'_>, system: &RawSystem) -> Result<MultibodySpec, Diagnostic> {
    refuse_other_keys(ck, system)?;
    let raw_bodies = system.body.as_deref().unwrap_or(&[]);
    let raw_particles = system.particle.as_deref().unwrap_or(&[]);
    if raw_bodies.is_empty() && raw_particles.is_empty() {
        let first =
            |list: Option<Vec<std::ops::Range<usize>>>| list.and_then(|l| l.into_iter().next());
        let span = first(
            system
                .joint
                .as_ref()
                .map(|j| j.iter().map(Spanned::span).collect()),
        )
        .or_else(|| {
            first(
                system
                    .spring
                    .as_ref()
                    .map(|j| j.iter().map(Spanned::span).collect()),
            )
        })
        .or_else(|| {
            first(
                system
                    .damper
                    .as_ref()
                    .map(|j| j.iter().map(Spanned::span).collect()),
            )
        });
        return Err(ck
            .error(
                span,
                "joints, springs and dampers need bodies: the file has no [[system.body]]",
            )
            .help("add `[[system.body]]` tables with `name`, `mass` and `inertia` (or `[[system.particle]]` with `name` and `mass`)"));
    }
    let mut bodies: Vec<BodySpec> = Vec::with_capacity(raw_bodies.len() + raw_particles.len());
    let written = (raw_bodies.iter().enumerate())
        .map(|(index, raw)| (body(ck, raw, index), raw.get_ref().name.as_ref()))
        .chain(
            (raw_particles.iter().enumerate())
                .map(|(index, raw)| (particle(ck, raw, index), raw.get_ref().name.as_ref())),
        );
    for (body, name) in written {
        let body = body?;
        if body.name == GROUND || bodies.iter().any(|b| b.name == body.name) {
            let why = match body.name == GROUND {
                true => "`ground` names the space frame; give the body another name".to_owned(),
                false => format!("two bodies or particles are named `{}`", body.name),
            };
            return Err(ck.error(name.map(Spanned::span), why));
        }
        bodies.push(body);
    }
    let gravity = match &system.gravity {
        None => [0.0; 3],
        Some(g) => {
            let names = ["x", "y", "z"].map(str::to_owned);
            let g = ck.vector("system.gravity", g, &names)?;
            [g[0], g[1], g[2]]
        }
    };
    let mut joints = Vec::new();
    for (index, raw) in system.joint.as_deref().unwrap_or(&[]).iter().enumerate() {
        let joint = joint(ck, raw, index, &bodies)?;
        if joints.iter().any(|j: &JointSpec| j.name == joint.name) {
            let span = raw
                .get_ref()
                .name
                .as_ref()
                .map_or(raw.span(), Spanned::span);
            return Err(ck.error(Some(span), format!("two joints are named `{}`", joint.name)));
        }
        joints.push(joint);
    }
    let springs = super::multibody_springs::springs(ck, system, &bodies)?;
    let dampers = super::multibody_springs::dampers(ck, system, &bodies)?;
    let Written {
        potential,
        parameters,
    } = potential(ck, system, &bodies)?;
    Ok(MultibodySpec {
        bodies,
        gravity,
        joints,
        springs,
        dampers,
        initial: Vec::new(),
        potential,
        parameters,
    })
}

pub(super) fn valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

fn joint(
    ck: &Checker<'_>,
    raw: &Spanned<RawJoint>,
    index: usize,
    bodies: &[BodySpec],
) -> Result<JointSpec, Diagnostic> {
    let j = raw.get_ref();
    let Some(kind) = &j.kind else {
        return Err(ck
            .error(
                Some(raw.span()),
                format!("joint #{} has no `kind`", index + 1),
            )
            .help(format!("one of {}", quoted(&JOINT_KINDS))));
    };
    let Some(sides) = &j.bodies else {
        return Err(ck
            .error(
                Some(raw.span()),
                format!("joint #{} has no `bodies`", index + 1),
            )
            .help("e.g. `bodies = [\"ground\", \"a\"]` (two bodies, or the ground and a body)"));
    };
    let side_index = |name: &str| -> Result<Option<usize>, Diagnostic> {
        if name == GROUND {
            return Ok(None);
        }
        bodies
            .iter()
            .position(|b| b.name == name)
            .map(Some)
            .ok_or_else(|| {
                let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
                ck.error(
                    Some(sides.span()),
                    format!("joint #{} names an unknown body `{name}`", index + 1),
                )
                .help(format!(
                    "the bodies are {} (and \"ground\")",
                    quoted(&names)
                ))
            })
    };
    let [a, b] = sides.get_ref().as_slice() else {
        return Err(ck.error(
            Some(sides.span()),
            format!(
                "`bodies` names {} sides; a joint joins two",
                sides.get_ref().len()
            ),
        ));
    };
    let pair = [side_index(a)?, side_index(b)?];
    if pair[0] == pair[1] {
        return Err(ck.error(
            Some(sides.span()),
            "a joint joins two different bodies (or a body and the ground)",
        ));
    }
    let points = match &j.at {
        Some(at) => pair_of_vectors(ck, at, "at")?,
        None => {
            return Err(ck
                .error(
                    Some(raw.span()),
                    format!("joint #{} has no `at`", index + 1),
                )
                .help("the joint point in each frame: `at = [[x, y, z], [x, y, z]]`"));
        }
    };
    let kind_name = kind.get_ref().as_str();
    let kind_span = kind.span();
    let kind = match kind_name {
        "spherical" => JointKindSpec::Spherical,
        "fixed" => JointKindSpec::Fixed,
        "revolute" => JointKindSpec::Revolute {
            axes: pair_of_vectors(ck, need_axis(ck, raw, j, index)?, "axis")?,
        },
        "prismatic" => {
            let axis = need_axis(ck, raw, j, index)?;
            let first = axis.get_ref().first().cloned().unwrap_or_default();
            let [x, y, z] = first.as_slice() else {
                return Err(ck.error(Some(axis.span()), "`axis` holds vectors of three numbers"));
            };
            JointKindSpec::Prismatic { axis: [*x, *y, *z] }
        }
        "distance" => JointKindSpec::Distance {
            length: match &j.length {
                None => None,
                Some(l) => match ck.finite("length", l)? {
                    l if l > 0.0 => Some(l),
                    l => {
                        return Err(ck.error(
                            Some(l_span(j)),
                            format!("the length must be positive, not {l}"),
                        ));
                    }
                },
            },
        },
        other => {
            return Err(ck
                .error(Some(kind.span()), format!("unknown joint kind `{other}`"))
                .help(format!("one of {}", quoted(&JOINT_KINDS))));
        }
    };
    let axis_ok = matches!(
        kind,
        JointKindSpec::Revolute { .. } | JointKindSpec::Prismatic { .. }
    );
    if let (Some(axis), false) = (&j.axis, axis_ok) {
        return Err(ck.error(
            Some(axis.span()),
            format!("a {kind_name} joint has no axis"),
        ));
    }
    if let (Some(length), false) = (&j.length, matches!(kind, JointKindSpec::Distance { .. })) {
        return Err(ck.error(
            Some(length.span()),
            format!("a {kind_name} joint has no length"),
        ));
    }
    let written = Sides {
        what: "joint",
        kind: Some((kind_name, kind_span.clone())),
        bodies: pair,
        points,
        at: span_or(j.at.as_ref(), &raw.span()),
    };
    check_sides(ck, &written, bodies)?;
    let name = match &j.name {
        Some(n) if valid_name(n.get_ref()) => n.get_ref().clone(),
        Some(n) => {
            return Err(ck
                .error(
                    Some(n.span()),
                    format!("`{}` is not a valid joint name", n.get_ref()),
                )
                .help("a name is letters, digits and `_`, starting with a letter"));
        }
        None => format!("{kind_name}{}", index + 1),
    };
    Ok(JointSpec {
        name,
        kind,
        bodies: pair,
        points,
    })
}

fn l_span(j: &RawJoint) -> Range<usize> {
    j.length.as_ref().map_or(0..0, Spanned::span)
}

fn need_axis<'a>(
    ck: &Checker<'_>,
    raw: &Spanned<RawJoint>,
    j: &'a RawJoint,
    index: usize,
) -> Result<&'a Spanned<Vec<Vec<f64>>>, Diagnostic> {
    j.axis.as_ref().ok_or_else(|| {
        ck.error(
            Some(raw.span()),
            format!("joint #{} has no `axis`", index + 1),
        )
        .help("the axis in each frame: `axis = [[0, 1, 0], [0, 1, 0]]`")
    })
}

/// Two 3-vectors, finite, not both zero for an axis.
pub(super) fn pair_of_vectors(
    ck: &Checker<'_>,
    written: &Spanned<Vec<Vec<f64>>>,
    key: &str,
) -> Result<[[f64; 3]; 2], Diagnostic> {
    let v = written.get_ref();
    let shape_ok = v.len() == 2 && v.iter().all(|r| r.len() == 3);
    if !shape_ok {
        return Err(ck
            .error(
                Some(written.span()),
                format!("`{key}` must be two vectors of three numbers, one per side"),
            )
            .help(format!("e.g. `{key} = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]`")));
    }
    if let Some(bad) = v.iter().flatten().find(|x| !x.is_finite()) {
        return Err(ck.error(
            Some(written.span()),
            format!("`{key}` has a non-finite entry ({bad})"),
        ));
    }
    if key == "axis" && v.iter().any(|r| r.iter().all(|x| *x == 0.0)) {
        return Err(ck.error(Some(written.span()), "an axis must be a nonzero vector"));
    }
    Ok([[v[0][0], v[0][1], v[0][2]], [v[1][0], v[1][1], v[1][2]]])
}

pub(super) fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The keys of systems in coordinates and of a single rigid body, which a multibody file does
/// not take.
fn refuse_other_keys(ck: &Checker<'_>, system: &RawSystem) -> Result<(), Diagnostic> {
    let keys = [
        (
            "coordinates",
            system.coordinates.as_ref().map(Spanned::span),
        ),
        ("lagrangian", system.lagrangian.as_ref().map(Spanned::span)),
        ("builtin", system.builtin.as_ref().map(Spanned::span)),
        (
            "hamiltonian",
            system.hamiltonian.as_ref().map(Spanned::span),
        ),
        (
            "discrete_lagrangian",
            system.discrete_lagrangian.as_ref().map(Spanned::span),
        ),
        (
            "constraints",
            system.constraints.as_ref().map(Spanned::span),
        ),
        ("controls", system.controls.as_ref().map(Spanned::span)),
        ("rigid_body", system.rigid_body.as_ref().map(Spanned::span)),
        ("torques", system.torques.as_ref().map(Spanned::span)),
        ("forces", system.forces.as_ref().map(Spanned::span)),
        (
            "symmetry",
            system
                .symmetry
                .as_ref()
                .and_then(|s| s.first())
                .map(Spanned::span),
        ),
    ];
    match keys.into_iter().find_map(|(k, s)| s.map(|s| (k, s))) {
        Some((key, span)) => Err(ck
            .error(
                Some(span),
                format!("`{key}` cannot be used with `[[system.body]]`"),
            )
            .note(
                "a multibody system is given by its bodies, its joints, a uniform `gravity`, \
                   `[[system.spring]]`/`[[system.damper]]` between body points and a \
                   `potential` over the bodies' entries; load expressions and declared \
                   symmetries are not available for it yet",
            )),
        None => Ok(()),
    }
}

impl JointKindSpec {
    /// The kind's name as files write it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Spherical => "spherical",
            Self::Revolute { .. } => "revolute",
            Self::Prismatic { .. } => "prismatic",
            Self::Fixed => "fixed",
            Self::Distance { .. } => "distance",
        }
    }

    /// The number of constraint rows (`marsden::lie::multibody::joint`).
    pub fn rows(&self) -> usize {
        match self {
            Self::Spherical => 3,
            Self::Revolute { .. } | Self::Prismatic { .. } => 5,
            Self::Fixed => 6,
            Self::Distance { .. } => 1,
        }
    }
}

impl MultibodySpec {
    /// "2 rigid bodies", "1 rigid body and 1 particle", "3 particles".
    pub fn members(&self) -> String {
        let particles = self.bodies.iter().filter(|b| b.particle).count();
        let bodies = self.bodies.len() - particles;
        let count = |n: usize, one: &str, many: &str| match n {
            1 => format!("1 {one}"),
            n => format!("{n} {many}"),
        };
        match (bodies, particles) {
            (b, 0) => count(b, "rigid body", "rigid bodies"),
            (0, p) => count(p, "particle", "particles"),
            (b, p) => format!(
                "{} and {}",
                count(b, "rigid body", "rigid bodies"),
                count(p, "particle", "particles")
            ),
        }
    }

    /// The coordinates of the centres: `<body>_x, <body>_y, <body>_z` per body.
    pub fn centre_names(&self) -> Vec<String> {
        (self.bodies.iter())
            .flat_map(|b| ["x", "y", "z"].map(|a| format!("{}_{a}", b.name)))
            .collect()
    }

    /// The columns of a group of body quantities: `<body>_<suffix>` per body and particle and
    /// suffix (centres and momenta).
    pub fn body_columns(&self, suffixes: &[&str]) -> Vec<String> {
        (self.bodies.iter())
            .flat_map(|b| suffixes.iter().map(move |s| format!("{}_{s}", b.name)))
            .collect()
    }

    /// The columns of a group of attitude quantities: `<body>_<suffix>` per body (particles
    /// have none) and suffix.
    pub fn attitude_columns(&self, suffixes: &[&str]) -> Vec<String> {
        (self.bodies.iter().filter(|b| !b.particle))
            .flat_map(|b| suffixes.iter().map(move |s| format!("{}_{s}", b.name)))
            .collect()
    }

    /// The number of joint rows (multipliers).
    pub fn joint_rows(&self) -> usize {
        self.joints.iter().map(|j| j.kind.rows()).sum()
    }

    /// The multipliers' columns `lambda_<joint>_<i>`.
    pub fn lambda_columns(&self) -> Vec<String> {
        (self.joints.iter())
            .flat_map(|j| (0..j.kind.rows()).map(move |i| format!("lambda_{}_{i}", j.name)))
            .collect()
    }
}
