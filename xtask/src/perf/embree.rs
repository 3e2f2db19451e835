//! The Embree anchor of `cargo xtask raycast-limit`: the rays a render recorded, traced by Strata
//! and by Embree 4 (Intel's ray-tracing kernels, through the `embreex` Python package), on the
//! same triangles.
//!
//! Embree is reached through `embreex`, whose only geometry is triangles; so both sides trace a
//! triangle version of the scene, in which each sphere is replaced by an icosphere of
//! [`SPHERE_SUBDIVISIONS`] (the scene's meshes, rectangles and cubes included, are triangles
//! already). The scene's triangles (world space, camera-relative, exactly as Strata's hierarchy
//! holds them) and the recorded rays go to `.npy` files under `target/raycast-limit/`;
//! `xtask/embree_trace.py`, run in a virtual environment this module makes under
//! `target/embree-venv/` (`pip install embreex`), builds an Embree scene from them and times
//! `EmbreeScene.run` over the same rays.
//!
//! What each side's time includes: Strata, `Accel::intersect` (the closest hit completed to a
//! surface point with normals, as a render uses it) or `Accel::occluded` over the recorded rays in
//! chunks on a rayon pool; Embree, `rtcIntersect1` (t, u, v, Ng, ids) or `rtcOccluded1` called one
//! ray at a time from `run`'s C loop, on one thread or on Python threads each taking a chunk
//! (`run` releases the GIL). Both: tnear 0 and the recorded tfar (∞ for closest-hit rays);
//! hierarchy builds, file writing and Python start-up excluded. Embree's scene uses
//! `RTC_SCENE_FLAG_ROBUST` (robust traversal, none of the optimisations that cost accuracy: the
//! nearest Embree comes to Strata's watertight triangle test); its default flags, faster and
//! less careful at shared edges, are reported beside it.

use super::median;
use geometry::{Accel, Shape, TriangleMesh};
use rayon::prelude::*;
use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use world::RayLog;

/// Times each sphere's icosahedron is split (four triangles each time): 20 · 4^4 = 5120
/// triangles per sphere.
pub const SPHERE_SUBDIVISIONS: u32 = 4;

/// The `embreex` release the comparison installs (Embree 4.4); its `run` is checked to take
/// per-ray tfar, to release the GIL and to answer occlusion with 0 (occluded) or -1.
const EMBREEX: &str = "embreex==4.4.0.post1";

/// The scene as triangles only: `shapes` with each sphere replaced by its icosphere (placed and
/// scaled in world space), and the number of spheres replaced.
pub fn tessellated(shapes: &[Shape]) -> (Vec<Shape>, usize) {
    let mut spheres = 0;
    let shapes = shapes
        .iter()
        .map(|shape| match shape {
            Shape::Mesh(_) => shape.clone(),
            Shape::Sphere(sphere) => {
                spheres += 1;
                let mut mesh = TriangleMesh::icosphere(SPHERE_SUBDIVISIONS);
                for p in &mut mesh.positions {
                    *p = sphere.center + sphere.radius * *p;
                }
                if sphere.flip_normals {
                    for n in mesh.normals.iter_mut().flatten() {
                        *n = -*n;
                    }
                }
                Shape::Mesh(mesh)
            }
        })
        .collect();
    (shapes, spheres)
}

/// All triangles of some meshes as one list, as the Embree side gets them.
#[derive(Debug, PartialEq)]
pub struct Merged {
    /// Vertex positions, world space.
    pub positions: Vec<[f32; 3]>,
    /// Vertex indices of each triangle into `positions`.
    pub indices: Vec<[u32; 3]>,
    /// Index in `indices` of each shape's first triangle: triangle `prim` of shape `s` is
    /// `first[s] + prim`.
    pub first: Vec<u32>,
}

/// The triangles of `shapes` (meshes only: [`tessellated`] first) merged into one list.
pub fn merged(shapes: &[Shape]) -> Result<Merged, String> {
    let mut out = Merged {
        positions: Vec::new(),
        indices: Vec::new(),
        first: Vec::new(),
    };
    for shape in shapes {
        let Shape::Mesh(mesh) = shape else {
            return Err("merged: a sphere left untessellated".to_string());
        };
        let base = u32::try_from(out.positions.len()).map_err(|_| "too many vertices")?;
        out.first
            .push(u32::try_from(out.indices.len()).map_err(|_| "too many triangles")?);
        out.positions
            .extend(mesh.positions.iter().map(|p| p.to_array()));
        out.indices
            .extend(mesh.indices.iter().map(|t| t.map(|i| base + i)));
    }
    Ok(out)
}

