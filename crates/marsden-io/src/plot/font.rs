//! The embedded font: plots never look for fonts on the machine.
//!
//! plotters is built with its `ab_glyph` feature and without `ttf`, so text is drawn only
//! with fonts registered through `plotters::style::register_font`; there is no system font
//! lookup at all. Every text style in this crate names [`FAMILY`], a name no system font
//! has, so a build in which something re-enabled plotters' `ttf` feature (which would swap
//! in system-font lookup) fails loudly in the plot tests instead of silently depending on
//! the machine's fonts. Do not enable plotters' `ttf` or default features elsewhere in the
//! workspace.

use std::sync::OnceLock;

use plotters::style::FontStyle;

/// The font family name under which the embedded DejaVu Sans is registered.
pub const FAMILY: &str = "marsden-embedded-dejavu-sans";

/// DejaVu Sans 2.37 (license: `assets/DejaVuSans-LICENSE.txt`).
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the embedded font once per process; later calls only report the outcome.
pub(crate) fn ensure_registered() -> Result<(), &'static str> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err("the embedded font could not be parsed")
    }
}
