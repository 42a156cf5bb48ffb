//! The scenario text, its span-preserving parse (toml_edit), key-path
//! lookups, and the translation of TOML/serde errors into [`Diagnostic`]s.

use super::diag::{did_you_mean, locate, Diagnostic, Severity};
use super::units::{unit_hint, unit_of};
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml_edit::{ImDocument, Item, Table, Value};

/// One step of a key path: a key or an array index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Seg<'a> {
    /// A key.
    K(&'a str),
    /// An index into an array or array of tables.
    I(usize),
}

/// The scenario text with its parse tree.
pub struct Source {
    /// The file as given by the user (for messages).
    pub path: PathBuf,
    /// The text.
    pub text: String,
    doc: Option<ImDocument<String>>,
}

enum Node<'a> {
    Item(&'a Item),
    Table(&'a Table),
    Value(&'a Value),
}

impl<'a> Node<'a> {
    fn span(&self) -> Option<Range<usize>> {
        match self {
            Node::Item(i) => match i {
                Item::Table(t) => t.span(),
                Item::ArrayOfTables(a) => a.span(),
                _ => i.span(),
            },
            Node::Table(t) => t.span(),
            Node::Value(v) => v.span(),
        }
    }

    fn key(&self, k: &str) -> Option<(Option<Range<usize>>, Node<'a>)> {
        let tl: &dyn toml_edit::TableLike = match self {
            Node::Item(i) => i.as_table_like()?,
            Node::Table(t) => *t as &dyn toml_edit::TableLike,
            Node::Value(Value::InlineTable(t)) => t as &dyn toml_edit::TableLike,
            _ => return None,
        };
        let (key, item) = tl.get_key_value(k)?;
        Some((key.span(), Node::Item(item)))
    }

    fn index(&self, i: usize) -> Option<Node<'a>> {
        match self {
            Node::Item(Item::ArrayOfTables(a)) => a.get(i).map(Node::Table),
            Node::Item(Item::Value(Value::Array(a))) | Node::Value(Value::Array(a)) => {
                a.get(i).map(Node::Value)
            }
            _ => None,
        }
    }
}

impl Source {
    /// Wraps `text` read from `path`.
    pub fn new(path: &Path, text: String) -> Self {
        let doc = ImDocument::parse(text.clone()).ok();
        Source {
            path: path.to_path_buf(),
            text,
            doc,
        }
    }

    fn node(&self, path: &[Seg]) -> Option<(Option<Range<usize>>, Node<'_>)> {
        let doc = self.doc.as_ref()?;
        let mut node = Node::Table(doc.as_table());
        let mut key_span = None;
        for s in path {
            match *s {
                Seg::K(k) => {
                    let (ks, n) = node.key(k)?;
                    key_span = ks;
                    node = n;
                }
                Seg::I(i) => {
                    node = node.index(i)?;
                    key_span = None;
                }
            }
        }
        Some((key_span, node))
    }

    /// Span of the value at `path` (or of its key, or of the nearest
    /// existing parent), for pointing at a bad value.
    pub fn value_span(&self, path: &[Seg]) -> Option<Range<usize>> {
        for n in (0..=path.len()).rev() {
            if let Some((ks, node)) = self.node(&path[..n]) {
                if let Some(s) = node.span().filter(|s| s.end > s.start) {
                    // a table's span covers its header; for a value, the value
                    return Some(if n < path.len() {
                        self.header_span(s)
                    } else {
                        s
                    });
                }
                if let Some(s) = ks {
                    return Some(s);
                }
            }
        }
        None
    }

    /// Span of the key at the end of `path` (falls back to the value).
    pub fn key_span(&self, path: &[Seg]) -> Option<Range<usize>> {
        if let Some((Some(ks), _)) = self.node(path) {
            return Some(ks);
        }
        self.value_span(path)
    }

    /// The first line of a span (for tables: the header).
    fn header_span(&self, s: Range<usize>) -> Range<usize> {
        let start = s.start.min(self.text.len());
        let end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |i| start + i);
        start
            ..end
                .min(s.end)
                .max(start + 1)
                .min(self.text.len().max(start))
    }

    /// Whether `path` exists in the file.
    pub fn has(&self, path: &[Seg]) -> bool {
        self.node(path).is_some()
    }

    /// An error at the value of `path`.
    pub fn error_at(&self, path: &[Seg], message: impl Into<String>) -> Diagnostic {
        self.diag_at(Severity::Error, self.value_span(path), message)
    }

    /// An error at the key of `path`.
    pub fn error_at_key(&self, path: &[Seg], message: impl Into<String>) -> Diagnostic {
        self.diag_at(Severity::Error, self.key_span(path), message)
    }

    /// A warning at the value of `path`.
    pub fn warning_at(&self, path: &[Seg], message: impl Into<String>) -> Diagnostic {
        self.diag_at(Severity::Warning, self.value_span(path), message)
    }

    /// A diagnostic at a byte span.
    pub fn diag_at(
        &self,
        severity: Severity,
        span: Option<Range<usize>>,
        message: impl Into<String>,
    ) -> Diagnostic {
        let mut d = Diagnostic::new(severity, &self.path, message);
        d.location = span.map(|s| locate(&self.text, s));
        d
    }

    /// The header (`[[pair]]`, `[simulation]`) of the table that contains byte
    /// `pos`, or `None` at the top level.
    pub fn table_at(&self, pos: usize) -> Option<String> {
        let pos = pos.min(self.text.len());
        let line_start = self.text[..pos].rfind('\n').map_or(0, |i| i + 1);
        let line_end = self.text[pos..]
            .find('\n')
            .map_or(self.text.len(), |i| pos + i);
        let current = self.text[line_start..line_end].trim_start();
        if current.starts_with('[') && !current.contains('=') {
            // the key is (part of) a table header: report the parent table
            let name = current.trim_start_matches('[');
            let name = &name[..name.find(']').unwrap_or(name.len())];
            let parent = name.rsplit_once('.').map(|p| p.0.trim());
            return parent.map(|p| format!("[{p}]"));
        }
        let before = &self.text[..line_start];
        for line in before.lines().rev() {
            let t = line.trim_start();
            if t.starts_with('[') {
                let end = t.rfind(']').map_or(t.len(), |i| i + 1);
                return Some(t[..end].to_string());
            }
        }
        None
    }

    /// The key whose value contains byte `pos` (the text before `=` on that
    /// line or the nearest line above with one).
    pub fn key_at(&self, pos: usize) -> Option<String> {
        let before = &self.text[..pos.min(self.text.len())];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let mut candidates = vec![&before[line_start..]];
        candidates.extend(before[..line_start].lines().rev());
        for line in candidates {
            let t = line.trim_start();
            if t.starts_with('[') && !t.contains('=') {
                return None;
            }
            if let Some(eq) = t.find('=') {
                let k = t[..eq].trim();
                // inline tables: take the last key before '='
                let k = k.rsplit(['{', ',', ' ']).next().unwrap_or(k).trim();
                if !k.is_empty() {
                    return Some(k.trim_matches('"').to_string());
                }
            }
        }
        None
    }

    /// Translates a `toml` deserialisation error.
    pub fn from_toml_error(&self, e: &toml::de::Error) -> Diagnostic {
        let msg = e.message().trim().to_string();
        let span = e.span();
        let pos = span.as_ref().map_or(0, |s| s.start);
        let table = self.table_at(pos);
        let in_table = table
            .as_ref()
            .map_or("at the top level".to_string(), |t| format!("in {t}"));
        // unknown key
        if let Some(rest) = msg.strip_prefix("unknown field `") {
            let (name, tail) = rest.split_once('`').unwrap_or((rest, ""));
            // serde lists the fields of the struct in order: the keys of its
            // table (`keys::Table::KEYS`, declared with it)
            let allowed = backticked(tail);
            let mut d = self.diag_at(
                Severity::Error,
                span.clone(),
                format!("unknown key '{name}' {in_table}"),
            );
            if let Some(s) = did_you_mean(name, allowed.iter().map(|s| s.as_str())) {
                d = d.label(format!("did you mean '{s}'?"));
            } else {
                d = d.label("unknown key");
            }
            if !allowed.is_empty() {
                d = d.note(format!("allowed keys: {}", allowed.join(", ")));
            }
            return d;
        }
        // unknown enum value
        if let Some(rest) = msg.strip_prefix("unknown variant `") {
            let (name, tail) = rest.split_once('`').unwrap_or((rest, ""));
            let allowed = backticked(tail);
            let key = self.key_at(pos).unwrap_or_default();
            let quoted: Vec<String> = allowed.iter().map(|a| format!("\"{a}\"")).collect();
            let mut d = self.diag_at(
                Severity::Error,
                span.clone(),
                format!("invalid value \"{name}\" for '{key}' {in_table}"),
            );
            d = match did_you_mean(name, allowed.iter().map(|s| s.as_str())) {
                Some(s) => d.label(format!("did you mean \"{s}\"?")),
                None => d.label(format!("expected one of {}", quoted.join(", "))),
            };
            return d.note(format!("allowed values: {}", quoted.join(", ")));
        }
        if let Some(rest) = msg.strip_prefix("missing field `") {
            let name = rest.split('`').next().unwrap_or(rest);
            return self.diag_at(
                Severity::Error,
                span.clone().map(|s| self.header_span(s)),
                format!("missing key '{name}' {in_table}"),
            );
        }
        if msg.starts_with("invalid type")
            || msg.starts_with("invalid length")
            || msg.starts_with("invalid value")
        {
            let key = self.key_at(pos).unwrap_or_default();
            let expected = msg.rsplit_once("expected ").map(|x| x.1).unwrap_or("");
            let what = describe_expected(expected, &key);
            let found = msg
                .strip_prefix("invalid type: ")
                .and_then(|r| r.split(", expected").next())
                .map(|f| format!("found {f}"))
                .or_else(|| {
                    msg.strip_prefix("invalid length ")
                        .and_then(|r| r.split(',').next())
                        .map(|n| format!("found {n} elements"))
                })
                .unwrap_or_else(|| "invalid value".to_string());
            let mut d = self.diag_at(
                Severity::Error,
                span.clone(),
                format!("wrong type for '{key}' {in_table}: expected {what}"),
            );
            d = d.label(found);
            let value_text = span
                .as_ref()
                .map(|s| self.text[s.clone()].to_string())
                .unwrap_or_default();
            if let Some(h) = unit_hint(&key, &value_text) {
                d = d.note(h);
            }
            return d;
        }
        // TOML syntax errors and anything else: keep the parser's message
        let first = msg.lines().next().unwrap_or("").to_string();
        let mut d = self.diag_at(
            Severity::Error,
            span.clone(),
            format!("invalid TOML: {first}"),
        );
        for extra in msg.lines().skip(1).filter(|l| !l.trim().is_empty()) {
            d = d.note(extra.trim().to_string());
        }
        d
    }
}

