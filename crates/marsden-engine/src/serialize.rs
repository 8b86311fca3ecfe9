//! Serde helpers shared by the engine's records and the summary written from them.

use serde::Serialize;

/// Serialises `(key, value)` pairs as a JSON object, keeping their order.
///
/// # Errors
/// The serializer's.
pub fn as_object<S: serde::Serializer, V: Serialize>(
    pairs: &[(String, V)],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_map(pairs.iter().map(|(k, v)| (k, v)))
}
