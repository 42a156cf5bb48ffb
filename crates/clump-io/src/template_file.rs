//! Reader for LIGGGHTS multisphere template files (`*.multisphere`), as used
//! by `fix particletemplate/multisphere ... spheres file FILE`.
//!
//! Format: one sphere per line, `x y z r` (four numbers, whitespace
//! separated; lengths in the file's unit, m unless scaled by the caller),
//! in the template's *input frame*. `#` starts a comment (whole line or
//! trailing); blank lines are allowed. Every error names the file, the
//! 1-based line number and what was expected; arbitrary bytes never panic.

use std::path::{Path, PathBuf};

use clump_core::shape::Sphere;
use glam::DVec3;

/// Why a template file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TemplateFileError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read template file: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not valid UTF-8 text.
    #[error(
        "{path}:{line}: not valid UTF-8 text (a template file holds lines of `x y z r` numbers)"
    )]
    NotUtf8 {
        /// The file.
        path: PathBuf,
        /// 1-based line of the first invalid byte.
        line: usize,
    },
    /// A line is malformed.
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What was wrong and what is allowed.
        message: String,
    },
    /// The file holds no sphere.
    #[error("{path}: no sphere found (expected lines of `x y z r`)")]
    Empty {
        /// The file.
        path: PathBuf,
    },
}

impl TemplateFileError {
    /// The 1-based line number the error refers to, if any.
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::NotUtf8 { line, .. } | Self::Syntax { line, .. } => Some(*line),
            _ => None,
        }
    }
}

/// Reads and parses a template file: spheres (centre and radius in the file's
/// length unit, input frame), in file order.
pub fn read_template_file(path: &Path) -> Result<Vec<Sphere>, TemplateFileError> {
    let bytes = std::fs::read(path).map_err(|source| TemplateFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_template_bytes(&bytes, path)
}

/// Parses the bytes of a template file; `path` is used in error messages only.
pub fn parse_template_bytes(bytes: &[u8], path: &Path) -> Result<Vec<Sphere>, TemplateFileError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => parse_template_str(text, path),
        Err(e) => {
            let line = 1 + bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            Err(TemplateFileError::NotUtf8 {
                path: path.to_path_buf(),
                line,
            })
        }
    }
}

/// Parses the text of a template file; `path` is used in error messages only.
pub fn parse_template_str(text: &str, path: &Path) -> Result<Vec<Sphere>, TemplateFileError> {
    let syntax = |line: usize, message: String| TemplateFileError::Syntax {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut spheres = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = match raw.find('#') {
            Some(k) => &raw[..k],
            None => raw,
        };
        let fields: Vec<&str> = content.split_whitespace().collect();
        if fields.is_empty() {
            continue;
        }
        if fields.len() != 4 {
            return Err(syntax(
                line,
                format!(
                    "expected 4 numbers x y z r, found {} field{}",
                    fields.len(),
                    if fields.len() == 1 { "" } else { "s" }
                ),
            ));
        }
        let mut v = [0.0f64; 4];
        for (k, (f, name)) in fields.iter().zip(["x", "y", "z", "r"]).enumerate() {
            let x: f64 = f.parse().map_err(|_| {
                syntax(
                    line,
                    format!(
                        "{name} is not a number: {:?} (expected 4 numbers x y z r)",
                        truncate(f)
                    ),
                )
            })?;
            if !x.is_finite() {
                return Err(syntax(line, format!("{name} must be finite, found {f}")));
            }
            v[k] = x;
        }
        if v[3] <= 0.0 {
            return Err(syntax(
                line,
                format!("radius must be > 0, found {}", fields[3]),
            ));
        }
        spheres.push(Sphere::new(DVec3::new(v[0], v[1], v[2]), v[3]));
    }
    if spheres.is_empty() {
        return Err(TemplateFileError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(spheres)
}

/// At most 40 characters of a field, for messages.
fn truncate(s: &str) -> String {
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> &'static Path {
        Path::new("t.multisphere")
    }

    #[test]
    fn parses_comments_and_blanks() {
        let text = "# header\n\n 1 2 3 0.5  # trailing\n\t-1e-3 0 +4 2\r\n";
        let s = parse_template_str(text, p()).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s[0], Sphere::new(DVec3::new(1.0, 2.0, 3.0), 0.5));
        assert_eq!(s[1], Sphere::new(DVec3::new(-1e-3, 0.0, 4.0), 2.0));
    }

    #[test]
    fn errors_name_file_and_line() {
        let e = parse_template_str("1 2 3 1\n1 2 3\n", p()).unwrap_err();
        assert_eq!(e.line(), Some(2));
        let m = e.to_string();
        assert!(
            m.contains("t.multisphere:2") && m.contains("expected 4 numbers x y z r, found 3"),
            "{m}"
        );
        let m = parse_template_str("1 2 3 0\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains(":1:") && m.contains("radius must be > 0"), "{m}");
        let m = parse_template_str("1 2 3 -1\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains("radius must be > 0"), "{m}");
        let m = parse_template_str("\n\n1 a 3 1\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains(":3:") && m.contains("y is not a number"), "{m}");
        let m = parse_template_str("1 nan 3 1\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains("y must be finite"), "{m}");
        let m = parse_template_str("1 2 3 inf\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains("r must be finite"), "{m}");
        let m = parse_template_str("1 2 3 4 5\n", p())
            .unwrap_err()
            .to_string();
        assert!(m.contains("found 5"), "{m}");
        let e = parse_template_str("# nothing\n\n", p()).unwrap_err();
        assert!(matches!(e, TemplateFileError::Empty { .. }));
        let e = parse_template_bytes(b"1 2 3 1\n\xff\xfe 1 2\n", p()).unwrap_err();
        assert_eq!(e.line(), Some(2));
        assert!(e.to_string().contains("UTF-8"));
        let e = read_template_file(Path::new("/nonexistent/x.multisphere")).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/x.multisphere"));
    }

    proptest::proptest! {
        #[test]
        fn never_panics(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..200)) {
            let _ = parse_template_bytes(&bytes, p());
        }
        #[test]
        fn never_panics_on_text(text in "[0-9eE+. \\-#a\\n\\t]{0,120}") {
            let _ = parse_template_str(&text, p());
        }
    }
}
