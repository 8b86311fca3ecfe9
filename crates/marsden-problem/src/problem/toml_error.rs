//! `toml`'s errors in the problem file's words: unknown keys name the key and its table,
//! suggest the closest valid key and list them all; other errors keep `toml`'s message and
//! point at the span it reports.

use crate::error::Diagnostic;
use crate::source::SourceFile;
use marsden_expr::closest;

/// Turns a parse error of `source` into a diagnostic.
pub fn diagnose(source: &SourceFile, error: &toml::de::Error) -> Diagnostic {
    let location = source.locate_opt(error.span());
    match unknown_key(error.message()) {
        Some((key, valid)) => {
            let table = table_of(&valid);
            let mut sorted = valid.clone();
            sorted.sort_unstable();
            Diagnostic::new(format!("unknown key `{key}` in {table}"))
                .at(location)
                .suggest(closest(key, valid.iter().copied()))
                .note(format!("valid keys in {table}: {}", sorted.join(", ")))
        }
        None => Diagnostic::new(format!(
            "the problem file is not valid: {}",
            crate::source::shorten(error.message().trim_end(), 300)
        ))
        .at(location),
    }
}

/// The key and the valid keys from serde's `unknown field` message:
/// ``unknown field `k`, expected one of `a`, `b`, `c` `` (or ``expected `a` or `b` ``,
/// ``expected `a` ``, `there are no fields`).
fn unknown_key(message: &str) -> Option<(&str, Vec<&str>)> {
    let rest = message.strip_prefix("unknown field `")?;
    let (key, rest) = rest.split_once('`')?;
    let valid = rest.split('`').skip(1).step_by(2).collect();
    Some((key, valid))
}

/// Which table a list of valid keys belongs to (each raw struct has a key no other one has).
fn table_of(valid: &[&str]) -> &'static str {
    let has = |key: &str| valid.contains(&key);
    if has("lagrangian") {
        "[system]"
    } else if has("kind") && has("bodies") {
        "[[system.joint]]"
    } else if has("inertia") && has("name") {
        "[[system.body]]"
    } else if has("mass") && has("name") && valid.len() == 2 {
        "[[system.particle]]"
    } else if has("Omega") && !has("q") {
        "[initial.<body>]"
    } else if has("generator") {
        "[[system.symmetry]]"
    } else if has("cost") {
        "[optimal_control]"
    } else if has("q") && !has("project") {
        "`start` or `end` of [optimal_control]"
    } else if has("when") {
        "[[events]]"
    } else if has("q") {
        "[initial]"
    } else if has("method") {
        "[integrator]"
    } else if has("format") {
        "[output]"
    } else if has("values") {
        "[sweep]"
    } else if has("every_step") {
        "[analysis]"
    } else if has("stop") {
        "[sweep] range"
    } else if has("system") {
        "the top level of the file"
    } else {
        "this table"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::raw;

    fn diagnose_text(text: &str) -> String {
        let source = SourceFile::new("p.toml", text.to_owned());
        let err = raw::parse(text).unwrap_err();
        diagnose(&source, &err).to_string()
    }

    #[test]
    fn unknown_key_names_key_table_suggestion_and_valid_keys() {
        let msg = diagnose_text("[system]\nbuiltin = \"pendulum\"\nlagrangain = \"x\"\n");
        assert!(
            msg.starts_with("error: unknown key `lagrangain` in [system]\n"),
            "{msg}"
        );
        assert!(msg.contains(" --> p.toml:3:1"), "{msg}");
        assert!(msg.contains("= help: did you mean `lagrangian`?"), "{msg}");
        assert!(
            msg.contains("= note: valid keys in [system]: body, builtin, constraints"),
            "{msg}"
        );
    }

    #[test]
    fn unknown_keys_in_every_table() {
        for (text, table) in [
            ("[initial]\nqq = [1]\n", "[initial]"),
            ("[integrator]\nstep = 1\n", "[integrator]"),
            ("[output]\nplot = true\n", "[output]"),
            (
                "[[system.symmetry]]\ngen = [\"1\"]\n",
                "[[system.symmetry]]",
            ),
            ("[sytem]\n", "the top level of the file"),
            (
                "[[events]]\nwhen = \"x\"\ndirecton = \"up\"\n",
                "[[events]]",
            ),
        ] {
            let msg = diagnose_text(text);
            assert!(msg.contains(&format!(" in {table}\n")), "{msg}");
        }
    }

    #[test]
    fn syntax_errors_keep_the_toml_message_and_location() {
        let msg = diagnose_text("[integrator]\nh = 0.05.1\n");
        assert!(
            msg.starts_with("error: the problem file is not valid: "),
            "{msg}"
        );
        assert!(msg.contains("p.toml:2:"), "{msg}");
    }
}
