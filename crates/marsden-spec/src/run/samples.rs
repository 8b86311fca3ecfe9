//! The stored samples of a run kept in memory ([`Samples`]), and the sinks that route rows:
//! [`Tee`] (files and memory at once) and [`NullSink`] (sweep members keep nothing).
//!
//! A row is laid out as the files are (`t, q…, p…, energy, J…, constraint_residual, λ…,
//! observables…, constraint_velocity_residual`, see
//! [`output`](super::output)); rows bound for memory carry the velocities `v…` after that.

use marsden_io::RowSink;

use crate::problem::SystemSpec;

/// The stored samples of a run, one column per quantity: row `k` of every column is the
/// `k`-th stored state (every `[output] every`-th step, the first and the last).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Samples {
    /// Coordinate names (the order of the columns of `q`, `p` and `v`).
    pub coordinates: Vec<String>,
    /// Times.
    pub t: Vec<f64>,
    /// A rigid body's attitude: nine columns, `R11 … R33` (row-major); empty otherwise.
    pub attitude: Vec<Vec<f64>>,
    /// A rigid body's body momentum: three columns `Π₁ … Π₃`; empty otherwise.
    pub body_momentum: Vec<Vec<f64>>,
    /// Positions: `q[i]` is the column of coordinate `i`.
    pub q: Vec<Vec<f64>>,
    /// Momenta, per coordinate.
    pub p: Vec<Vec<f64>>,
    /// Velocities (by the inverse Legendre transform; NaN where it failed, and for a file's own
    /// `L_d`), per coordinate.
    pub v: Vec<Vec<f64>>,
    /// Energy `⟨p, v⟩ − L` (empty for a file's own `L_d`: no continuous L, no energy).
    pub energy: Vec<f64>,
    /// Whether the rows carry an energy.
    has_energy: bool,
    /// Momentum maps `J`, by symmetry name (in the file's order).
    pub momenta: Vec<(String, Vec<f64>)>,
    /// `max_i |φ_i(q)|`, if the system has constraints.
    pub constraint_residual: Option<Vec<f64>>,
    /// The multipliers `λ_i`, one column per constraint.
    pub lambda: Vec<Vec<f64>>,
    /// `[output] observables`, by name (in the file's order).
    pub observables: Vec<(String, Vec<f64>)>,
    /// The hidden constraint's residual `max_i |(Dφ(q)·v)_i|`, if the system has constraints.
    pub constraint_velocity_residual: Option<Vec<f64>>,
}

impl Samples {
    /// Empty columns for the trajectory of `system`.
    pub fn new(system: &SystemSpec) -> Self {
        let n = system.dof();
        let multibody = system.multibody();
        let joint_rows = multibody.map_or(0, |m| m.joint_rows());
        let constrained = !system.constraint.components().is_empty() || multibody.is_some();
        // One attitude per body: a rigid body's, or each of a multibody system's (particles
        // have none).
        let bodies = match (system.rigid(), multibody) {
            (Some(_), _) => 1,
            (None, Some(m)) => m.bodies.iter().filter(|b| !b.particle).count(),
            (None, None) => 0,
        };
        Self {
            coordinates: system.coordinates.clone(),
            t: Vec::new(),
            attitude: vec![Vec::new(); 9 * bodies],
            body_momentum: vec![Vec::new(); 3 * bodies],
            q: vec![Vec::new(); n],
            p: vec![Vec::new(); n],
            v: vec![Vec::new(); n],
            energy: Vec::new(),
            has_energy: system.has_energy(),
            momenta: (system.momentum_names().into_iter())
                .map(|name| (name, Vec::new()))
                .collect(),
            constraint_residual: constrained.then(Vec::new),
            lambda: vec![Vec::new(); system.constraint.components().len() + joint_rows],
            observables: Vec::new(),
            constraint_velocity_residual: constrained.then(Vec::new),
        }
    }

    /// Empty columns for the trajectory of `spec`: its system's, and its observables'.
    pub fn of(spec: &crate::problem::RunSpec) -> Self {
        let mut samples = Self::new(&spec.system);
        samples.observables = (spec.events.observables.names.iter())
            .map(|name| (name.clone(), Vec::new()))
            .collect();
        samples
    }

    /// Number of stored samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether nothing was stored.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Values per row as the files have them (without the velocities).
    pub fn file_width(&self) -> usize {
        let n = self.coordinates.len();
        1 + usize::from(self.has_energy)
            + self.attitude.len()
            + self.body_momentum.len()
            + 2 * n
            + self.momenta.len()
            + usize::from(self.constraint_residual.is_some())
            + self.lambda.len()
            + self.observables.len()
            + usize::from(self.constraint_velocity_residual.is_some())
    }
}

/// Splits a row (the file columns, then `v`) into the columns.
impl RowSink for Samples {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        let mut values = row.iter().copied();
        let mut next = || values.next().unwrap_or(f64::NAN);
        self.t.push(next());
        for column in self.attitude.iter_mut().chain(&mut self.body_momentum) {
            column.push(next());
        }
        for column in self.q.iter_mut().chain(&mut self.p) {
            column.push(next());
        }
        if self.has_energy {
            self.energy.push(next());
        }
        for (_, column) in &mut self.momenta {
            column.push(next());
        }
        if let Some(column) = &mut self.constraint_residual {
            column.push(next());
        }
        let observables = self.observables.iter_mut().map(|(_, c)| c);
        let hidden = self.constraint_velocity_residual.iter_mut();
        for column in (self.lambda.iter_mut().chain(observables).chain(hidden)).chain(&mut self.v) {
            column.push(next());
        }
        Ok(())
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn rows_written(&self) -> u64 {
        self.t.len() as u64
    }
}

/// Rows to the files (their columns only) and to memory (with the velocities).
pub struct Tee<'a> {
    /// The file writer.
    pub files: &'a mut dyn RowSink,
    /// The in-memory columns.
    pub memory: &'a mut Samples,
}

impl RowSink for Tee<'_> {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        let width = self.memory.file_width().min(row.len());
        self.files.write_row(&row[..width])?;
        self.memory.write_row(row)
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        self.files.flush()
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        self.files.finish()
    }
    fn rows_written(&self) -> u64 {
        self.files.rows_written()
    }
    /// The files' mark: what a checkpoint cuts them back to (the memory is not resumed).
    fn mark(&mut self) -> marsden_io::Result<marsden_io::SinkMark> {
        self.files.mark()
    }
}

/// A sink that keeps nothing (sweep members write no trajectory).
#[derive(Debug, Default)]
pub struct NullSink {
    rows: u64,
}

impl RowSink for NullSink {
    fn write_row(&mut self, _row: &[f64]) -> marsden_io::Result<()> {
        self.rows += 1;
        Ok(())
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn rows_written(&self) -> u64 {
        self.rows
    }
}
