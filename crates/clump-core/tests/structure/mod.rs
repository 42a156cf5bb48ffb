//! A reader of a crate's sources as text, for the structure tests: which
//! file imports which (an edge per path that names an item of another file),
//! and how long each function is. Not a Rust parser: comments, strings and
//! `#[cfg(test)]` modules are cut, then paths are read from `use` trees and
//! from the code.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file below `dir`.
pub fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The source with comments removed and string and char literals emptied
/// (line structure kept).
pub fn strip(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied().unwrap_or('\0');
        if c == '/' && next == '/' {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == '*' {
            i += 2;
            while i + 1 < b.len() && !(b[i] == '*' && b[i + 1] == '/') {
                if b[i] == '\n' {
                    out.push('\n');
                }
                i += 1;
            }
            i += 2;
        } else if c == 'r' && (next == '"' || next == '#') && !prev_ident(&b, i) {
            // raw string r"..." or r#"..."#
            let mut j = i + 1;
            let mut hashes = 0;
            while j < b.len() && b[j] == '#' {
                hashes += 1;
                j += 1;
            }
            if j < b.len() && b[j] == '"' {
                j += 1;
                loop {
                    if j >= b.len() {
                        break;
                    }
                    if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                        j += 1 + hashes;
                        break;
                    }
                    if b[j] == '\n' {
                        out.push('\n');
                    }
                    j += 1;
                }
                out.push_str("\"\"");
                i = j;
            } else {
                out.push(c);
                i += 1;
            }
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                if i < b.len() && b[i] == '\n' {
                    out.push('\n');
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' && (b.get(i + 2) == Some(&'\'') || next == '\\') {
            // a char literal ('x' or an escape); else a lifetime
            i += 1;
            while i < b.len() && b[i] != '\'' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn prev_ident(b: &[char], i: usize) -> bool {
    i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')
}

/// The code without its `#[cfg(test)]` items (the brace block after the
/// attribute).
pub fn without_tests(code: &str) -> String {
    let mut out = String::new();
    let mut rest = code;
    while let Some(k) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..k]);
        let after = &rest[k..];
        let Some(open) = after.find(['{', ';']) else {
            rest = "";
            break;
        };
        if after.as_bytes()[open] == b';' {
            rest = &after[open + 1..];
            continue;
        }
        let mut depth = 0;
        let mut end = after.len();
        for (j, ch) in after[open..].char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + j + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        // keep the line count
        out.extend(after[..end].chars().filter(|&c| c == '\n'));
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// One source file of a crate.
pub struct File {
    pub path: PathBuf,
    /// Its module path from the crate root (`[]` for lib.rs / main.rs).
    pub module: Vec<String>,
    /// Its code: comments, literals and test modules cut.
    pub code: String,
    /// Whether the file is a module folder's `mod.rs` (or the crate root).
    pub is_dir_module: bool,
}

/// The files of the crate whose sources are in `src`.
pub fn crate_files(src: &Path) -> Vec<File> {
    let mut paths = Vec::new();
    sources(src, &mut paths);
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let rel = p.strip_prefix(src).unwrap();
            let mut module: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            let last = module.pop().unwrap();
            let stem = last.trim_end_matches(".rs").to_string();
            let root = module.is_empty() && (stem == "lib" || stem == "main");
            let is_dir_module = stem == "mod" || root;
            if !is_dir_module {
                module.push(stem);
            }
            let text = std::fs::read_to_string(&p).unwrap();
            File {
                path: p,
                module,
                code: without_tests(&strip(&text)),
                is_dir_module,
            }
        })
        .collect()
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The paths of a `use` tree (`a::{b, c::{d, e}}` → `a::b`, `a::c::d`,
/// `a::c::e`), each as segments.
fn use_paths(tree: &str) -> Vec<Vec<String>> {
    fn expand(prefix: &[String], s: &str, out: &mut Vec<Vec<String>>) {
        let s = s.trim();
        if let Some(open) = s.find('{') {
            let head: Vec<String> = s[..open]
                .split("::")
                .map(str::trim)
                .filter(|x| !x.is_empty())
                .map(String::from)
                .collect();
            let mut p = prefix.to_vec();
            p.extend(head);
            let inner = &s[open + 1..s.rfind('}').unwrap_or(s.len())];
            // split on top-level commas
            let mut depth = 0;
            let mut start = 0;
            for (j, ch) in inner.char_indices() {
                match ch {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        expand(&p, &inner[start..j], out);
                        start = j + 1;
                    }
                    _ => {}
                }
            }
            expand(&p, &inner[start..], out);
        } else {
            let s = s.split(" as ").next().unwrap().trim();
            if s.is_empty() {
                return;
            }
            let mut p = prefix.to_vec();
            p.extend(s.split("::").map(|x| x.trim().to_string()));
            out.push(p);
        }
    }
    let mut out = Vec::new();
    expand(&[], tree, &mut out);
    out
}

