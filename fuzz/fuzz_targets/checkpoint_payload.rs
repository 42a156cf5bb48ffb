//! Past the CRC: the input is the checkpoint's JSON payload, wrapped in a
//! valid header (correct length and CRC, and the fingerprint of the scenario
//! it holds when it decodes), so that the fuzzer reaches the state decoding,
//! the scenario rebuild and `World::restore_state`. Never panics.
#![no_main]
use clump_io::checkpoint::encode_checkpoint;
use clump_io::run::{load_checkpoint, Checkpoint};
use clump_io::scenario::{self, Files};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let json = String::from_utf8_lossy(data).into_owned();
    let fingerprint = serde_json::from_str::<Checkpoint>(&json)
        .ok()
        .and_then(|ck| {
            scenario::parse(
                Path::new(&ck.scenario_path),
                ck.scenario_text.clone(),
                Files::embedded(ck.files.clone()),
            )
            .ok()
        })
        .map_or(0, |s| s.fingerprint());
    if let Ok(bytes) = encode_checkpoint(&json, fingerprint) {
        let _ = load_checkpoint(&bytes, Path::new("fuzz.ckpt"));
    }
});