/// The `backticked` words of a serde message tail.
fn backticked(s: &str) -> Vec<String> {
    s.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// "a number in Pa" etc. from serde's "expected f64" and the key.
fn describe_expected(expected: &str, key: &str) -> String {
    let unit = unit_of(key);
    let with_unit = |base: &str| match unit {
        Some(u) if !u.is_empty() => format!("{base} in {u}"),
        _ => base.to_string(),
    };
    let e = expected.trim();
    if e == "f64" || e == "f32" {
        with_unit("a number")
    } else if e.starts_with('u') && e[1..].parse::<u32>().is_ok() || e == "usize" {
        "a non-negative integer".into()
    } else if e.starts_with('i') && e[1..].parse::<u32>().is_ok() {
        "an integer".into()
    } else if e.contains("length 3") {
        with_unit("an array of 3 numbers [x, y, z]")
    } else if e.contains("length 4") {
        if key == "orientation" {
            "a quaternion [w, x, y, z]".into()
        } else {
            "an array of 4 numbers [x, y, z, r] in m".into()
        }
    } else if e == "a boolean" || e == "bool" {
        "true or false".into()
    } else if e == "a string" {
        "a string (in quotes)".into()
    } else if e.starts_with("a sequence") {
        "an array [...]".into()
    } else if e.starts_with("a time step") {
        "a time step in s (a number such as 1e-5) or \"auto\"".into()
    } else if e.starts_with("struct") || e.starts_with("a map") {
        "a table { ... }".into()
    } else if e.starts_with("variant identifier") || e.starts_with("one of") {
        format!("one of {e}")
    } else {
        e.to_string()
    }
}
