//! The blocks of `summary.json` for bodies: a rigid body's invariants and last attitude
//! (`rigid_body`), and a multibody run's joints, attitudes and total momenta (`multibody`).

use serde::Serialize;

use marsden_engine::serialize::as_object;

/// `rigid_body { … }`: what a rigid body's run kept besides the energy and the momenta.
#[derive(Debug, Clone, Serialize)]
pub struct RigidBodySummary {
    /// `max |RᵀR − I|` over the stored samples: the attitude stays a rotation.
    pub orthogonality_defect: f64,
    /// The Casimir `|Π|²`: initial value and largest drift over the stored samples (constant
    /// for a free body).
    pub casimir: CasimirSummary,
    /// The last good attitude, rows (body → space).
    pub final_attitude: [[f64; 3]; 3],
    /// The last good body momentum `Π`.
    pub final_body_momentum: Vec<f64>,
}

/// `multibody { … }`: what a multibody run kept besides the energy.
#[derive(Debug, Clone, Serialize)]
pub struct MultibodySummary {
    /// Number of bodies.
    pub bodies: usize,
    /// Number of particles.
    pub particles: usize,
    /// The joints, in the file's order.
    pub joints: Vec<JointSummary>,
    /// `max |g|` over the stored samples and all joint rows: the joints hold.
    pub max_joint_residual: f64,
    /// `max |RᵀR − I|` over the stored samples and all bodies.
    pub orthogonality_defect: f64,
    /// The total angular momentum about the origin `Σ RΠ + x × p`: initial value and largest
    /// drift per axis (conserved about an axis through the origin that the joints and the
    /// field are symmetric about; monitored otherwise).
    pub angular_momentum: AngularMomentumSummary,
    /// Newton iterations on the joints' multipliers over the run.
    pub joint_iterations: usize,
    /// The last good attitude of each body, rows (body → space), by body name.
    #[serde(serialize_with = "as_object")]
    pub final_attitudes: Vec<(String, [[f64; 3]; 3])>,
    /// The multipliers of the last step, by joint name (the reaction on a body is `−Σ λ ∂g/∂x`).
    #[serde(serialize_with = "as_object")]
    pub final_multipliers: Vec<(String, Vec<f64>)>,
}

/// One joint of `multibody.joints`.
#[derive(Debug, Clone, Serialize)]
pub struct JointSummary {
    /// Its name.
    pub name: String,
    /// Its kind.
    pub kind: &'static str,
    /// The two sides (body names or `ground`).
    pub bodies: [String; 2],
    /// Its constraint rows.
    pub rows: usize,
}

/// `angular_momentum { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct AngularMomentumSummary {
    /// `L₀`.
    pub initial: [f64; 3],
    /// `max_k |L_k − L₀|` per axis.
    pub max_abs_drift: [f64; 3],
}

impl MultibodySummary {
    pub(crate) fn of(
        spec: &crate::problem::multibody::MultibodySpec,
        record: &marsden_engine::multibody::MultibodyRecord,
    ) -> Self {
        let name =
            |s: Option<usize>| s.map_or("ground".to_owned(), |b| spec.bodies[b].name.clone());
        let joints = (spec.joints.iter())
            .map(|j| JointSummary {
                name: j.name.clone(),
                kind: j.kind.name(),
                bodies: [name(j.bodies[0]), name(j.bodies[1])],
                rows: j.kind.rows(),
            })
            .collect();
        let r = &record.final_attitudes;
        let final_attitudes = (spec.bodies.iter().enumerate())
            .filter(|(_, b)| !b.particle)
            .map(|(i, b)| {
                let a = &r[9 * i..9 * i + 9];
                (
                    b.name.clone(),
                    [[a[0], a[1], a[2]], [a[3], a[4], a[5]], [a[6], a[7], a[8]]],
                )
            })
            .collect();
        let mut offset = 0;
        let final_multipliers = (spec.joints.iter())
            .map(|j| {
                let rows = j.kind.rows();
                let values = record
                    .final_multipliers
                    .get(offset..offset + rows)
                    .unwrap_or_default()
                    .to_vec();
                offset += rows;
                (j.name.clone(), values)
            })
            .collect();
        let l = &record.angular_momentum;
        MultibodySummary {
            bodies: spec.bodies.iter().filter(|b| !b.particle).count(),
            particles: spec.bodies.iter().filter(|b| b.particle).count(),
            joints,
            max_joint_residual: record.max_joint_residual,
            orthogonality_defect: record.max_orthogonality_defect,
            angular_momentum: AngularMomentumSummary {
                initial: [l[0].initial, l[1].initial, l[2].initial],
                max_abs_drift: [l[0].max_abs_drift, l[1].max_abs_drift, l[2].max_abs_drift],
            },
            joint_iterations: record.joint_iterations,
            final_attitudes,
            final_multipliers,
        }
    }
}

/// `casimir { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct CasimirSummary {
    /// `|Π₀|²`.
    pub initial: f64,
    /// `max |(|Π_k|² − |Π₀|²)|`.
    pub max_abs_drift: f64,
}

impl RigidBodySummary {
    pub(crate) fn of(record: &marsden_engine::rigid::RigidRecord) -> Self {
        let r = &record.final_attitude;
        RigidBodySummary {
            orthogonality_defect: record.monitor.max_orthogonality_defect,
            casimir: CasimirSummary {
                initial: record.monitor.casimir.initial,
                max_abs_drift: record.monitor.casimir.max_abs_drift,
            },
            final_attitude: [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]],
            final_body_momentum: record.final_momentum.clone(),
        }
    }
}
