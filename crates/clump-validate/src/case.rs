//! One validation case (a table row), a group of cases with its plots, and
//! the whole suite.

/// One row of the report: a measured quantity against an expected value
/// that comes from outside the code.
#[derive(Debug, Clone)]
pub struct Case {
    /// What is checked.
    pub name: String,
    /// Where the expected value comes from (paper, REFERENCE.md section,
    /// analytic formula).
    pub source: String,
    /// Expected value, formatted with its unit.
    pub expected: String,
    /// Measured value, formatted with its unit.
    pub measured: String,
    /// Tolerance, formatted.
    pub tolerance: String,
    /// Whether the measured value is within the tolerance.
    pub pass: bool,
}

impl Case {
    /// A case on a scalar: passes when `|measured − expected| ≤ rel_tol·|expected|`.
    /// `unit` is appended to both numbers.
    pub fn relative(
        name: impl Into<String>,
        source: impl Into<String>,
        expected: f64,
        measured: f64,
        rel_tol: f64,
        unit: &str,
    ) -> Case {
        let err = rel_err(measured, expected);
        Case {
            name: name.into(),
            source: source.into(),
            expected: format!("{} {unit}", fmt(expected)),
            measured: format!(
                "{} {unit} ({:+.3} %)",
                fmt(measured),
                100.0 * signed_rel(measured, expected)
            ),
            tolerance: format!("±{} %", tidy(100.0 * rel_tol)),
            pass: err <= rel_tol,
        }
    }

    /// A case on a scalar: passes when `|measured − expected| ≤ abs_tol`.
    pub fn absolute(
        name: impl Into<String>,
        source: impl Into<String>,
        expected: f64,
        measured: f64,
        abs_tol: f64,
        unit: &str,
    ) -> Case {
        Case {
            name: name.into(),
            source: source.into(),
            expected: format!("{} {unit}", fmt(expected)),
            measured: format!("{} {unit}", fmt(measured)),
            tolerance: format!("±{} {unit}", tidy(abs_tol)),
            pass: (measured - expected).abs() <= abs_tol && measured.is_finite(),
        }
    }

    /// A case on a scalar that must lie in `[lo, hi]`.
    pub fn range(
        name: impl Into<String>,
        source: impl Into<String>,
        lo: f64,
        hi: f64,
        measured: f64,
        unit: &str,
    ) -> Case {
        Case {
            name: name.into(),
            source: source.into(),
            expected: format!("{} to {} {unit}", fmt(lo), fmt(hi)),
            measured: format!("{} {unit}", fmt(measured)),
            tolerance: "in range".into(),
            pass: measured >= lo && measured <= hi,
        }
    }

    /// A case on a non-negative error that must not exceed `bound`.
    pub fn at_most(
        name: impl Into<String>,
        source: impl Into<String>,
        expected: impl Into<String>,
        measured: f64,
        bound: f64,
    ) -> Case {
        Case {
            name: name.into(),
            source: source.into(),
            expected: expected.into(),
            measured: fmt(measured),
            tolerance: format!("≤ {}", tidy(bound)),
            pass: measured <= bound,
        }
    }

    /// A case whose set-up or run failed before anything could be measured.
    pub fn error(
        name: impl Into<String>,
        source: impl Into<String>,
        why: impl std::fmt::Display,
    ) -> Case {
        Case {
            name: name.into(),
            source: source.into(),
            expected: "—".into(),
            measured: format!("error: {why}"),
            tolerance: "—".into(),
            pass: false,
        }
    }
}

/// A group of cases with its plots (file names relative to the report) and
/// free-text notes.
#[derive(Debug, Clone, Default)]
pub struct Group {
    /// Section title.
    pub name: String,
    /// The rows.
    pub cases: Vec<Case>,
    /// `(file name, caption)` of each PNG written.
    pub plots: Vec<(String, String)>,
    /// Notes (set-up, parameters, observations, plot errors).
    pub notes: Vec<String>,
    /// Wall time of the group, s.
    pub seconds: f64,
}

impl Group {
    /// Adds a plot written by `result` (a failure becomes a note, not a panic).
    pub fn plot(&mut self, file: &str, caption: &str, result: Result<(), String>) {
        match result {
            Ok(()) => self.plots.push((file.to_string(), caption.to_string())),
            Err(e) => self
                .notes
                .push(format!("plot {file} could not be written: {e}")),
        }
    }
}

/// All groups.
#[derive(Debug, Clone, Default)]
pub struct Suite {
    /// Groups in report order.
    pub groups: Vec<Group>,
}

impl Suite {
    /// Number of failed cases.
    pub fn failures(&self) -> usize {
        self.groups
            .iter()
            .flat_map(|g| &g.cases)
            .filter(|c| !c.pass)
            .count()
    }
    /// Number of cases.
    pub fn len(&self) -> usize {
        self.groups.iter().map(|g| g.cases.len()).sum()
    }
    /// True when there are no cases.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Relative error `|a − b| / |b|` (infinite for a non-finite `a`).
pub fn rel_err(a: f64, b: f64) -> f64 {
    if !a.is_finite() {
        return f64::INFINITY;
    }
    signed_rel(a, b).abs()
}

fn signed_rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        a
    } else {
        (a - b) / b.abs()
    }
}

/// Formats a tolerance without trailing zeros: `0.5`, `0.01`, `1e-10`.
pub fn tidy(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-3 {
        let e = x.abs().log10().floor() as i32;
        let m = (x / 10f64.powi(e) * 1e6).round() / 1e6;
        format!("{m}e{e}")
    } else {
        format!("{}", (x * 1e9).round() / 1e9)
    }
}

/// Formats a number with 4 significant digits (scientific outside 1e-3..1e5).
pub fn fmt(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{x:.4e}")
    } else {
        let digits = if a == 0.0 {
            0
        } else {
            (3 - a.log10().floor() as i32).clamp(0, 6) as usize
        };
        format!("{x:.digits$}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cases_pass_and_fail_by_their_tolerance() {
        assert!(Case::relative("a", "s", 2.0, 2.009, 0.005, "m").pass);
        assert!(!Case::relative("a", "s", 2.0, 2.02, 0.005, "m").pass);
        assert!(!Case::relative("a", "s", 2.0, f64::NAN, 0.005, "m").pass);
        assert!(Case::absolute("a", "s", 0.5, 0.505, 0.01, "").pass);
        assert!(!Case::absolute("a", "s", 0.5, f64::NAN, 0.01, "").pass);
        assert!(Case::range("a", "s", 0.58, 0.62, 0.6, "").pass);
        assert!(!Case::range("a", "s", 0.58, 0.62, 0.63, "").pass);
        assert!(!Case::at_most("a", "s", "0", 2e-6, 1e-6).pass);
        assert!(!Case::error("a", "s", "boom").pass);
    }

    #[test]
    fn numbers_format_with_four_significant_digits() {
        assert_eq!(fmt(10.7), "10.70");
        assert_eq!(fmt(0.2127), "0.2127");
        assert_eq!(fmt(1.5e-7), "1.5000e-7");
        assert_eq!(fmt(0.0), "0");
        assert_eq!(tidy(100.0 * 0.005), "0.5");
        assert_eq!(tidy(1e-10), "1e-10");
        assert_eq!(tidy(0.15), "0.15");
    }
}
