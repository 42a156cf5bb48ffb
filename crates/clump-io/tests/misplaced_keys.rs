//! Keys that belong to another type of wall or region, or another kind of
//! insertion, are refused at their line with the keys that do apply (the
//! lists of `scenario::keys`). The region cases cover both an inline table
//! and a `[insert.region]` table.

mod support;
use clump_io::scenario::{self, Files};
use std::path::Path;
use support::refused;

fn base() -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenarios");
    std::fs::read_to_string(dir.join("base_valid.toml")).unwrap()
}

const REGION: &str =
    "region = { type = \"box\", lo = [-0.05, -0.05, 0.01], hi = [0.05, 0.05, 0.1] }";

#[test]
fn base_is_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenarios");
    scenario::parse(Path::new("case.toml"), base(), Files::disk(&dir))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(base().contains(REGION));
}

#[test]
fn box_wall_with_a_plane_key() {
    let t = base().replace(
        "hi = [0.01, 0.01, 0.0]\n",
        "hi = [0.01, 0.01, 0.0]\nnormal = [0.0, 0.0, 1.0]\n",
    );
    refused(
        &t,
        "normal = [0.0, 0.0, 1.0]\ninside",
        &[
            "'normal' does not apply to a wall of type \"box\"",
            "a box uses lo, hi, inside",
        ],
    );
}

#[test]
fn stream_with_a_pack_key() {
    let t = base()
        .replace("kind = \"pack\"", "kind = \"stream\"")
        .replace(
            "seed = 1\n",
            "seed = 1\nbodies_per_second = 10.0\nvolume_fraction = 0.1\n",
        );
    refused(
        &t,
        "volume_fraction = 0.1",
        &[
            "'volume_fraction' does not apply to kind = \"stream\"",
            "note: kind = \"stream\" uses: stage, mix, template, count, region, seed, velocity, \
             orientation, bodies_per_second, kg_per_second, start, end, max_attempts",
        ],
    );
}

#[test]
fn pack_with_a_stream_key() {
    let t = base().replace("seed = 1\n", "seed = 1\nstart = 0.01\n");
    refused(
        &t,
        "start = 0.01",
        &[
            "'start' does not apply to kind = \"pack\"",
            "note: kind = \"pack\" uses: stage, mix, template, count, volume_fraction, region, \
             seed, velocity, orientation, max_attempts",
        ],
    );
}

#[test]
fn file_insert_with_a_pack_key() {
    let t = base().replace("kind = \"pack\"", "kind = \"file\"");
    refused(
        &t,
        "mix = \"pebbles\"\ncount",
        &[
            "'mix' does not apply to kind = \"file\"",
            "note: kind = \"file\" uses: stage, file, template, format, orientation_frame",
        ],
    );
}

#[test]
fn inline_box_region_with_a_cylinder_key() {
    let t = base().replace(REGION, &REGION.replace(" }", ", radius = 0.01 }"));
    refused(
        &t,
        "radius = 0.01 }",
        &["'radius' does not apply to a region of type \"box\" (it uses lo, hi)"],
    );
}

#[test]
fn region_table_of_a_cylinder_with_a_box_key() {
    let t = base().replace(REGION, "").replace(
        "seed = 1\n",
        "seed = 1\n[insert.region]\ntype = \"cylinder\"\nbase = [0.0, 0.0, 0.01]\n\
         radius = 0.04\nheight = 0.05\nhi = [0.05, 0.05, 0.1]\n",
    );
    refused(
        &t,
        "hi = [0.05, 0.05, 0.1]\n",
        &["'hi' does not apply to a region of type \"cylinder\" (it uses base, axis, radius, height)"],
    );
}
