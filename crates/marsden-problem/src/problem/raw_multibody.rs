//! Stage 1 of a multibody file: `[[system.body]]`, `[[system.joint]]` and the per-body tables
//! `[initial.<body>]`, as written ([`super::raw`]'s conventions: every field optional, values
//! spanned, unknown keys refused).
//!
//! ```toml
//! [system]
//! gravity = [0.0, 0.0, -9.81]
//! [[system.body]]
//! name = "a"
//! mass = 1.0
//! inertia = [0.0833, 0.0833, 0.001]
//! [[system.joint]]
//! kind = "revolute"                 # spherical | revolute | prismatic | fixed | distance
//! bodies = ["ground", "a"]
//! at = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]
//! axis = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
//! [[system.spring]]                 # or [[system.damper]] with `coefficient = c`
//! bodies = ["ground", "a"]
//! at = [[1.0, 0.0, 0.0], [0.0, 0.0, 0.5]]
//! stiffness = 10.0
//! rest_length = 0.5                 # default: the distance at the start
//! [initial.a]
//! x = [0.0, 0.0, -0.5]
//! R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]   # or quaternion / rotation_vector
//! v = [0.0, 0.0, 0.0]                     # or p
//! Omega = [0.0, 0.0, 0.0]                 # or Pi
//! ```
//!
//! `[initial]` keeps its own keys beside the body tables; its deserializer
//! ([`super::raw::RawInitial`]'s) sends every key it does not know to [`RawBodyInitial`] when
//! the value is a table, and refuses it with serde's "unknown field" message otherwise (so the
//! "did you mean" of [`super::toml_error`] still applies).

use serde::Deserialize;
use toml::Spanned;

use super::raw::{RawInertia, SpannedList};

/// `[[system.body]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBody {
    /// The body's name (its columns are `<name>_x`, `<name>_R11`, …).
    pub name: Option<Spanned<String>>,
    /// Its mass.
    pub mass: Option<Spanned<f64>>,
    /// Principal moments about the centre of mass (body axes) or the 3×3 tensor.
    pub inertia: Option<Spanned<RawInertia>>,
}

/// `[[system.particle]]`: a point mass (configuration ℝ³).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawParticle {
    /// The particle's name (its columns are `<name>_x`, `<name>_p_x`, …).
    pub name: Option<Spanned<String>>,
    /// Its mass.
    pub mass: Option<Spanned<f64>>,
}

/// `[[system.joint]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawJoint {
    /// A name for its columns (`lambda_<name>_<i>`; default `<kind><index>`).
    pub name: Option<Spanned<String>>,
    /// `spherical`, `revolute`, `prismatic`, `fixed` or `distance`.
    pub kind: Option<Spanned<String>>,
    /// The two sides: body names or `"ground"`.
    pub bodies: Option<Spanned<Vec<String>>>,
    /// The joint point in each side's frame (the space frame for the ground).
    pub at: Option<Spanned<Vec<Vec<f64>>>>,
    /// Revolute: the hinge axis in each frame; prismatic: the sliding axis in the first side's
    /// frame (the second entry is then ignored; one entry is enough).
    pub axis: Option<Spanned<Vec<Vec<f64>>>>,
    /// Distance: the rod's length (default: the distance in the initial state).
    pub length: Option<Spanned<f64>>,
}

/// `[[system.spring]]`: `U = ½ k (‖p_b − p_a‖ − ℓ₀)²` between two points.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSpring {
    /// A name for messages (default `spring<index>`).
    pub name: Option<Spanned<String>>,
    /// The two sides: body names or `"ground"`.
    pub bodies: Option<Spanned<Vec<String>>>,
    /// The point in each side's frame (the space frame for the ground).
    pub at: Option<Spanned<Vec<Vec<f64>>>>,
    /// The stiffness `k ≥ 0`.
    pub stiffness: Option<Spanned<f64>>,
    /// The rest length `ℓ₀ ≥ 0` (default: the distance of the points in the initial state).
    pub rest_length: Option<Spanned<f64>>,
}

/// `[[system.damper]]`: the force `−c (ḋ·e) e` along the line of two points.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDamper {
    /// A name for messages (default `damper<index>`).
    pub name: Option<Spanned<String>>,
    /// The two sides: body names or `"ground"`.
    pub bodies: Option<Spanned<Vec<String>>>,
    /// The point in each side's frame (the space frame for the ground).
    pub at: Option<Spanned<Vec<Vec<f64>>>>,
    /// The coefficient `c ≥ 0`.
    pub coefficient: Option<Spanned<f64>>,
}

/// `[initial.<body>]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBodyInitial {
    /// The centre of mass.
    pub x: Option<SpannedList<f64>>,
    /// Its velocity (or `p`).
    pub v: Option<SpannedList<f64>>,
    /// Its momentum `m v` (or `v`).
    pub p: Option<SpannedList<f64>>,
    /// The attitude as a matrix (rows; body → space).
    #[serde(rename = "R")]
    pub r: Option<Spanned<Vec<Vec<f64>>>>,
    /// The attitude as a unit quaternion `[w, x, y, z]`.
    pub quaternion: Option<SpannedList<f64>>,
    /// The attitude as a rotation vector (axis times angle).
    pub rotation_vector: Option<SpannedList<f64>>,
    /// The body angular velocity (or `Pi`).
    #[serde(rename = "Omega")]
    pub omega: Option<SpannedList<f64>>,
    /// The body angular momentum `Π = JΩ` (or `Omega`).
    #[serde(rename = "Pi")]
    pub pi: Option<SpannedList<f64>>,
}

/// One `[initial.<body>]` table with the body's name as written.
#[derive(Debug)]
pub struct NamedBodyInitial {
    /// The table's name.
    pub name: String,
    /// Its keys.
    pub data: RawBodyInitial,
}

/// The value of a key `[initial]` does not know: a body's table, or an unknown key.
pub(super) struct BodyOrUnknown<'k> {
    /// The key, for the "unknown field" message.
    pub key: &'k str,
    /// The keys `[initial]` knows, for the same message.
    pub known: &'static [&'static str],
}

impl<'de> serde::de::DeserializeSeed<'de> for BodyOrUnknown<'_> {
    type Value = RawBodyInitial;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Self::Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> serde::de::Visitor<'de> for BodyOrUnknown<'_> {
    type Value = RawBodyInitial;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "a table [initial.{}] of a body's initial data", self.key)
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
        RawBodyInitial::deserialize(serde::de::value::MapAccessDeserializer::new(map))
    }

    fn visit_bool<E: serde::de::Error>(self, _: bool) -> Result<Self::Value, E> {
        Err(E::unknown_field(self.key, self.known))
    }
    fn visit_i64<E: serde::de::Error>(self, _: i64) -> Result<Self::Value, E> {
        Err(E::unknown_field(self.key, self.known))
    }
    fn visit_u64<E: serde::de::Error>(self, _: u64) -> Result<Self::Value, E> {
        Err(E::unknown_field(self.key, self.known))
    }
    fn visit_f64<E: serde::de::Error>(self, _: f64) -> Result<Self::Value, E> {
        Err(E::unknown_field(self.key, self.known))
    }
    fn visit_str<E: serde::de::Error>(self, _: &str) -> Result<Self::Value, E> {
        Err(E::unknown_field(self.key, self.known))
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, _: A) -> Result<Self::Value, A::Error> {
        Err(serde::de::Error::unknown_field(self.key, self.known))
    }
}
