//! Overrides applied to a problem already validated: a binding checks a problem once and then
//! runs it with other outputs (Python's `solve(every=…, dir=…, checkpoint_every=…)`) without
//! reading the file again.
//!
//! The output's overrides change nothing the other checks looked at, so they are applied to a
//! copy of the validated [`RunSpec`] by the same functions the file's checks call
//! ([`settings::every_override`], [`settings::checkpoint_every_override`],
//! [`checkpoints::refuse_at`]): the same values refused with the same words. The grid's
//! overrides (`steps`, `h`) change what was checked (`t_end`, `[output] times`, the last
//! step), so with one of them the file's text is validated again.

use super::check::Checker;
use super::spec::{Overrides, RunSpec};
use super::{checkpoints, settings, validate};
use crate::error::Diagnostic;

impl RunSpec {
    /// This problem with `overrides` applied on top of its own (a value given in both is
    /// `overrides`'): the spec [`from_toml_str`](super::from_toml_str) would give with the two
    /// merged, its [`RunSpec::overrides`] recording them for checkpoints.
    ///
    /// A problem with `[sweep]` applies them to the sweep; a member of a sweep
    /// ([`member`](super::member)) takes its overrides when it is made.
    ///
    /// # Errors
    /// A value the overrides cannot take (`every` or `checkpoint_every` of 0, checkpoints of
    /// a run that cannot be resumed), as the file's checks word it.
    pub fn with_overrides(&self, overrides: &Overrides) -> Result<RunSpec, Diagnostic> {
        let merged = merge(&self.overrides, overrides);
        if overrides.steps.is_some() || overrides.h.is_some() {
            return validate(self.source.clone(), &merged);
        }
        let mut spec = self.clone();
        if let Some(dir) = &overrides.out {
            spec.output.dir = dir.clone();
        }
        if let Some(every) = overrides.every {
            spec.output.every = settings::every_override(every)?;
        }
        if let Some(every) = overrides.checkpoint_every {
            spec.output.checkpoint_every = Some(settings::checkpoint_every_override(every)?);
            refuse_checkpoints(&spec)?;
        }
        spec.overrides = merged;
        Ok(spec)
    }
}

/// `base`'s overrides with `over`'s on top.
fn merge(base: &Overrides, over: &Overrides) -> Overrides {
    Overrides {
        steps: over.steps.or(base.steps),
        h: over.h.or(base.h),
        out: over.out.clone().or_else(|| base.out.clone()),
        checkpoint_every: over.checkpoint_every.or(base.checkpoint_every),
        every: over.every.or(base.every),
    }
}

/// Refuses checkpoints asked by an override of a run that cannot be resumed, as the file's
/// checks do. A `checkpoint_every` the file wrote itself passed those checks already, so the
/// value refused here is the override's, with no caret in the file.
fn refuse_checkpoints(spec: &RunSpec) -> Result<(), Diagnostic> {
    // A sweep checkpoints whole members, whatever they are (as in the file's checks).
    if spec.sweep.is_some() {
        return Ok(());
    }
    let run = checkpoints::RunKind {
        system: &spec.system,
        method: &spec.integrator.method,
    };
    let ck = Checker::new(&spec.source);
    checkpoints::refuse_at(&ck, None, spec.output.checkpoint_every, run)
}

#[cfg(test)]
mod tests {
    use super::*;

    const PENDULUM: &str = "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n\
                            [integrator]\nh = 0.1\nsteps = 10\n";

    fn read(text: &str, overrides: &Overrides) -> Result<RunSpec, Diagnostic> {
        super::super::from_toml_str(text, "p.toml", overrides)
    }

    #[test]
    fn output_overrides_give_what_the_file_read_with_them_gives() {
        let overrides = Overrides {
            out: Some("elsewhere".into()),
            every: Some(3),
            checkpoint_every: Some(5),
            ..Overrides::default()
        };
        let base = read(PENDULUM, &Overrides::default()).unwrap();
        let applied = base.with_overrides(&overrides).unwrap();
        let direct = read(PENDULUM, &overrides).unwrap();
        assert_eq!(applied.output, direct.output);
        assert_eq!(applied.overrides, direct.overrides);
    }

    #[test]
    fn refusals_are_worded_as_the_file_checks_word_them() {
        let base = read(PENDULUM, &Overrides::default()).unwrap();
        for overrides in [
            Overrides {
                every: Some(0),
                ..Overrides::default()
            },
            Overrides {
                checkpoint_every: Some(0),
                ..Overrides::default()
            },
        ] {
            let applied = base.with_overrides(&overrides).unwrap_err();
            let direct = read(PENDULUM, &overrides).unwrap_err();
            assert_eq!(applied.to_string(), direct.to_string());
        }
    }

    #[test]
    fn checkpoints_of_a_run_that_cannot_resume_are_refused_alike() {
        let text = PENDULUM.replace("h = 0.1", "h = 0.1\nmethod = \"exact\"");
        let overrides = Overrides {
            checkpoint_every: Some(2),
            ..Overrides::default()
        };
        let base = read(&text, &Overrides::default()).unwrap();
        let applied = base.with_overrides(&overrides).unwrap_err();
        let direct = read(&text, &overrides).unwrap_err();
        assert_eq!(applied.to_string(), direct.to_string());
    }

    #[test]
    fn grid_overrides_read_the_file_again() {
        let overrides = Overrides {
            steps: Some(4),
            ..Overrides::default()
        };
        let base = read(PENDULUM, &Overrides::default()).unwrap();
        let applied = base.with_overrides(&overrides).unwrap();
        assert_eq!(applied.integrator.grid.steps, 4);
        assert_eq!(applied.overrides.steps, Some(4));
    }
}
