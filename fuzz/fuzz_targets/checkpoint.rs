//! Checkpoint files never panic on arbitrary bytes: header, length, CRC,
//! payload decoding, the stored scenario and restoring the world state.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = clump_io::run::load_checkpoint(data, Path::new("fuzz.ckpt"));
});
