//! Corrupted scene and mesh files must produce errors, never panics or runaway allocations.
//!
//! Mutations come from a fixed-seed xorshift generator; a failure prints the seed and the
//! mutation index so the input can be rebuilt.

mod common;

use common::{data_dir, write_scene};

/// Seed of the mutation generator.
const SEED: u32 = 0x9e37_79b9;
/// Mutated variants tried per input file.
const VARIANTS: usize = 150;

/// Marsaglia's xorshift32.
struct XorShift(u32);

impl XorShift {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() as usize) % n.max(1)
    }
}

/// One random corruption of `bytes`: truncation, a byte overwritten, a byte removed, or a span
/// duplicated.
fn mutate(bytes: &[u8], rng: &mut XorShift) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let at = rng.below(out.len());
    match rng.below(4) {
        0 => out.truncate(at),
        1 => out[at] = b"<>\"/=$ 0123456789-.e\n\0\xff"[rng.below(23)],
        2 => {
            out.remove(at);
        }
        _ => {
            let len = rng.below(64).min(out.len() - at);
            let span = out[at..at + len].to_vec();
            out.splice(at..at, span);
        }
    }
    out
}

/// Loads a scene after `catch_unwind`, returning whether it panicked.
fn panics(path: &std::path::Path) -> bool {
    std::panic::catch_unwind(|| {
        let _ = scene::parse_file(path, &[]);
    })
    .is_err()
}

#[test]
fn mutated_scene_files_never_panic() {
    let original = std::fs::read(data_dir().join("cornell.xml")).unwrap();
    let mut rng = XorShift(SEED);
    let mut accepted = 0;
    for variant in 0..VARIANTS {
        let bytes = mutate(&original, &mut rng);
        let path = write_scene("mutated_scene.xml", "");
        std::fs::write(&path, &bytes).unwrap();
        assert!(
            !panics(&path),
            "panic on mutated cornell.xml: seed {SEED:#x}, variant {variant}"
        );
        accepted += usize::from(scene::parse_file(&path, &[]).is_ok());
    }
    // Most corruptions must be caught; a few (e.g. a changed digit) are still valid scenes.
    assert!(
        accepted < VARIANTS / 2,
        "{accepted} of {VARIANTS} corrupted scenes accepted"
    );
}

#[test]
fn mutated_meshes_never_panic() {
    for mesh in ["quad_le.ply", "quad_be.ply", "pentagon.ply", "box.obj"] {
        let original = std::fs::read(data_dir().join("meshes").join(mesh)).unwrap();
        let kind = if mesh.ends_with(".obj") { "obj" } else { "ply" };
        let scene_path = write_scene(
            &format!("mutated_{kind}.xml"),
            &common::wrap(&format!(
                "<shape type=\"{kind}\"><string name=\"filename\" value=\"meshes/mutated.{kind}\"/></shape>"
            )),
        );
        let mesh_path = scene_path
            .parent()
            .unwrap()
            .join(format!("meshes/mutated.{kind}"));
        let mut rng = XorShift(SEED);
        for variant in 0..VARIANTS {
            std::fs::write(&mesh_path, mutate(&original, &mut rng)).unwrap();
            assert!(
                !panics(&scene_path),
                "panic on mutated {mesh}: seed {SEED:#x}, variant {variant}"
            );
            if let Ok(desc) = scene::parse_file(&scene_path, &[]) {
                // Whatever is accepted must be self-consistent.
                let scene::Geometry::Mesh(m) = &desc.shapes[0].geometry else {
                    panic!("mesh expected")
                };
                let n = m.positions.len();
                assert!(m.triangles.iter().flatten().all(|&i| (i as usize) < n));
                assert!(m.normals.as_ref().is_none_or(|v| v.len() == n));
                assert!(m.uvs.as_ref().is_none_or(|v| v.len() == n));
                assert!(m.positions.iter().all(|p| p.is_finite()));
            }
        }
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let depth = 20_000;
    let text = format!(
        "<scene version=\"3.0.0\">{}{}</scene>",
        "<bsdf type=\"twosided\">".repeat(depth),
        "</bsdf>".repeat(depth)
    );
    let err = common::load("deep.xml", &text).unwrap_err();
    assert!(err.message.contains("nested deeper"), "{err}");
}
