//! Fuzzes the PLY reader (ascii and binary): any bytes must give a mesh whose triangles index its
//! vertices, or an error; never a panic, a hang or an allocation larger than the input justifies.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = scene::parse_ply(data) {
        let n = mesh.positions.len();
        assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
        assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
        assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
    }
});