/// A little-endian element type of a `.npy` file.
pub trait NpyElement: Copy {
    /// NumPy's type string, e.g. `<f4`.
    const DESCR: &'static str;
    /// Appends the element's little-endian bytes.
    fn put(self, out: &mut Vec<u8>);
}

impl NpyElement for f32 {
    const DESCR: &'static str = "<f4";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl NpyElement for u32 {
    const DESCR: &'static str = "<u4";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl NpyElement for i32 {
    const DESCR: &'static str = "<i4";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl NpyElement for u8 {
    const DESCR: &'static str = "|u1";
    fn put(self, out: &mut Vec<u8>) {
        out.push(self);
    }
}

/// A C-ordered array of `shape` (one or two axes) in NumPy's `.npy` format, version 1.0: the
/// magic string, the header's length, the header (a Python dict literal padded with spaces as
/// `numpy.save` pads it, to a multiple of 64 bytes with room for the first axis to grow to 21
/// digits) and the elements.
///
/// # Panics
/// If `values` does not hold `shape`'s product of elements, or `shape` has no axes.
pub fn npy<T: NpyElement>(shape: &[usize], values: impl IntoIterator<Item = T>) -> Vec<u8> {
    let dims = match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': {dims}, }}",
        T::DESCR
    );
    let first_axis_digits = shape[0].to_string().len();
    header.push_str(&" ".repeat(21 - first_axis_digits.min(21)));
    // Magic (6), version (2), header length (2), header, newline: a multiple of 64 bytes.
    let used = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - used % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + shape.iter().product::<usize>() * 4);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    let mut count = 0;
    for value in values {
        value.put(&mut out);
        count += 1;
    }
    assert_eq!(
        count,
        shape.iter().product::<usize>(),
        "{count} elements for shape {shape:?}"
    );
    out
}

/// Writes `bytes` to `dir/name.npy` whole or not at all (a temporary file renamed).
fn write_file(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), String> {
    let path = dir.join(format!("{name}.npy"));
    let partial = dir.join(format!("{name}.npy.partial"));
    std::fs::write(&partial, bytes)
        .and_then(|()| std::fs::rename(&partial, &path))
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Rows of three floats as an `(n, 3)` array.
fn rows(values: impl ExactSizeIterator<Item = [f32; 3]>) -> Vec<u8> {
    let n = values.len();
    npy(&[n, 3], values.flatten())
}

/// Strata's answer for each recorded ray on `accel`: closest-hit distance (∞ on a miss) and
/// merged triangle index (-1 on a miss), and whether each shadow ray is occluded.
fn strata_answers(accel: &Accel, first: &[u32], log: &RayLog) -> (Vec<(f32, i32)>, Vec<u8>) {
    let closest = log
        .closest
        .par_iter()
        .map(|ray| match accel.intersect(ray, f32::INFINITY) {
            Some(hit) => (hit.t, (first[hit.shape as usize] + hit.prim) as i32),
            None => (f32::INFINITY, -1),
        })
        .collect();
    let shadow = log
        .shadow
        .par_iter()
        .map(|s| u8::from(accel.occluded(&s.ray, s.t_max)))
        .collect();
    (closest, shadow)
}

/// Writes the triangles, the rays and Strata's answers for `embree_trace.py` into `dir`.
fn export(dir: &Path, triangles: &Merged, accel: &Accel, log: &RayLog) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let (closest, shadow) = strata_answers(accel, &triangles.first, log);
    let (n, m) = (log.closest.len(), log.shadow.len());
    let files: [(&str, Vec<u8>); 11] = [
        ("vertices", rows(triangles.positions.iter().copied())),
        (
            "triangles",
            npy(
                &[triangles.indices.len(), 3],
                triangles.indices.iter().flatten().copied(),
            ),
        ),
        (
            "closest_origins",
            rows(log.closest.iter().map(|r| r.origin.to_array())),
        ),
        (
            "closest_dirs",
            rows(log.closest.iter().map(|r| r.dir.to_array())),
        ),
        (
            "closest_tfar",
            npy(&[n], std::iter::repeat_n(f32::INFINITY, n)),
        ),
        (
            "shadow_origins",
            rows(log.shadow.iter().map(|s| s.ray.origin.to_array())),
        ),
        (
            "shadow_dirs",
            rows(log.shadow.iter().map(|s| s.ray.dir.to_array())),
        ),
        ("shadow_tfar", npy(&[m], log.shadow.iter().map(|s| s.t_max))),
        ("strata_closest_t", npy(&[n], closest.iter().map(|c| c.0))),
        ("strata_closest_tri", npy(&[n], closest.iter().map(|c| c.1))),
        ("strata_shadow", npy(&[m], shadow.iter().copied())),
    ];
    for (name, bytes) in &files {
        write_file(dir, name, bytes)?;
    }
    Ok(())
}

