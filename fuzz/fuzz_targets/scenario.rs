//! Scenario parsing and validation never panic on arbitrary bytes. The
//! input is the scenario text (lossy UTF-8); referenced files resolve to a
//! small embedded template file and bodies file.
#![no_main]
use clump_io::scenario::{self, Files};
use libfuzzer_sys::fuzz_target;
use std::collections::BTreeMap;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    let mut files = BTreeMap::new();
    files.insert(
        "t.txt".to_string(),
        b"0 0 0 0.001\n0.001 0 0 0.001\n".to_vec(),
    );
    files.insert(
        "b.csv".to_string(),
        b"template,x,y,z\n0,0,0,0.01\n".to_vec(),
    );
    if let Ok(sc) = scenario::parse(Path::new("fuzz.toml"), text, Files::embedded(files)) {
        let _ = sc.build_world();
        let _ = sc.total_steps();
    }
});