/// Every path in `code` that starts with `crate`, `super`, `self` or one of
/// `children` (a module folder's own modules), as segments; `use` trees
/// expanded, re-exports (`pub use`) of the file's own child modules left
/// out (a module folder's face, not an import).
fn paths(code: &str, children: &BTreeSet<String>) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest_code = String::new();
    // use statements
    let mut s = code;
    while let Some(k) = find_word(s, "use") {
        let before = &s[..k];
        rest_code.push_str(before);
        let line_start = before.rfind(['\n', ';', '{', '}']).map_or(0, |x| x + 1);
        let public = before[line_start..].contains("pub");
        let after = &s[k + 3..];
        let end = after.find(';').unwrap_or(after.len());
        for p in use_paths(&after[..end]) {
            let child = p.first().is_some_and(|f| children.contains(f))
                || (p.first().is_some_and(|f| f == "self")
                    && p.get(1).is_some_and(|f| children.contains(f)));
            if !(public && child) {
                out.push(p);
            }
        }
        s = &after[(end + 1).min(after.len())..];
    }
    rest_code.push_str(s);
    // paths in the code
    let b: Vec<char> = rest_code.chars().collect();
    let mut i = 0;
    while i < b.len() {
        if is_ident(b[i]) && (i == 0 || !(is_ident(b[i - 1]) || b[i - 1] == ':')) {
            let mut segs = Vec::new();
            let mut j = i;
            loop {
                let st = j;
                while j < b.len() && is_ident(b[j]) {
                    j += 1;
                }
                segs.push(b[st..j].iter().collect::<String>());
                if j + 2 < b.len() && b[j] == ':' && b[j + 1] == ':' && is_ident(b[j + 2]) {
                    j += 2;
                } else {
                    break;
                }
            }
            let head = segs[0].as_str();
            if segs.len() > 1
                && (head == "crate" || head == "super" || head == "self" || children.contains(head))
            {
                out.push(segs);
            }
            i = j.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// The first occurrence of `w` as a whole word.
fn find_word(s: &str, w: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(k) = s[from..].find(w) {
        let at = from + k;
        let before = s[..at].chars().next_back();
        let after = s[at + w.len()..].chars().next();
        if !before.is_some_and(is_ident) && !after.is_some_and(is_ident) {
            return Some(at);
        }
        from = at + w.len();
    }
    None
}

/// Whether `code` defines an item called `name` at any depth.
fn defines(code: &str, name: &str) -> bool {
    [
        "fn", "struct", "enum", "trait", "type", "const", "static", "mod", "union",
    ]
    .iter()
    .any(|kw| {
        let pat = format!("{kw} {name}");
        let mut from = 0;
        while let Some(k) = code[from..].find(&pat) {
            let at = from + k;
            let end = at + pat.len();
            let ok_before = !code[..at].chars().next_back().is_some_and(is_ident);
            let ok_after = !code[end..].chars().next().is_some_and(is_ident);
            if ok_before && ok_after {
                return true;
            }
            from = end;
        }
        false
    }) || code.contains(&format!("macro_rules! {name}"))
}

/// The file-level import graph of a crate: file index → the files it
/// imports from. A module folder's `mod.rs` (and the crate root) is the
/// folder's face: its uses of its own modules are its composition, not
/// imports; what it defines, its modules may use.
pub fn file_graph(files: &[File]) -> Vec<BTreeSet<usize>> {
    let by_module: BTreeMap<&[String], usize> = files
        .iter()
        .enumerate()
        .map(|(i, f)| (&f.module[..], i))
        .collect();
    files
        .iter()
        .enumerate()
        .map(|(me, f)| {
            // the module that `self` names, and whose `super` is the parent
            let base: Vec<String> = f.module.clone();
            let children: BTreeSet<String> = files
                .iter()
                .filter(|g| g.module.len() == base.len() + 1 && g.module.starts_with(&base))
                .map(|g| g.module.last().unwrap().clone())
                .filter(|_| f.is_dir_module)
                .collect();
            let mut deps = BTreeSet::new();
            for p in paths(&f.code, &children) {
                let Some(abs) = absolute(&base, f.is_dir_module, &p) else {
                    continue;
                };
                if let Some(t) = resolve(files, &by_module, &abs) {
                    // a module folder's face uses its own modules: that is
                    // how it is composed, not an import
                    let own = f.is_dir_module && files[t].module.starts_with(&f.module);
                    if t != me && !own {
                        deps.insert(t);
                    }
                }
            }
            deps
        })
        .collect()
}

/// A path as segments from the crate root, or None for an external one.
fn absolute(base: &[String], dir_module: bool, p: &[String]) -> Option<Vec<String>> {
    let mut cur: Vec<String> = base.to_vec();
    let mut segs = p;
    match segs.first()?.as_str() {
        "crate" => {
            cur.clear();
            segs = &segs[1..];
        }
        "self" => segs = &segs[1..],
        "super" => {
            while segs.first().is_some_and(|s| s == "super") {
                cur.pop()?;
                segs = &segs[1..];
            }
        }
        _ if dir_module => {}
        _ => return None,
    }
    let _ = dir_module;
    cur.extend(segs.iter().cloned());
    Some(cur)
}

/// The file that defines what `abs` names: the deepest module file on the
/// path, or, where that file only re-exports the item, the file of its
/// folder that defines it.
fn resolve(
    files: &[File],
    by_module: &BTreeMap<&[String], usize>,
    abs: &[String],
) -> Option<usize> {
    let (k, &file) = (0..=abs.len())
        .rev()
        .find_map(|k| by_module.get(&abs[..k]).map(|f| (k, f)))?;
    let Some(item) = abs.get(k) else {
        return Some(file);
    };
    let f = &files[file];
    if !f.is_dir_module || defines(&f.code, item) {
        return Some(file);
    }
    let found = files.iter().position(|g| {
        g.module.len() > f.module.len() && g.module.starts_with(&f.module) && defines(&g.code, item)
    });
    Some(found.unwrap_or(file))
}

/// The import circles of a crate: each strongly connected set of two or
/// more files, as their paths relative to `src`.
pub fn circles(src: &Path) -> Vec<Vec<String>> {
    let files = crate_files(src);
    let g = file_graph(&files);
    // Tarjan's strongly connected components
    struct T<'a> {
        g: &'a [BTreeSet<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(t: &mut T, v: usize) {
        t.index[v] = Some(t.next);
        t.low[v] = t.next;
        t.next += 1;
        t.stack.push(v);
        t.on[v] = true;
        for &w in t.g[v].clone().iter() {
            match t.index[w] {
                None => {
                    visit(t, w);
                    t.low[v] = t.low[v].min(t.low[w]);
                }
                Some(iw) if t.on[w] => t.low[v] = t.low[v].min(iw),
                _ => {}
            }
        }
        if Some(t.low[v]) == t.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                t.out.push(comp);
            }
        }
    }
    let n = files.len();
    let mut t = T {
        g: &g,
        index: vec![None; n],
        low: vec![0; n],
        on: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            visit(&mut t, v);
        }
    }
    t.out
        .into_iter()
        .map(|c| {
            let mut names: Vec<String> = c
                .iter()
                .map(|&i| {
                    let f = &files[i];
                    let rel = f.path.strip_prefix(src).unwrap().display().to_string();
                    let deps: Vec<String> = g[i]
                        .iter()
                        .filter(|d| c.contains(d))
                        .map(|&d| {
                            files[d]
                                .path
                                .strip_prefix(src)
                                .unwrap()
                                .display()
                                .to_string()
                        })
                        .collect();
                    format!("{rel} -> [{}]", deps.join(", "))
                })
                .collect();
            names.sort();
            names
        })
        .collect()
}

