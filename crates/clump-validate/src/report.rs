//! The Markdown report: one table per group, its plots and notes.

use crate::case::Suite;
use std::fmt::Write as _;
use std::path::Path;

/// Escapes a table cell (pipes and newlines).
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// Renders the report as Markdown. `header` lines (command, wall time,
/// machine) go under the title.
pub fn markdown(suite: &Suite, header: &[String]) -> String {
    let mut s = String::new();
    let fails = suite.failures();
    let _ = writeln!(s, "# Clump validation report\n");
    for h in header {
        let _ = writeln!(s, "{h}  ");
    }
    let _ = writeln!(
        s,
        "\n**{} cases, {} passed, {} failed.**\n",
        suite.len(),
        suite.len() - fails,
        fails
    );
    let _ = writeln!(
        s,
        "Every expected value comes from outside the code: a closed-form solution, a published benchmark or `validation/REFERENCE.md` (section given in *source*).\n"
    );
    for g in &suite.groups {
        let _ = writeln!(s, "## {}\n", g.name);
        let _ = writeln!(s, "_{:.1} s_\n", g.seconds);
        if !g.cases.is_empty() {
            let _ = writeln!(
                s,
                "| case | source | expected | measured | tolerance | result |"
            );
            let _ = writeln!(s, "|---|---|---|---|---|---|");
            for c in &g.cases {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {} |",
                    cell(&c.name),
                    cell(&c.source),
                    cell(&c.expected),
                    cell(&c.measured),
                    cell(&c.tolerance),
                    if c.pass { "PASS" } else { "**FAIL**" }
                );
            }
            s.push('\n');
        }
        for n in &g.notes {
            let _ = writeln!(s, "- {n}");
        }
        if !g.notes.is_empty() {
            s.push('\n');
        }
        for (file, caption) in &g.plots {
            let _ = writeln!(s, "![{caption}]({file})\n\n*{caption}*\n");
        }
    }
    s
}

/// Writes `report.md` into `dir`.
pub fn write(dir: &Path, suite: &Suite, header: &[String]) -> std::io::Result<()> {
    std::fs::write(dir.join("report.md"), markdown(suite, header))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::{Case, Group};

    #[test]
    fn report_has_one_row_per_case_and_marks_failures() {
        let mut g = Group::default();
        g.name = "g".into();
        g.cases
            .push(Case::absolute("ok | pipe", "s", 1.0, 1.0, 0.1, ""));
        g.cases.push(Case::absolute("bad", "s", 1.0, 2.0, 0.1, ""));
        g.plots.push(("p.png".into(), "caption".into()));
        let s = Suite { groups: vec![g] };
        let md = markdown(&s, &["h".into()]);
        assert!(md.contains("**2 cases, 1 passed, 1 failed.**"));
        assert!(md.contains("ok \\| pipe"));
        assert!(md.contains("**FAIL**"));
        assert!(md.contains("![caption](p.png)"));
    }
}
