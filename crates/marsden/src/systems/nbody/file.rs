//! The N-body initial-data format of the benchmark data (kept beside the repository with the C
//! reference `verlet.c`): the first line holds the number of bodies `N`, then one line per body
//! `m x y z vx vy vz` (whitespace separated). Momenta are `p = m v`. Blank lines and lines starting
//! with `#` are skipped. Every error about the contents names the line (1-based) it was found on.
//!
//! [`load`] reads a file into a ready system and its initial state `(NBody, q₀, p₀)` (what a
//! `builtin = "nbody"` run needs); [`parse`] reads text into [`NBodyData`].
//!
//! ```
//! use marsden::systems::nbody::file;
//!
//! let data = file::parse("2\n1.0 0 0 0 0 0 0\n1e-3 1 0 0 0 1 0\n")?;
//! let (system, q0, p0) = data.into_system(1.0, 0.01)?;
//! assert_eq!((system.bodies(), q0[3], p0[4]), (2, 1.0, 1e-3));
//! # Ok::<(), marsden::systems::nbody::NBodyFileError>(())
//! ```

use crate::error::InputError;
use std::path::Path;

use thiserror::Error;

use super::NBody;

/// Masses, positions and velocities read from an N-body file (positions and velocities in the
/// coordinate order of [`super::NBody`]: `x₁ y₁ z₁ x₂ …`).
#[derive(Debug, Clone, PartialEq)]
pub struct NBodyData {
    /// One mass per body.
    pub masses: Vec<f64>,
    /// Positions, length `3N`.
    pub q: Vec<f64>,
    /// Velocities, length `3N`.
    pub v: Vec<f64>,
}

impl NBodyData {
    /// Momenta `pᵢ = mᵢ vᵢ`, length `3N`.
    pub fn momenta(&self) -> Vec<f64> {
        self.v
            .chunks_exact(3)
            .zip(&self.masses)
            .flat_map(|(v, m)| [m * v[0], m * v[1], m * v[2]])
            .collect()
    }

    /// The system of these bodies with gravitational constant `g` and softening length
    /// `softening` ([`NBody::with_parameters`]), and its initial positions and momenta.
    pub fn into_system(
        self,
        g: f64,
        softening: f64,
    ) -> Result<(NBody, Vec<f64>, Vec<f64>), NBodyFileError> {
        let p = self.momenta();
        let system = NBody::with_parameters(self.masses, g, softening).map_err(|e| match e {
            crate::error::Error::Input(InputError::InvalidOption {
                name,
                value,
                reason,
            }) => NBodyFileError::InvalidParameter {
                name,
                value,
                reason,
            },
            // `with_parameters` reports nothing else.
            _ => NBodyFileError::InvalidParameter {
                name: "system",
                value: f64::NAN,
                reason: "invalid N-body parameters",
            },
        })?;
        Ok((system, self.q, p))
    }
}

/// Reads the N-body file at `path` and builds the system with gravitational constant `g` and
/// softening length `softening`: `(system, q₀, p₀)`, momenta `p = m v`.
pub fn load(
    path: impl AsRef<Path>,
    g: f64,
    softening: f64,
) -> Result<(NBody, Vec<f64>, Vec<f64>), NBodyFileError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| NBodyFileError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    parse(&text)?.into_system(g, softening)
}

/// What is wrong with an N-body file, and where.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NBodyFileError {
    /// The file could not be read.
    #[error("cannot read `{path}`: {message}")]
    Io {
        /// The path given.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// `G` or the softening length is out of range (see [`NBody::with_parameters`]).
    #[error("invalid N-body parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// `G`, `softening` or `masses`.
        name: &'static str,
        /// The value given.
        value: f64,
        /// Valid range.
        reason: &'static str,
    },
    /// The file has no line with the number of bodies.
    #[error("the file is empty: the first line must hold the number of bodies N")]
    Empty,
    /// The first line is not a positive whole number.
    #[error("line {line}: the number of bodies must be a positive whole number, found `{found}`")]
    BadCount {
        /// Line number (1-based).
        line: usize,
        /// What was there.
        found: String,
    },
    /// A body's line does not hold seven numbers.
    #[error("line {line}: expected 7 numbers `m x y z vx vy vz`, found {found} field(s): `{text}`")]
    FieldCount {
        /// Line number (1-based).
        line: usize,
        /// Number of fields found.
        found: usize,
        /// The line.
        text: String,
    },
    /// A field is not a finite number.
    #[error("line {line}: field {field} (`{name}`) is not a finite number: `{found}`")]
    BadNumber {
        /// Line number (1-based).
        line: usize,
        /// Field position (1-based).
        field: usize,
        /// Field name (`m`, `x`, …).
        name: &'static str,
        /// What was there.
        found: String,
    },
    /// A mass is zero or negative.
    #[error("line {line}: the mass must be positive, found {mass}")]
    NonPositiveMass {
        /// Line number (1-based).
        line: usize,
        /// The mass.
        mass: f64,
    },
    /// Fewer body lines than announced.
    #[error("the first line announces {expected} bodies, but the file has {found}")]
    MissingBodies {
        /// Bodies announced.
        expected: usize,
        /// Body lines found.
        found: usize,
    },
    /// More body lines than announced.
    #[error("line {line}: more bodies than the {expected} announced on the first line")]
    ExtraBodies {
        /// Line number (1-based) of the first extra body.
        line: usize,
        /// Bodies announced.
        expected: usize,
    },
}

