//! The module structure of clump-core: no import cycle among its top-level
//! modules, and no source file beyond about 800 lines. Read from the
//! sources as text: every `crate::<module>` path outside comments counts as
//! a dependency of the top-level module whose file holds it.
//!
//! `cargo test -p clump-core --test module_structure -- --nocapture`
//! prints the dependency list.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

mod structure;

use structure::sources;

/// The top-level module a file belongs to (`lib` for lib.rs).
fn owner(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// Module dependencies: `crate::m` paths and `use super::` at the top level
/// of a module folder are the only ways to reach another module.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let me = owner(&src, f);
        if me == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        let deps = g.entry(me.clone()).or_default();
        for line in text.lines() {
            let code = line.split("//").next().unwrap();
            let mut rest = code;
            while let Some(k) = rest.find("crate::") {
                let tail = &rest[k + 7..];
                let name: String = tail
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() && name != me && name.chars().next().unwrap().is_lowercase() {
                    deps.insert(name);
                }
                rest = tail;
            }
        }
    }
    g
}

#[test]
fn no_import_cycle_among_top_level_modules() {
    let g = graph();
    for (m, d) in &g {
        println!(
            "{m} -> {}",
            d.iter().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    // depth-first search for a back edge
    fn visit(
        m: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match state.get(m) {
            Some(1) => {
                let i = path.iter().position(|x| x == m).unwrap();
                let mut cycle = path[i..].to_vec();
                cycle.push(m.to_string());
                return Some(cycle);
            }
            Some(2) => return None,
            _ => {}
        }
        state.insert(m.to_string(), 1);
        path.push(m.to_string());
        for d in g.get(m).into_iter().flatten() {
            if let Some(c) = visit(d, g, state, path) {
                return Some(c);
            }
        }
        path.pop();
        state.insert(m.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for m in g.keys() {
        if let Some(c) = visit(m, &g, &mut state, &mut Vec::new()) {
            panic!("import cycle: {}", c.join(" -> "));
        }
    }
}

#[test]
fn no_source_file_beyond_800_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let long: Vec<String> = files
        .iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(f).unwrap().lines().count();
            (n > 800).then(|| format!("{} ({n} lines)", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "files over 800 lines: {long:?}");
}

/// The crates whose files are checked: every crate of the repository.
fn crate_sources() -> Vec<PathBuf> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&crates)
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    out.sort();
    out
}

/// No circle of imports between the files of a crate: a file that imports
/// an item of another (through `use` or a path in the code) depends on it,
/// and no file depends on itself through others.
#[test]
fn no_import_circle_between_files() {
    let mut found = Vec::new();
    for src in crate_sources() {
        for c in structure::circles(&src) {
            found.push(format!("{}:\n    {}", src.display(), c.join("\n    ")));
        }
    }
    assert!(found.is_empty(), "import circles:\n{}", found.join("\n"));
}

/// No function beyond 150 lines in clump-core: one screen of ideas.
#[test]
fn no_function_beyond_150_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    files.sort();
    let long: Vec<String> = files
        .iter()
        .flat_map(|f| structure::long_functions(f, 150))
        .collect();
    assert!(
        long.is_empty(),
        "functions over 150 lines:\n{}",
        long.join("\n")
    );
}

/// The structure checks find what they look for: a circle between two
/// files and a long function, in sources written for the test.
#[test]
fn the_checks_find_a_circle_and_a_long_function() {
    let dir = std::env::temp_dir().join(format!("clump-structure-{}", std::process::id()));
    let src = dir.join("src");
    std::fs::create_dir_all(src.join("a")).unwrap();
    std::fs::write(src.join("lib.rs"), "mod a;\nmod c;\n").unwrap();
    std::fs::write(
        src.join("a/mod.rs"),
        "mod b;\npub use b::Thing;\npub struct Other;\n",
    )
    .unwrap();
    std::fs::write(
        src.join("a/b.rs"),
        "// crate::c::Gone in a comment is no import\nuse crate::c::{Helper, more::{X}};\npub struct Thing;\n",
    )
    .unwrap();
    let long_body = "    let x = 1;\n".repeat(160);
    std::fs::write(
        src.join("c.rs"),
        format!("pub struct Helper;\nfn uses() {{ let _ = crate::a::Thing; }}\nfn long() {{\n{long_body}}}\n"),
    )
    .unwrap();
    let circles = structure::circles(&src);
    assert_eq!(circles.len(), 1, "{circles:?}");
    assert!(
        circles[0].iter().any(|l| l.starts_with("a/b.rs")),
        "{circles:?}"
    );
    assert!(
        circles[0].iter().any(|l| l.starts_with("c.rs")),
        "{circles:?}"
    );
    let long = structure::long_functions(&src.join("c.rs"), 150);
    assert_eq!(long.len(), 1, "{long:?}");
    assert!(long[0].contains("long (162 lines)"), "{long:?}");
    std::fs::remove_dir_all(&dir).ok();
}
