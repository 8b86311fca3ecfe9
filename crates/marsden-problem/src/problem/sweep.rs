//! `[sweep]`: an ensemble of runs of one problem file, one member per value of a parameter or
//! of an initial value, or per point of a grid of several.
//!
//! ```toml
//! [sweep]
//! parameter = "l"                                  # a scalar parameter (or a builtin's default)
//! values = [0.5, 1.0, 2.0]                         # the members' values, in order
//! # initial = "q[0]"                               # instead of `parameter`: q[i], v[i] or p[i]
//! # range = { start = 0.1, stop = 1.0, count = 10 } # instead of `values`: evenly spaced, both ends
//!
//! # [sweep.and]                                    # optional: a second axis (and `[sweep.and.and]` …)
//! # initial = "q[0]"                               # members: every (l, q[0]) pair, q[0] fastest
//! # values = [0.1, 0.2]
//! ```
//!
//! Member `k` is the problem file with the swept values replaced by member `k`'s
//! ([`SweepSpec::values_of`]), validated like any file (`member`): a value the problem cannot
//! take fails that member only.

use std::ops::Range;

use toml::Spanned;

use super::check::Checker;
use super::raw::{Ordered, RawParameter, RawProblem, RawRange, RawSweep};
use super::spec::{InitialData, InitialSpec, SystemSpec};
use crate::error::Diagnostic;
use marsden_expr::closest;

/// Which initial vector a swept initial value belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InitialVector {
    /// Positions `q`.
    Q,
    /// Velocities `v`.
    V,
    /// Momenta `p`.
    P,
}

impl InitialVector {
    /// `"q"`, `"v"` or `"p"`.
    pub fn name(self) -> &'static str {
        match self {
            InitialVector::Q => "q",
            InitialVector::V => "v",
            InitialVector::P => "p",
        }
    }
}

/// What a sweep varies.
#[derive(Debug, Clone, PartialEq)]
pub enum SweepTarget {
    /// A scalar parameter, by name.
    Parameter(String),
    /// Component `index` of an initial vector.
    Initial(InitialVector, usize),
}

impl SweepTarget {
    /// The column name of the swept value: the parameter's name or `q[0]`.
    pub fn label(&self) -> String {
        match self {
            SweepTarget::Parameter(name) => name.clone(),
            SweepTarget::Initial(vector, i) => format!("{}[{i}]", vector.name()),
        }
    }
}

/// One axis of a sweep: what is varied and over which values.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepAxis {
    /// What is varied.
    pub target: SweepTarget,
    /// The values along this axis, in order (at least one, all finite).
    pub values: AxisValues,
    /// Where the target is written.
    pub span: Range<usize>,
}

/// The values along an axis: a list, or an evenly spaced range computed on demand (a range of
/// [`MAX_MEMBERS`] values holds three numbers, not 80 MB).
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// `values = [...]`, or a range of one value.
    List(Vec<f64>),
    /// `range = { start, stop, count }`, `count ≥ 2`, `start < stop`: `start + k·step` with
    /// `step = (stop − start)/(count − 1)`, the last value `stop` itself.
    Range {
        /// The first value.
        start: f64,
        /// The last value.
        stop: f64,
        /// How many values.
        count: usize,
    },
}

impl AxisValues {
    /// How many values.
    pub fn len(&self) -> usize {
        match self {
            Self::List(values) => values.len(),
            Self::Range { count, .. } => *count,
        }
    }

    /// Whether there are none (never, for a validated axis).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Value `k` (`k < len()`).
    pub fn get(&self, k: usize) -> f64 {
        match *self {
            Self::List(ref values) => values[k],
            Self::Range { stop, count, .. } if k + 1 == count => stop,
            Self::Range { start, stop, count } => {
                let step = (stop - start) / (count - 1) as f64;
                start + k as f64 * step
            }
        }
    }
}

/// A validated `[sweep]`: one axis, or several (`[sweep.and]`) whose members are every
/// combination of their values, the last axis varying fastest.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSpec {
    /// The axes, in the file's order (at least one).
    pub axes: Vec<SweepAxis>,
}

