//! LIGGGHTS-format template files never panic on arbitrary bytes.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = clump_io::template_file::parse_template_bytes(data, Path::new("fuzz.txt"));
});
