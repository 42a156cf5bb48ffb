//! The checked-in header `include/clump.h` is what cbindgen generates from
//! the crate's source with `cbindgen.toml`; with `CLUMP_BLESS_HEADER=1`
//! the test writes it instead.

use std::path::Path;

#[test]
fn header_matches_cbindgen() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    // cbindgen follows the `mod` declarations of lib.rs
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen parses the crate")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = dir.join("include/clump.h");
    if std::env::var_os("CLUMP_BLESS_HEADER").is_some() {
        std::fs::write(&path, &generated).expect("write include/clump.h");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "include/clump.h differs from what cbindgen generates; regenerate it with \
         CLUMP_BLESS_HEADER=1 cargo test -p clump-capi --test header"
    );
}
