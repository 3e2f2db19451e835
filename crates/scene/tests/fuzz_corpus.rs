//! Replays the committed cargo-fuzz corpora (`fuzz/corpus/{scene_xml,obj,ply}`, see README.md,
//! Fuzzing) through the same entry points the fuzz targets call: every input must give a scene
//! or an error (meshes: one whose triangles index its vertices), never a panic.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use scene::MeshDesc;

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz")
}

/// The contents of every file of one target's corpus, with their names.
fn corpus(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = fuzz_dir().join("corpus").join(target);
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&path).unwrap())
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "empty corpus {}", dir.display());
    files
}

/// Runs `check` on every input of `target`'s corpus; fails naming each input that panicked.
fn replay(target: &str, check: impl Fn(&[u8])) {
    let inputs = corpus(target);
    let panicked: Vec<&str> = inputs
        .iter()
        .filter(|(_, bytes)| catch_unwind(AssertUnwindSafe(|| check(bytes))).is_err())
        .map(|(name, _)| name.as_str())
        .collect();
    assert!(
        panicked.is_empty(),
        "{} of {} inputs in fuzz/corpus/{target} panicked (replay one with \
         `cargo fuzz run {target} fuzz/corpus/{target}/NAME`): {panicked:?}",
        panicked.len(),
        inputs.len()
    );
}

/// The invariants the mesh fuzz targets assert.
fn check_mesh(mesh: &MeshDesc) {
    let n = mesh.positions.len();
    assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < n));
    assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
    assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
}

#[test]
fn scene_xml_corpus_replays_without_panics() {
    // As in fuzz/fuzz_targets/scene_xml.rs: relative mesh paths resolve against fuzz/meshes/.
    let path = fuzz_dir().join("meshes/fuzz.xml");
    replay("scene_xml", |bytes| {
        if let Ok(desc) = scene::parse_bytes(bytes, &path, &[]) {
            let _ = scene::build(desc);
        }
    });
}

#[test]
fn obj_corpus_replays_without_panics() {
    replay("obj", |bytes| {
        if let Ok(mesh) = scene::parse_obj(bytes, true) {
            check_mesh(&mesh);
        }
    });
}

#[test]
fn ply_corpus_replays_without_panics() {
    replay("ply", |bytes| {
        if let Ok(mesh) = scene::parse_ply(bytes) {
            check_mesh(&mesh);
        }
    });
}