/// The Python of the virtual environment under `target`, with `embreex` installed in it: made
/// and installed on first use.
fn embree_python(target: &Path) -> Result<PathBuf, String> {
    let venv = target.join("embree-venv");
    let python = if cfg!(windows) {
        venv.join("Scripts").join("python.exe")
    } else {
        venv.join("bin").join("python")
    };
    let run = |command: &mut Command, what: &str| -> Result<(), String> {
        let status = command
            .status()
            .map_err(|e| format!("cannot {what}: {e}"))?;
        if status.success() {
            Ok(())
        } else {
            Err(format!("{what} failed ({status})"))
        }
    };
    if !python.exists() {
        eprintln!("making {} for embreex", venv.display());
        run(
            Command::new("python3").args(["-m", "venv"]).arg(&venv),
            &format!("python3 -m venv {}", venv.display()),
        )?;
    }
    let has_embreex = Command::new(&python)
        .args(["-c", "import embreex, numpy"])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !has_embreex {
        eprintln!("installing {EMBREEX} into {}", venv.display());
        run(
            Command::new(&python).args(["-m", "pip", "install", "--quiet", EMBREEX, "numpy"]),
            &format!("pip install {EMBREEX}"),
        )?;
    }
    Ok(python)
}

/// Median seconds of Strata tracing the recorded rays on the triangle scene: per thread count,
/// (closest-hit, occlusion).
pub type StrataTimes = Vec<(usize, f64, f64)>;