impl SweepSpec {
    /// Number of members: the product of the axes' lengths.
    pub fn count(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// The swept values of member `k` (`k < count()`), one per axis: the digits of `k` in the
    /// mixed radix of the axes' lengths, the last axis the fastest.
    pub fn values_of(&self, k: usize) -> Vec<f64> {
        let mut rest = k;
        let mut values = vec![0.0; self.axes.len()];
        for (slot, axis) in values.iter_mut().zip(&self.axes).rev() {
            let n = axis.values.len();
            *slot = axis.values.get(rest % n);
            rest /= n;
        }
        values
    }

    /// The column names of the swept values (`l`, `q[0]`), one per axis.
    pub fn labels(&self) -> Vec<String> {
        self.axes.iter().map(|a| a.target.label()).collect()
    }

    /// The swept values' names joined for a title: `l` or `l × q[0]`.
    pub fn label(&self) -> String {
        self.labels().join(" × ")
    }
}

/// Validates `[sweep]` (and its `[sweep.and]` axes) against the `system` and `initial` state
/// of the file (`from_file`: the initial state is read from `[initial] file`).
///
/// # Errors
/// An unknown parameter (the valid ones are listed), an initial value the file does not give,
/// an empty or reversed range, a list with no or non-finite values, a value swept twice, more
/// than [`MAX_MEMBERS`] members in all.
pub fn sweep(
    ck: &Checker<'_>,
    raw: Option<&Spanned<RawSweep>>,
    system: &SystemSpec,
    initial: &InitialSpec,
    from_file: bool,
) -> Result<Option<SweepSpec>, Diagnostic> {
    let mut axes: Vec<SweepAxis> = Vec::new();
    let mut next = raw;
    let mut members: usize = 1;
    while let Some(raw) = next {
        let axis = axis(ck, raw, system, initial, from_file)?;
        if axes.iter().any(|a| a.target == axis.target) {
            let msg = format!("`{}` is swept twice", axis.target.label());
            return Err(ck
                .error(Some(axis.span.clone()), msg)
                .help("each axis of a grid varies a different value"));
        }
        members = members
            .checked_mul(axis.values.len())
            .filter(|&m| m <= MAX_MEMBERS)
            .ok_or_else(|| {
                ck.error(
                    Some(raw.span()),
                    format!("the grid has more than the limit of {MAX_MEMBERS:.0e} sweep members"),
                )
            })?;
        axes.push(axis);
        next = raw.get_ref().and.as_deref();
    }
    Ok((!axes.is_empty()).then_some(SweepSpec { axes }))
}

/// One axis: its target and values.
fn axis(
    ck: &Checker<'_>,
    raw: &Spanned<RawSweep>,
    system: &SystemSpec,
    initial: &InitialSpec,
    from_file: bool,
) -> Result<SweepAxis, Diagnostic> {
    let table = raw.get_ref();
    let (target, span) = match (&table.parameter, &table.initial) {
        (Some(_), Some(i)) => {
            let msg = "give either `parameter` or `initial` in [sweep], not both";
            return Err(ck.error(Some(i.span()), msg));
        }
        (None, None) => {
            return Err(ck
                .error(Some(raw.span()), "[sweep] needs what to vary")
                .help("`parameter = \"l\"` or `initial = \"q[0]\"`"));
        }
        (Some(name), None) => (parameter(ck, name, system)?, name.span()),
        (None, Some(text)) => (initial_value(ck, text, initial, from_file)?, text.span()),
    };
    let values = values(ck, raw)?;
    Ok(SweepAxis {
        target,
        values,
        span,
    })
}

fn parameter(
    ck: &Checker<'_>,
    name: &Spanned<String>,
    system: &SystemSpec,
) -> Result<SweepTarget, Diagnostic> {
    let valid: Vec<&str> = system.parameters.iter().map(|(n, _)| n.as_str()).collect();
    if valid.contains(&name.get_ref().as_str()) {
        return Ok(SweepTarget::Parameter(name.get_ref().clone()));
    }
    let listed = if valid.is_empty() {
        "the system has no scalar parameters".to_owned()
    } else {
        format!("parameters: {}", valid.join(", "))
    };
    Err(ck
        .error(
            Some(name.span()),
            format!("cannot sweep unknown parameter `{}`", name.get_ref()),
        )
        .suggest(closest(name.get_ref(), valid.iter().copied()))
        .note(listed))
}

fn initial_value(
    ck: &Checker<'_>,
    text: &Spanned<String>,
    initial: &InitialSpec,
    from_file: bool,
) -> Result<SweepTarget, Diagnostic> {
    let n = initial.q.len();
    let given = match initial.data {
        InitialData::Velocity(_) => InitialVector::V,
        InitialData::Momentum(_) => InitialVector::P,
    };
    let valid = format!(
        "q[0] … q[{}] or {}[0] … {}[{}]",
        n - 1,
        given.name(),
        given.name(),
        n - 1
    );
    let bad = |why: String| {
        ck.error(Some(text.span()), why)
            .note(format!("initial values of this file: {valid}"))
    };
    if from_file {
        return Err(ck
            .error(
                Some(text.span()),
                "cannot sweep an initial value given by `[initial] file`",
            )
            .help("sweep a parameter instead, or write the initial state as `q` and `v`"));
    }
    let Some((vector, index)) = parse_initial(text.get_ref()) else {
        return Err(bad(format!(
            "`{}` is not an initial value: write `q[i]`, `v[i]` or `p[i]`",
            text.get_ref()
        )));
    };
    if vector != InitialVector::Q && vector != given {
        return Err(bad(format!(
            "cannot sweep `{}`: the file gives the initial {} `{}`, not `{}`",
            text.get_ref(),
            if given == InitialVector::V {
                "velocities"
            } else {
                "momenta"
            },
            given.name(),
            vector.name()
        )));
    }
    if index >= n {
        return Err(bad(format!(
            "`{}` is out of range: the system has {n} coordinate{}",
            text.get_ref(),
            super::check::plural(n)
        )));
    }
    Ok(SweepTarget::Initial(vector, index))
}

/// `q[3]` → `(Q, 3)`.
fn parse_initial(text: &str) -> Option<(InitialVector, usize)> {
    let (name, rest) = text.trim().split_once('[')?;
    let index = rest.strip_suffix(']')?.trim().parse().ok()?;
    let vector = match name.trim() {
        "q" => InitialVector::Q,
        "v" => InitialVector::V,
        "p" => InitialVector::P,
        _ => return None,
    };
    Some((vector, index))
}

fn values(ck: &Checker<'_>, raw: &Spanned<RawSweep>) -> Result<AxisValues, Diagnostic> {
    let table = raw.get_ref();
    match (&table.values, &table.range) {
        (Some(_), Some(range)) => Err(ck.error(
            Some(range.span()),
            "give either `values` or `range` in [sweep], not both",
        )),
        (None, None) => Err(ck
            .error(Some(raw.span()), "[sweep] needs the values to run")
            .help("`values = [0.5, 1.0]` or `range = { start = 0.1, stop = 1.0, count = 10 }`")),
        (Some(list), None) => {
            if list.get_ref().is_empty() {
                return Err(ck.error(Some(list.span()), "`values` is empty: nothing to sweep"));
            }
            let each = list.get_ref().iter().enumerate();
            each.map(|(i, v)| ck.finite(&format!("sweep.values[{i}]"), v))
                .collect::<Result<Vec<f64>, _>>()
                .map(AxisValues::List)
        }
        (None, Some(range)) => range_values(ck, range),
    }
}

/// Most members a sweep may have (checked before their values are allocated).
pub const MAX_MEMBERS: usize = 10_000_000;

/// `count` values from `start` to `stop`, both included (`count = 1`: `start` alone).
fn range_values(ck: &Checker<'_>, raw: &Spanned<RawRange>) -> Result<AxisValues, Diagnostic> {
    let r = raw.get_ref();
    let missing = |key: &str| {
        ck.error(Some(raw.span()), format!("`range` needs `{key}`"))
            .help("`range = { start = 0.1, stop = 1.0, count = 10 }`")
    };
    let start = ck.finite(
        "range.start",
        r.start.as_ref().ok_or_else(|| missing("start"))?,
    )?;
    let stop = ck.finite(
        "range.stop",
        r.stop.as_ref().ok_or_else(|| missing("stop"))?,
    )?;
    let count_value = r.count.as_ref().ok_or_else(|| missing("count"))?;
    let count = usize::try_from(*count_value.get_ref()).unwrap_or(0);
    if count == 0 {
        return Err(ck.error(
            Some(count_value.span()),
            format!(
                "the range is empty: count = {}, it must be at least 1",
                count_value.get_ref()
            ),
        ));
    }
    if count > MAX_MEMBERS {
        return Err(ck.error(
            Some(count_value.span()),
            format!("count = {count} is more than the limit of {MAX_MEMBERS:.0e} sweep members"),
        ));
    }
    if start > stop || (start == stop && count > 1) {
        return Err(ck
            .error(
                Some(raw.span()),
                format!("the range is empty: start = {start} must be below stop = {stop}"),
            )
            .help(
                "the values run upwards from `start` to `stop`; `count = 1` runs `start` alone",
            ));
    }
    if count == 1 {
        return Ok(AxisValues::List(vec![start]));
    }
    Ok(AxisValues::Range { start, stop, count })
}

/// Writes member `k`'s value of every axis into the raw file at the swept places.
pub fn apply_member(raw: &mut RawProblem, sweep: &SweepSpec, k: usize) {
    for (axis, value) in sweep.axes.iter().zip(sweep.values_of(k)) {
        apply(raw, axis, value);
    }
}

/// Writes `value` into the raw file at the swept place (the span of the `[sweep]` target when
/// the value was not written, e.g. a builtin's default parameter).
fn apply(raw: &mut RawProblem, axis: &SweepAxis, value: f64) {
    let span = axis.span.clone();
    match &axis.target {
        SweepTarget::Parameter(name) => {
            let Some(system) = raw.system.as_mut() else {
                return;
            };
            let table = system
                .get_mut()
                .parameters
                .get_or_insert_with(|| Spanned::new(span.clone(), Ordered(Vec::new())));
            let entries = &mut table.get_mut().0;
            let number = |at: Range<usize>| Spanned::new(at, RawParameter::Number(value));
            match entries.iter_mut().find(|(n, _)| n == name) {
                Some((_, written)) => *written = number(written.span()),
                None => entries.push((name.clone(), number(span))),
            }
        }
        SweepTarget::Initial(vector, index) => {
            let Some(initial) = raw.initial.as_mut() else {
                return;
            };
            let table = initial.get_mut();
            let list = match vector {
                InitialVector::Q => table.q.as_mut(),
                InitialVector::V => table.v.as_mut(),
                InitialVector::P => table.p.as_mut(),
            };
            if let Some(slot) = list.and_then(|l| l.get_mut().get_mut(*index)) {
                *slot = Spanned::new(slot.span(), value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::AxisValues;

    /// The values a range had when they were stored: `start + k·step` with the step computed
    /// once, the last replaced by `stop`.
    fn stored(start: f64, stop: f64, count: usize) -> Vec<f64> {
        let step = (stop - start) / (count - 1) as f64;
        let mut values: Vec<f64> = (0..count).map(|k| start + k as f64 * step).collect();
        values[count - 1] = stop;
        values
    }

    #[test]
    fn range_values_on_demand_are_the_stored_values_bit_for_bit() {
        for (start, stop, count) in [(0.1, 3.0, 30), (-1.0, 1e-3, 7), (0.0, 1.0, 2)] {
            let range = AxisValues::Range { start, stop, count };
            let on_demand: Vec<f64> = (0..range.len()).map(|k| range.get(k)).collect();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&on_demand), bits(&stored(start, stop, count)));
        }
    }

    #[test]
    fn a_range_of_ten_million_values_ends_at_stop() {
        let range = AxisValues::Range {
            start: 0.1,
            stop: 3.0,
            count: 10_000_000,
        };
        assert_eq!(range.len(), 10_000_000);
        assert_eq!(range.get(0), 0.1);
        assert_eq!(range.get(9_999_999), 3.0);
        assert!((range.get(5_000_000) - (0.1 + 2.9 * 5e6 / 9_999_999.0)).abs() < 1e-12);
    }
}
