//! Diagnostics with file, line, column and a source excerpt, in the style of
//! `rustc`/`miette`:
//!
//! ```text
//! error: unknown key 'restitutoin' in [[pair]]
//!   --> scenario.toml:12:1
//!    |
//! 12 | restitutoin = 0.5
//!    | ^^^^^^^^^^^ did you mean 'restitution'?
//! ```

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// The scenario cannot be run.
    Error,
    /// The scenario runs, but something looks wrong.
    Warning,
}

/// A position in the scenario text (1-based line and column, in characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (characters).
    pub column: usize,
    /// The text of the line.
    pub line_text: String,
    /// Number of characters to underline (≥ 1).
    pub width: usize,
}

/// One error or warning about a scenario file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// The headline, e.g. `unknown key 'restitutoin' in [[pair]]`.
    pub message: String,
    /// The file the location refers to (as given by the user).
    pub file: PathBuf,
    /// Where in the file, if known.
    pub location: Option<Location>,
    /// Text printed after the underline (e.g. `did you mean 'restitution'?`).
    pub label: Option<String>,
    /// Extra `= help:` / `= note:` lines.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// A diagnostic without a location.
    pub fn new(severity: Severity, file: &Path, message: impl Into<String>) -> Self {
        Diagnostic {
            severity,
            message: message.into(),
            file: file.to_path_buf(),
            location: None,
            label: None,
            notes: Vec::new(),
        }
    }

    /// Adds a note line.
    pub fn note(mut self, n: impl Into<String>) -> Self {
        self.notes.push(n.into());
        self
    }

    /// Sets the label after the underline.
    pub fn label(mut self, l: impl Into<String>) -> Self {
        self.label = Some(l.into());
        self
    }

    /// The 1-based line, if known.
    pub fn line(&self) -> Option<usize> {
        self.location.as_ref().map(|l| l.line)
    }
}

/// Location of the byte range `span` in `text`.
pub fn locate(text: &str, span: Range<usize>) -> Location {
    let start = span.start.min(text.len());
    let start = (0..=start)
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line = text[..line_start].matches('\n').count() + 1;
    let column = text[line_start..start].chars().count() + 1;
    let line_text = text[line_start..line_end]
        .trim_end_matches('\r')
        .to_string();
    let end = span.end.min(line_end).max(start);
    let end = (end..=text.len())
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(text.len());
    let width = text[start..end].chars().count().max(1);
    Location {
        line,
        column,
        line_text,
        width,
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sev = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        writeln!(f, "{sev}: {}", self.message)?;
        let file = self.file.display();
        match &self.location {
            Some(loc) => {
                let num = loc.line.to_string();
                let pad = " ".repeat(num.len());
                writeln!(f, "{pad}--> {file}:{}:{}", loc.line, loc.column)?;
                writeln!(f, "{pad} |")?;
                let (text, column) = excerpt(&loc.line_text, loc.column);
                writeln!(f, "{num} | {text}")?;
                let lead: String = text
                    .chars()
                    .take(column - 1)
                    .map(|c| if c == '\t' { '\t' } else { ' ' })
                    .collect();
                let room = text.chars().count().saturating_sub(column - 1).max(1);
                let carets = "^".repeat(loc.width.min(room));
                match &self.label {
                    Some(l) => writeln!(f, "{pad} | {lead}{carets} {l}")?,
                    None => writeln!(f, "{pad} | {lead}{carets}")?,
                }
                for n in &self.notes {
                    writeln!(f, "{pad} = {n}")?;
                }
            }
            None => {
                writeln!(f, " --> {file}")?;
                if let Some(l) = &self.label {
                    writeln!(f, "  = {l}")?;
                }
                for n in &self.notes {
                    writeln!(f, "  = {n}")?;
                }
            }
        }
        Ok(())
    }
}

/// A scenario that cannot be used: bad input (exit status 2).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScenarioError {
    /// The error (and possibly more after it).
    pub diagnostics: Vec<Diagnostic>,
}

impl ScenarioError {
    /// A single-diagnostic error.
    pub fn one(d: Diagnostic) -> Self {
        ScenarioError {
            diagnostics: vec![d],
        }
    }

    /// The first diagnostic.
    pub fn first(&self) -> &Diagnostic {
        &self.diagnostics[0]
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, d) in self.diagnostics.iter().enumerate() {
            if k > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for ScenarioError {}

/// `x` as Rust prints it, or in exponent form when that is long (Rust
/// prints 1e-300 with 300 digits).
pub fn num(x: f64) -> String {
    let s = format!("{x}");
    if s.len() > 24 {
        format!("{x:e}")
    } else {
        s
    }
}

/// `s`, or its start and its length when it is longer than 48 characters
/// (a line or token of megabytes must not be echoed whole).
pub fn shorten(s: &str) -> String {
    const MAX: usize = 48;
    let n = s.chars().count();
    if n <= MAX {
        s.to_string()
    } else {
        let head: String = s.chars().take(32).collect();
        format!("{head}… ({n} characters)")
    }
}

/// The part of `line` shown in an excerpt: at most [`EXCERPT`] characters
/// around the 1-based `column`, with `…` where it was cut; returns the text
/// and the column within it.
fn excerpt(line: &str, column: usize) -> (String, usize) {
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= EXCERPT {
        return (line.to_string(), column);
    }
    let start = column
        .saturating_sub(1 + EXCERPT / 2)
        .min(chars.len() - EXCERPT);
    let end = start + EXCERPT;
    let mut t = String::new();
    if start > 0 {
        t.push('…');
    }
    t.extend(&chars[start..end]);
    if end < chars.len() {
        t.push('…');
    }
    (t, column - start + usize::from(start > 0))
}

/// Longest source line shown whole in an excerpt, characters.
const EXCERPT: usize = 120;

/// 1-based line and column (in characters) of the first invalid byte that
/// `e` reports in `bytes`.
pub fn utf8_position(bytes: &[u8], e: &std::str::Utf8Error) -> (usize, usize) {
    let good = &bytes[..e.valid_up_to()];
    let line_start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
    let column = 1 + std::str::from_utf8(&good[line_start..]).map_or(0, |s| s.chars().count());
    (line, column)
}

#[allow(clippy::unnecessary_map_or)] // `is_none_or` needs Rust 1.82; the MSRV is 1.80
/// The closest of `candidates` to `word` (Jaro–Winkler ≥ 0.8 or a small edit
/// distance), for "did you mean".
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let mut best: Option<(&str, f64)> = None;
    for c in candidates {
        let jw = strsim::jaro_winkler(word, c);
        let lev = strsim::levenshtein(word, c);
        let ok = jw >= 0.8 || lev <= 2.max(word.len() / 4);
        if ok && best.map_or(true, |b| jw > b.1) {
            best = Some((c, jw));
        }
    }
    best.map(|b| b.0)
}

/// `'a', 'b' and 'c'` for messages.
pub fn list(items: &[String]) -> String {
    let q: Vec<String> = items.iter().map(|s| format!("'{s}'")).collect();
    match q.len() {
        0 => "none".into(),
        1 => q[0].clone(),
        n => format!("{} and {}", q[..n - 1].join(", "), q[n - 1]),
    }
}
