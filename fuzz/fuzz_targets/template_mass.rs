//! A template file, parsed and integrated (`clump template` without the
//! printing): mass properties never panic, whatever the spheres (coincident,
//! nested, huge or tiny coordinates, hundreds of spheres, which the
//! integration cuts into slabs).
#![no_main]
use clump_core::shape::ClumpTemplate;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    if let Ok(spheres) = clump_io::template_file::parse_template_bytes(data, Path::new("f.txt")) {
        let _ = ClumpTemplate::from_spheres("fuzz", &spheres, 1000.0);
    }
});
