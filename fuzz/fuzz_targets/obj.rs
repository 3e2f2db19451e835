//! Fuzzes the OBJ reader: any bytes must give a mesh whose triangles index its vertices, or an
//! error; never a panic, a hang or an unbounded allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = scene::parse_obj(data, true) {
        let n = mesh.positions.len();
        assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
        assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
        assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
    }
});