/// Every function of the file longer than `limit` lines (from its `fn` line
/// to its closing brace), as `path:line name (n lines)`; test code included.
pub fn long_functions(path: &Path, limit: usize) -> Vec<String> {
    let text = strip(&std::fs::read_to_string(path).unwrap());
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (ln, line) in lines.iter().enumerate() {
        let Some(k) = find_word(line, "fn") else {
            continue;
        };
        let name: String = line[k + 2..]
            .trim_start()
            .chars()
            .take_while(|&c| is_ident(c))
            .collect();
        if name.is_empty() {
            continue;
        }
        // the body: from the first `{` after the signature (a `;` first:
        // a declaration without a body) to its matching `}`
        let mut depth = 0i32;
        let mut opened = false;
        let mut end = None;
        'scan: for (m, l) in lines.iter().enumerate().skip(ln) {
            let from = if m == ln { k } else { 0 };
            for ch in l[from..].chars() {
                match ch {
                    ';' if !opened && depth == 0 => break 'scan,
                    '{' => {
                        depth += 1;
                        opened = true;
                    }
                    '}' => {
                        depth -= 1;
                        if opened && depth == 0 {
                            end = Some(m);
                            break 'scan;
                        }
                    }
                    _ => {}
                }
            }
        }
        if let Some(e) = end {
            let n = e - ln + 1;
            if n > limit {
                out.push(format!("{}:{} {name} ({n} lines)", path.display(), ln + 1));
            }
        }
    }
    out
}
