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
