//! Checkpoint round trip and every kind of damage.

use clump_io::checkpoint::{
    decode_checkpoint, encode_checkpoint, read_checkpoint, write_checkpoint, CheckpointError,
    HEADER_LEN,
};
use proptest::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct State {
    step: u64,
    xs: Vec<f64>,
    name: String,
    nested: Vec<(u32, Option<[f64; 3]>)>,
}

fn sample() -> State {
    State {
        step: 12345,
        xs: (0..100).map(|i| (i as f64).sin() * 1e-3).collect(),
        name: "drum".into(),
        nested: vec![(1, Some([1.0, -2.0, f64::MIN_POSITIVE])), (7, None)],
    }
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_ckp_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

#[test]
fn round_trip() {
    let p = tmp("ok.ckp");
    write_checkpoint(&p, &sample(), 0xDEADBEEF).unwrap();
    let (s, fp): (State, u64) = read_checkpoint(&p).unwrap();
    assert_eq!(s, sample());
    assert_eq!(fp, 0xDEADBEEF);
}

fn expect_err(bytes: &[u8]) -> CheckpointError {
    decode_checkpoint::<State>(bytes, Path::new("run.ckp")).unwrap_err()
}

#[test]
fn damage_gives_distinct_errors() {
    let good = encode_checkpoint(&sample(), 7).unwrap();
    // wrong magic
    let mut b = good.clone();
    b[0] = b'X';
    let e = expect_err(&b);
    assert!(matches!(e, CheckpointError::BadMagic { .. }), "{e}");
    assert!(e.to_string().contains("run.ckp") && e.to_string().contains("not a Clump checkpoint"));
    // too short
    let e = expect_err(&good[..20]);
    assert!(matches!(e, CheckpointError::TooShort { .. }), "{e}");
    let e = expect_err(&[]);
    assert!(matches!(e, CheckpointError::TooShort { .. }), "{e}");
    // wrong version
    let mut b = good.clone();
    b[8] = 99;
    let e = expect_err(&b);
    assert!(
        matches!(e, CheckpointError::UnsupportedVersion { found: 99, .. }),
        "{e}"
    );
    // truncated payload
    let e = expect_err(&good[..good.len() - 3]);
    assert!(matches!(e, CheckpointError::LengthMismatch { .. }), "{e}");
    assert!(e.to_string().contains("truncated"));
    // flipped payload bit
    let mut b = good.clone();
    b[HEADER_LEN + 10] ^= 0x10;
    let e = expect_err(&b);
    assert!(matches!(e, CheckpointError::BadChecksum { .. }), "{e}");
    // a valid container with a payload of another type
    let other = encode_checkpoint(&(1u8, 2u8), 7).unwrap();
    let e = expect_err(&other);
    assert!(matches!(e, CheckpointError::Decode { .. }), "{e}");
    // missing file
    let e = read_checkpoint::<State>(tmp("missing.ckp")).unwrap_err();
    assert!(matches!(e, CheckpointError::Io { .. }), "{e}");
    assert!(e.to_string().contains("missing.ckp"));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let _ = decode_checkpoint::<State>(&bytes, Path::new("x"));
        let mut with_magic = b"CLUMPCKP\x01\0\0\0".to_vec();
        with_magic.extend_from_slice(&bytes);
        let _ = decode_checkpoint::<State>(&with_magic, Path::new("x"));
    }

    #[test]
    fn truncations_and_bit_flips_are_detected(cut in 0usize..2000, flip in 0usize..20000, also_flip in any::<bool>()) {
        let good = encode_checkpoint(&sample(), 3).unwrap();
        let cut = cut % good.len();
        prop_assert!(decode_checkpoint::<State>(&good[..cut], Path::new("x")).is_err());
        if also_flip {
            let mut b = good.clone();
            let bit = flip % (8 * b.len());
            b[bit / 8] ^= 1 << (bit % 8);
            // a flip in the fingerprint is not detectable (it is data); everything else is
            let r = decode_checkpoint::<State>(&b, Path::new("x"));
            if !(12..20).contains(&(bit / 8)) {
                prop_assert!(r.is_err());
            } else {
                prop_assert!(r.is_ok());
            }
        }
    }
}
