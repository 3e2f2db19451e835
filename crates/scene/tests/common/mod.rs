//! Helpers shared by the integration tests.

// Each test binary uses a different subset of these helpers.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::Once;

use glam::Vec3;
use scene::{LoadError, MeshDesc, SceneDesc};

/// The fixture directory.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// The scratch directory for generated scenes, with a fresh copy of the fixture meshes in
/// `meshes/` (so relative paths like `meshes/box.obj` resolve), made once per test process.
fn scratch_dir() -> PathBuf {
    static COPY: Once = Once::new();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scene-tests");
    COPY.call_once(|| {
        std::fs::create_dir_all(dir.join("meshes")).unwrap();
        for entry in std::fs::read_dir(data_dir().join("meshes")).unwrap() {
            let entry = entry.unwrap();
            let target = dir.join("meshes").join(entry.file_name());
            // Copy then rename, so a reader never sees a half-written file.
            let partial = target.with_extension(format!("partial{}", std::process::id()));
            std::fs::copy(entry.path(), &partial).unwrap();
            std::fs::rename(&partial, &target).unwrap();
        }
    });
    dir
}

/// Writes `text` as `name` in the scratch directory and returns its path.
pub fn write_scene(name: &str, text: &str) -> PathBuf {
    let path = scratch_dir().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Loads a scene written from `text` without overrides.
pub fn load(name: &str, text: &str) -> Result<SceneDesc, LoadError> {
    scene::parse_file(&write_scene(name, text), &[])
}

/// A scene with the mandatory integrator and sensor around `body`; `body` starts on line 4.
pub fn wrap(body: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<sensor type=\"perspective\"/>\n{body}\n</scene>\n"
    )
}

/// Unit geometric normal of triangle `i`.
pub fn triangle_normal(mesh: &MeshDesc, i: usize) -> Vec3 {
    let [a, b, c] = mesh.triangles[i].map(|v| mesh.positions[v as usize]);
    (b - a).cross(c - a).normalize()
}

/// True when `a` and `b` differ by less than `tol` in every component.
pub fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() < tol
}