/// Traces the recorded rays of `log` with Embree on the triangles of `shapes` (spheres
/// tessellated), compares hit by hit with Strata on the same triangles, and prints the table.
/// `strata_times` times Strata on the given hierarchy at a thread count, `runs` times, returning
/// the medians (closest-hit, occlusion seconds). False when the two sides disagree on whether
/// more than [`MAX_DISAGREEMENT`] of the rays hit: the export, not the tracing, would be wrong.
pub fn compare(
    root: &Path,
    shapes: &[Shape],
    log: &RayLog,
    thread_counts: &[usize],
    runs: usize,
    strata_times: impl Fn(&Accel, usize) -> Result<(f64, f64), String>,
) -> Result<bool, String> {
    let (shapes, spheres) = tessellated(shapes);
    let triangles = merged(&shapes)?;
    let accel = Accel::new(shapes);
    let target = root.join("target");
    let dir = target.join("raycast-limit");
    export(&dir, &triangles, &accel, log)?;
    let python = embree_python(&target)?;
    let strata: StrataTimes = thread_counts
        .iter()
        .map(|&t| strata_times(&accel, t).map(|(c, o)| (t, c, o)))
        .collect::<Result<_, _>>()?;
    let script = root.join("xtask").join("embree_trace.py");
    let threads_arg = thread_counts
        .iter()
        .map(usize::to_string)
        .collect::<Vec<_>>()
        .join(",");
    let output = Command::new(&python)
        .arg(&script)
        .arg(&dir)
        .args(["--threads", &threads_arg, "--runs", &runs.to_string()])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run {}: {e}", script.display()))?;
    if !output.status.success() {
        return Err(format!("{} failed ({})", script.display(), output.status));
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let result: Value = serde_json::from_str(stdout.lines().last().unwrap_or(""))
        .map_err(|e| format!("{}: unreadable result ({e}): {stdout}", script.display()))?;
    let (table, agree) = report(
        &result,
        &strata,
        (log.closest.len(), log.shadow.len()),
        triangles.indices.len(),
        spheres,
    )?;
    print!("{table}");
    println!("(rays and triangles in {})", dir.display());
    Ok(agree)
}

/// The largest fraction of closest-hit or of occlusion rays on which Embree and Strata may
/// disagree about a hit (edge hits, rounding): beyond it the comparison is reported as failed.
pub const MAX_DISAGREEMENT: f64 = 1e-3;

/// The comparison table from the script's JSON `result` and Strata's medians, and whether the
/// two sides agree on hits within [`MAX_DISAGREEMENT`].
/// `rays` counts the closest-hit and the occlusion rays.
fn report(
    result: &Value,
    strata: &StrataTimes,
    rays: (usize, usize),
    triangle_count: usize,
    spheres: usize,
) -> Result<(String, bool), String> {
    let number = |mode: &str, key: &str, threads: Option<usize>| -> Result<f64, String> {
        let mut v = &result["modes"][mode][key];
        if let Some(t) = threads {
            v = &v[t.to_string()];
        }
        v.as_f64()
            .ok_or_else(|| format!("embree_trace.py: no {mode}.{key} for {threads:?} threads"))
    };
    let (n, m) = (rays.0 as f64, rays.1 as f64);
    let mut out = String::new();
    let mut agree = true;
    let version = result["embree"].as_str().unwrap_or("?");
    let _ = writeln!(
        out,
        "Embree {version} (embreex) against Strata, the same rays through the same \
         {triangle_count} triangles{}",
        if spheres > 0 {
            format!(
                " ({spheres} spheres tessellated into {} triangles each, for both)",
                20 << (2 * SPHERE_SUBDIVISIONS)
            )
        } else {
            String::new()
        }
    );
    let _ = writeln!(
        out,
        "  Strata: Accel::intersect (hit completed with point and normals) / Accel::occluded \
         on a rayon pool;\n  Embree: rtcIntersect1 / rtcOccluded1 ray by ray in \
         EmbreeScene.run, one call on 1 thread, 65536-ray chunks on Python threads otherwise;\n  \
         both: tnear 0, recorded tfar, only the tracing timed (builds, export, Python start excluded)"
    );
    let _ = writeln!(
        out,
        "{:<12} {:>9} {:>7} {:>9} {:>9} {:>9}   {:>9} {:>9}",
        "M rays/s", "rays", "threads", "Strata", "Embree", "ratio", "Emb. fast", "ratio"
    );
    for (name, key, rays) in [
        ("closest-hit", "closest_seconds", n),
        ("occlusion", "occluded_seconds", m),
    ] {
        for &(threads, closest, occluded) in strata {
            let mine = if key == "closest_seconds" {
                closest
            } else {
                occluded
            };
            let robust = number("robust", key, Some(threads))?;
            let fast = number("fast", key, Some(threads))?;
            let _ = writeln!(
                out,
                "{name:<12} {rays:>9} {threads:>7} {:>9.2} {:>9.2} {:>9.2}   {:>9.2} {:>9.2}",
                rays / mine / 1e6,
                rays / robust / 1e6,
                robust / mine,
                rays / fast / 1e6,
                fast / mine,
            );
        }
    }
    let _ = writeln!(
        out,
        "ratio = Strata rays/s ÷ Embree rays/s (goal ≥ 0.8); Embree with RTC_SCENE_FLAG_ROBUST \
         (nearest to Strata's watertight test); Emb. fast = Embree's default flags"
    );
    for mode in ["robust", "fast"] {
        let disagree = &result["modes"][mode]["disagree"];
        let count = |key: &str| -> Result<u64, String> {
            disagree[key]
                .as_u64()
                .ok_or_else(|| format!("embree_trace.py: no {mode}.disagree.{key}"))
        };
        let fraction = |k: u64, of: f64| k as f64 / of.max(1.0);
        let (hit, tri, t, occ) = (
            count("closest_hit_miss")?,
            count("closest_triangle")?,
            count("closest_t")?,
            count("occluded")?,
        );
        agree &= fraction(hit, n) <= MAX_DISAGREEMENT && fraction(occ, m) <= MAX_DISAGREEMENT;
        let _ = writeln!(
            out,
            "Embree {mode:<6} vs Strata: hit/miss differs on {hit} closest-hit rays ({:.2e}), \
             triangle on {tri} ({:.2e}), t by > 1e-4 t + 1e-6 on {t} ({:.2e}); \
             occlusion differs on {occ} ({:.2e}); build {:.3} s (not timed)",
            fraction(hit, n),
            fraction(tri, n),
            fraction(t, n),
            fraction(occ, m),
            number(mode, "build_seconds", None)?,
        );
    }
    if !agree {
        let _ = writeln!(
            out,
            "FAILED: Embree and Strata disagree on more than {MAX_DISAGREEMENT:e} of the rays: \
             the exported triangles or rays are wrong"
        );
    }
    Ok((out, agree))
}

/// Medians of `runs` timings of `trace` (closest-hit and occlusion seconds).
pub fn median_times(runs: usize, mut trace: impl FnMut() -> (f64, f64)) -> (f64, f64) {
    let (closest, occluded): (Vec<f64>, Vec<f64>) = (0..runs).map(|_| trace()).unzip();
    (median(&closest), median(&occluded))
}

#[cfg(test)]
mod tests {
    use super::*;
    use geometry::{Ray, Sphere};
    use glam::{Mat3, Vec3};

    #[test]
    fn npy_matches_numpy_save_byte_for_byte() {
        // `numpy.save` (NumPy 2.4) of np.array([1.0, 2.0], dtype='<f4'): a 118-byte header.
        let mut expected = b"\x93NUMPY\x01\x00v\x00".to_vec();
        let mut header = "{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }".to_string();
        header.push_str(&" ".repeat(117 - header.len()));
        header.push('\n');
        expected.extend_from_slice(header.as_bytes());
        expected.extend_from_slice(b"\x00\x00\x80?\x00\x00\x00@");
        assert_eq!(npy(&[2], [1.0f32, 2.0]), expected);

        // np.zeros((1, 3), dtype='<u4'): the same header length, a two-axis shape.
        let bytes = npy(&[1, 3], [0u32; 3]);
        assert_eq!(bytes.len(), 128 + 12);
        assert_eq!(&bytes[8..10], b"v\x00");
        assert!(
            std::str::from_utf8(&bytes[10..128])
                .unwrap()
                .starts_with("{'descr': '<u4', 'fortran_order': False, 'shape': (1, 3), }  ")
        );
        assert_eq!(bytes[127], b'\n');
    }

    #[test]
    fn npy_headers_are_as_long_as_numpys() {
        // Header lengths (magic to newline) of `numpy.save` (NumPy 2.4) for `|u1` arrays of these
        // shapes; the last needs the room NumPy leaves for the first axis to grow.
        let mut sixteen_axes = vec![1];
        sixteen_axes.extend([0; 15]);
        for (shape, length) in [
            (vec![7, 3], 128),
            (vec![123_456_789, 0], 128),
            (vec![1_981_241], 128),
            (sixteen_axes, 192),
        ] {
            let count = shape.iter().product();
            let bytes = npy(&shape, std::iter::repeat_n(7u8, count));
            assert_eq!(bytes.len(), length + count, "{shape:?}");
            assert_eq!(
                usize::from(u16::from_le_bytes([bytes[8], bytes[9]])),
                length - 10
            );
            let header = std::str::from_utf8(&bytes[10..length]).unwrap();
            let dims = match shape.len() {
                1 => format!("({},)", shape[0]),
                _ => format!("{shape:?}").replace('[', "(").replace(']', ")"),
            };
            assert!(header.starts_with(&format!(
                "{{'descr': '|u1', 'fortran_order': False, 'shape': {dims}, }}"
            )));
            assert!(header.ends_with(" \n"));
            assert!(bytes[length..].iter().all(|&b| b == 7));
        }
    }

    fn sphere(center: Vec3, radius: f32) -> Shape {
        Shape::Sphere(Sphere {
            center,
            radius,
            flip_normals: false,
            to_local: Mat3::IDENTITY,
        })
    }

    fn quad(z: f32) -> Shape {
        Shape::Mesh(TriangleMesh {
            positions: vec![
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(1.0, -1.0, z),
                Vec3::new(1.0, 1.0, z),
                Vec3::new(-1.0, 1.0, z),
            ],
            normals: None,
            uvs: None,
            indices: vec![[0, 1, 2], [0, 2, 3]],
        })
    }

    #[test]
    fn spheres_become_icospheres_on_their_surface() {
        let center = Vec3::new(3.0, -2.0, 5.0);
        let (shapes, spheres) = tessellated(&[quad(0.0), sphere(center, 0.5)]);
        assert_eq!(spheres, 1);
        assert_eq!(shapes[0], quad(0.0));
        let Shape::Mesh(mesh) = &shapes[1] else {
            panic!("the sphere was not tessellated");
        };
        assert_eq!(mesh.indices.len(), 5120);
        for p in &mesh.positions {
            assert!(
                ((*p - center).length() - 0.5).abs() < 1e-5,
                "{p} off the sphere"
            );
        }
        // A ray at the centre hits the analytic sphere and its tessellation at nearly the same
        // distance: 10 - 0.5, less at most the icosphere's sagitta (below 1% of the radius).
        let ray = Ray::new(center + Vec3::new(0.0, 0.0, 10.0), Vec3::NEG_Z);
        let analytic = Accel::new(vec![sphere(center, 0.5)]).intersect(&ray, f32::INFINITY);
        let triangles = Accel::new(shapes).intersect(&ray, f32::INFINITY);
        assert!((analytic.unwrap().t - 9.5).abs() < 1e-4);
        let t = triangles.unwrap().t;
        assert!((9.5..9.505).contains(&t), "tessellated hit at {t}");
    }

    #[test]
    fn merged_offsets_indices_and_counts_first_triangles() {
        let (shapes, _) = tessellated(&[quad(0.0), sphere(Vec3::ZERO, 1.0), quad(2.0)]);
        let all = merged(&shapes).unwrap();
        assert_eq!(all.first, vec![0, 2, 5122]);
        assert_eq!(all.indices.len(), 5124);
        let sphere_vertices = all.positions.len() - 8;
        // The last quad's first triangle refers to its own vertices, after the sphere's.
        let base = (4 + sphere_vertices) as u32;
        assert_eq!(all.indices[5122], [base, base + 1, base + 2]);
        assert_eq!(all.positions[base as usize], [-1.0, -1.0, 2.0]);
        assert!(merged(&[sphere(Vec3::ZERO, 1.0)]).is_err());
    }

    fn script_result(closest_disagree: u64, occluded_disagree: u64) -> Value {
        let mode = serde_json::json!({
            "build_seconds": 0.01,
            "closest_seconds": {"1": 0.5, "2": 0.25},
            "occluded_seconds": {"1": 4.0, "2": 2.0},
            "disagree": {"closest_hit_miss": closest_disagree, "closest_triangle": 0,
                         "closest_t": 0, "occluded": occluded_disagree},
        });
        serde_json::json!({"embree": "4.4.0", "modes": {"robust": mode, "fast": mode}})
    }

    #[test]
    fn report_divides_strata_rays_per_second_by_embrees() {
        // A million closest-hit rays: Strata 1 s on one thread (1 M rays/s), Embree 0.5 s (2 M):
        // ratio 0.5. Two million occlusion rays: Strata 1 s (2 M), Embree 4 s (0.5 M): ratio 4.
        let strata = vec![(1, 1.0, 1.0), (2, 1.0, 0.5)];
        let (table, agree) =
            report(&script_result(0, 0), &strata, (1_000_000, 2_000_000), 36, 0).unwrap();
        assert!(agree, "{table}");
        let row = |name: &str, threads: &str| -> Vec<String> {
            table
                .lines()
                .find(|l| {
                    let w: Vec<_> = l.split_whitespace().collect();
                    w.first() == Some(&name) && w.get(2) == Some(&threads)
                })
                .unwrap_or_else(|| panic!("no {name} row for {threads} threads in\n{table}"))
                .split_whitespace()
                .map(str::to_string)
                .collect()
        };
        assert_eq!(row("closest-hit", "1")[3..6], ["1.00", "2.00", "0.50"]);
        assert_eq!(row("closest-hit", "2")[3..6], ["1.00", "4.00", "0.25"]);
        assert_eq!(row("occlusion", "1")[3..6], ["2.00", "0.50", "4.00"]);
        assert_eq!(row("occlusion", "2")[3..6], ["4.00", "1.00", "4.00"]);
        assert!(!table.contains("spheres"));
    }

    #[test]
    fn report_fails_when_more_than_a_thousandth_of_the_rays_disagree() {
        let strata = vec![(1, 1.0, 1.0)];
        let check = |closest, occluded| {
            report(
                &script_result(closest, occluded),
                &strata,
                (1000, 2000),
                36,
                1,
            )
            .unwrap()
        };
        assert!(check(1, 2).1);
        let (table, agree) = check(2, 0);
        assert!(!agree && table.contains("FAILED"), "{table}");
        assert!(!check(0, 3).1);
        assert!(
            check(0, 0)
                .0
                .contains("1 spheres tessellated into 5120 triangles each")
        );
    }

    #[test]
    fn report_refuses_a_result_without_a_thread_count() {
        let strata = vec![(4, 1.0, 1.0)];
        assert!(report(&script_result(0, 0), &strata, (1000, 2000), 36, 0).is_err());
    }
}
