//! Bad `[output] contacts`, `[output.fields]` and `[[output.flow]]` entries
//! are refused with the file, the line and what is allowed.

mod support;
use clump_io::scenario::{self, Files};
use std::path::Path;
use support::refused;

fn dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenarios")
}

/// The base scenario with `extra` appended to its `[output]` table.
fn with_output(extra: &str) -> String {
    let base = std::fs::read_to_string(dir().join("base_valid.toml")).unwrap();
    let i = base.find("[output]\n").expect("base has [output]") + "[output]\n".len();
    format!("{}{extra}\n{}", &base[..i], &base[i..])
}

#[test]
fn good_entries_are_accepted() {
    let t = with_output(
        "contacts = { every = 0.01 }\nfields = { every = 0.01, axes = [\"x\", \"z\"], cells = [4, 10], width = 0.002, kernel = \"lucy\" }",
    );
    scenario::parse(Path::new("case.toml"), t, Files::disk(&dir()))
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn bad_fields_are_refused() {
    let t = with_output("fields = { every = 0.01, axes = [\"w\"], cells = [4], width = 0.002 }");
    refused(
        &t,
        "fields = {",
        &["unknown axis 'w'", "\"x\", \"y\", \"z\""],
    );
    let t = with_output("fields = { every = 0.01, axes = [\"z\"], cells = [4] }");
    refused(&t, "fields = {", &["missing key 'width'"]);
    let t = with_output("fields = { every = 0.01, axes = [\"z\"], cells = [4], widht = 0.002 }");
    refused(&t, "fields = {", &["widht", "width"]);
    let t =
        with_output("fields = { every = 0.01, axes = [\"z\", \"x\"], cells = [4], width = 0.002 }");
    refused(&t, "fields = {", &["one count per axis"]);
    let t = with_output(
        "fields = { every = 0.01, axes = [\"z\"], cells = [4], width = 0.002, kernel = \"box\" }",
    );
    refused(&t, "fields = {", &["kernel", "gaussian", "lucy"]);
    let t = with_output("contacts = { every = -1.0 }");
    refused(&t, "contacts = {", &["'every' must be > 0"]);
}

#[test]
fn bad_flow_probes_are_refused() {
    let probe = |body: &str| format!("{}\n[[output.flow]]\n{body}\n", with_output(""));
    let t = probe("name = \"a\"\ntype = \"circle\"\nevery = 0.01");
    refused(
        &t,
        "type = \"circle\"",
        &["unknown probe type 'circle'", "\"plane\" and \"region\""],
    );
    let t = probe("name = \"a\"\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nlo = [0.0, 0.0, 0.0]\nevery = 0.01");
    refused(
        &t,
        "lo = [0.0, 0.0, 0.0]\nevery",
        &["belong to a region probe"],
    );
    let t = probe("name = \"a\"\ntype = \"region\"\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\nbins = [0.2, 0.1]\nevery = 0.01");
    refused(&t, "bins = [0.2", &["ascending"]);
    let t = probe("name = \"a\"\ntype = \"region\"\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\nevery = 0.01\n\n[[output.flow]]\nname = \"b\"\ntype = \"region\"\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\nevery = 0.02");
    refused(&t, "every = 0.02", &["one interval"]);
    let t = probe("type = \"region\"\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\nevery = 0.01");
    refused(&t, "[[output.flow]]", &["missing key 'name'"]);
}