const FIELDS: [&str; 7] = ["m", "x", "y", "z", "vx", "vy", "vz"];

/// Parses the text of an N-body file.
pub fn parse(text: &str) -> Result<NBodyData, NBodyFileError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (line, first) = lines.next().ok_or(NBodyFileError::Empty)?;
    let expected = first
        .parse::<usize>()
        .ok()
        .filter(|n| *n > 0)
        .ok_or_else(|| NBodyFileError::BadCount {
            line,
            found: first.to_owned(),
        })?;
    let mut data = NBodyData {
        masses: Vec::with_capacity(expected),
        q: Vec::with_capacity(3 * expected),
        v: Vec::with_capacity(3 * expected),
    };
    for (line, text) in lines {
        if data.masses.len() == expected {
            return Err(NBodyFileError::ExtraBodies { line, expected });
        }
        let body = parse_body(line, text)?;
        data.masses.push(body[0]);
        data.q.extend_from_slice(&body[1..4]);
        data.v.extend_from_slice(&body[4..7]);
    }
    if data.masses.len() != expected {
        return Err(NBodyFileError::MissingBodies {
            expected,
            found: data.masses.len(),
        });
    }
    Ok(data)
}

/// One body's line: seven finite numbers, the mass positive.
fn parse_body(line: usize, text: &str) -> Result<[f64; 7], NBodyFileError> {
    let fields: Vec<&str> = text.split_whitespace().collect();
    if fields.len() != 7 {
        return Err(NBodyFileError::FieldCount {
            line,
            found: fields.len(),
            text: text.to_owned(),
        });
    }
    let mut body = [0.0; 7];
    for (k, (slot, field)) in body.iter_mut().zip(&fields).enumerate() {
        *slot = field
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| NBodyFileError::BadNumber {
                line,
                field: k + 1,
                name: FIELDS[k],
                found: (*field).to_owned(),
            })?;
    }
    if body[0] <= 0.0 {
        return Err(NBodyFileError::NonPositiveMass {
            line,
            mass: body[0],
        });
    }
    Ok(body)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_bodies_and_momenta() {
        let data = parse("2\n1.0 0 0 0 0 0 0\n# comment\n\n0.5 1 2 3 4 5 6\n").unwrap();
        assert_eq!(data.masses, [1.0, 0.5]);
        assert_eq!(data.q, [0.0, 0.0, 0.0, 1.0, 2.0, 3.0]);
        assert_eq!(data.momenta()[3..], [2.0, 2.5, 3.0]);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse("2\n1 0 0 0 0 0 0\n1 0 0 x 0 0 0\n").unwrap_err();
        assert_eq!(
            e,
            NBodyFileError::BadNumber {
                line: 3,
                field: 4,
                name: "z",
                found: "x".into()
            }
        );
        assert!(e.to_string().starts_with("line 3:"), "{e}");
        let e = parse("2\n1 0 0 0 0 0\n").unwrap_err();
        assert!(matches!(
            e,
            NBodyFileError::FieldCount {
                line: 2,
                found: 6,
                ..
            }
        ));
        assert!(matches!(
            parse("two\n").unwrap_err(),
            NBodyFileError::BadCount { line: 1, .. }
        ));
        assert!(matches!(
            parse("2\n1 0 0 0 0 0 0\n").unwrap_err(),
            NBodyFileError::MissingBodies {
                expected: 2,
                found: 1
            }
        ));
        assert!(matches!(
            parse("1\n1 0 0 0 0 0 0\n1 0 0 0 0 0 0\n").unwrap_err(),
            NBodyFileError::ExtraBodies {
                line: 3,
                expected: 1
            }
        ));
        assert!(matches!(
            parse("1\n-1 0 0 0 0 0 0\n").unwrap_err(),
            NBodyFileError::NonPositiveMass { line: 2, .. }
        ));
        assert_eq!(parse(""), Err(NBodyFileError::Empty));
    }
}
