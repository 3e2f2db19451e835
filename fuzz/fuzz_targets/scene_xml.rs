//! Fuzzes the Mitsuba XML scene loader: any bytes must give a scene or a `LoadError`, never a
//! panic, a hang or an unbounded allocation. Accepted scenes are also built (BVH, lights), since
//! values the parser lets through must be safe to build. Relative mesh paths resolve against
//! `fuzz/meshes/`, so inputs can name `box.obj`, `pentagon.ply` and `quad_le.ply`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/meshes/fuzz.xml"));
    if let Ok(desc) = scene::parse_bytes(data, path, &[]) {
        let _ = scene::build(desc);
    }
});
