//! STL (binary and ASCII) and OBJ parsing, and building the triangle mesh
//! from the result, never panic on arbitrary bytes. The first byte picks the
//! format.
#![no_main]
use clump_core::wall::TriMesh;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&sel, bytes)) = data.split_first() else {
        return;
    };
    let parsed = if sel & 1 == 0 {
        clump_io::mesh_file::parse_stl(bytes)
    } else {
        clump_io::mesh_file::parse_obj(bytes)
    };
    if let Ok((v, t)) = parsed {
        let _ = TriMesh::new(v, t);
    }
});
