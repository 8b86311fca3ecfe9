//! `translation = "x"`, `rotation = "z"`: the generator lists they stand for, and a pointed
//! error for a name that does not fit the system.

use super::refused;
use marsden_spec::RunSpec;

/// Kepler (coordinates x, y) with the symmetry lines `symmetry`.
fn kepler(symmetry: &str) -> String {
    format!(
        "[system]\nbuiltin = \"kepler\"\n{symmetry}\n[initial]\nq = [0.4, 0.0]\np = [0.0, 2.0]\n\
         [integrator]\nmethod = \"midpoint\"\nh = 0.01\nsteps = 20\n[output]\nplots = false\n"
    )
}

/// Three bodies (coordinates x1 y1 z1 … z3) with the symmetry lines `symmetry`.
fn nbody(symmetry: &str) -> String {
    format!(
        "[system]\nbuiltin = \"nbody\"\nparameters = {{ masses = [1.0, 1.0, 1.0] }}\n{symmetry}\n\
         [initial]\nq = [1, 0, 0, -1, 0, 0, 0, 1, 0.5]\np = [0, 0.5, 0, 0, -0.5, 0, 0.1, 0, 0]\n\
         [integrator]\nh = 0.01\nsteps = 5\n[output]\nplots = false\n"
    )
}

fn symmetries(text: &str) -> Vec<marsden_spec::model::Symmetry> {
    let spec = RunSpec::from_toml_str(text, "p.toml").unwrap_or_else(|d| panic!("{d}"));
    spec.system.symmetries
}

#[test]
fn named_symmetries_compile_to_the_written_generator_lists() {
    let named = symmetries(&nbody(
        "[[system.symmetry]]\ntranslation = \"x\"\n[[system.symmetry]]\ntranslation = \"y\"\n\
         [[system.symmetry]]\nrotation = \"z\"\n[[system.symmetry]]\nname = \"Lx\"\nrotation = \"x\"\n",
    ));
    let written = symmetries(&nbody(
        "[[system.symmetry]]\nname = \"Px\"\ngenerator = [\"1\", \"0\", \"0\", \"1\", \"0\", \"0\", \"1\", \"0\", \"0\"]\n\
         [[system.symmetry]]\nname = \"Py\"\ngenerator = [\"0\", \"1\", \"0\", \"0\", \"1\", \"0\", \"0\", \"1\", \"0\"]\n\
         [[system.symmetry]]\nname = \"Lz\"\ngenerator = [\"-y1\", \"x1\", \"0\", \"-y2\", \"x2\", \"0\", \"-y3\", \"x3\", \"0\"]\n\
         [[system.symmetry]]\nname = \"Lx\"\ngenerator = [\"0\", \"-z1\", \"y1\", \"0\", \"-z2\", \"y2\", \"0\", \"-z3\", \"y3\"]\n",
    ));
    assert_eq!(named, written);
    let planar = symmetries(&kepler("[[system.symmetry]]\nrotation = \"z\"\n"));
    let list = symmetries(&kepler(
        "[[system.symmetry]]\nname = \"Lz\"\ngenerator = [\"-y\", \"x\"]\n",
    ));
    assert_eq!(planar, list);
}

#[test]
fn a_named_symmetry_that_does_not_fit_is_refused_with_the_valid_names() {
    let shown = refused(&kepler("[[system.symmetry]]\ntranslation = \"z\"\n"));
    assert!(
        shown.contains("`translation = \"z\"` does not fit"),
        "{shown}"
    );
    assert!(
        shown.contains("valid here: translation = \"x\", \"y\""),
        "{shown}"
    );
    assert!(shown.contains("p.toml:"), "{shown}");
    let shown = refused(&kepler("[[system.symmetry]]\nrotation = \"x\"\n"));
    assert!(shown.contains("valid here: rotation = \"z\""), "{shown}");
    let shown = refused(&kepler("[[system.symmetry]]\nrotation = \"w\"\n"));
    assert!(shown.contains("must be \"x\", \"y\" or \"z\""), "{shown}");
    let pendulum = kepler("[[system.symmetry]]\nrotation = \"z\"\n")
        .replace("builtin = \"kepler\"", "builtin = \"pendulum\"")
        .replace("[0.4, 0.0]", "[0.4]")
        .replace("[0.0, 2.0]", "[0.0]");
    let shown = refused(&pendulum);
    assert!(
        shown.contains("no `rotation` fits the coordinates (theta)"),
        "{shown}"
    );
}

#[test]
fn a_named_symmetry_with_a_generator_or_two_names_is_refused() {
    let shown = refused(&kepler(
        "[[system.symmetry]]\nrotation = \"z\"\ngenerator = [\"-y\", \"x\"]\n",
    ));
    assert!(
        shown.contains("either `generator` or `rotation`"),
        "{shown}"
    );
    let shown = refused(&kepler(
        "[[system.symmetry]]\nrotation = \"z\"\ntranslation = \"x\"\n",
    ));
    assert!(
        shown.contains("either `translation` or `rotation`"),
        "{shown}"
    );
    let shown = refused(&kepler(
        "[[system.symmetry]]\nrotation = \"z\"\n[[system.symmetry]]\nrotation = \"z\"\n",
    ));
    assert!(
        shown.contains("symmetry name `Lz` must be unique"),
        "{shown}"
    );
}
