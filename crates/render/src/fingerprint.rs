//! A fingerprint of a scene's content, which a saved render state records so that it is only
//! resumed for the same scene, and every rendered EXR records so that `strata merge` only adds up
//! renders of the same scene.

use std::fmt::{self, Write};

use scene::SceneDesc;

/// A fingerprint of everything in `desc` that decides the image, as 16 hex digits: the FNV-1a
/// hash of its integrator, sensor, film, sampler, shapes (with the vertices read from the mesh
/// files the scene names), BSDFs (with the texels of their bitmap textures) and emitters (with
/// an environment map's texels), written out exactly (floats as the shortest decimal that reads
/// back to the same value). The description holds what included files add, so they count too.
/// Where the scene file lies is left out, so a moved scene still matches; a changed mesh,
/// texture or included file does not.
pub fn scene_fingerprint(desc: &SceneDesc) -> String {
    let SceneDesc {
        source: _,
        integrator,
        sensor,
        film,
        sampler,
        shapes,
        bsdfs,
        emitters,
    } = desc;
    let mut hash = Fnv1a::new();
    write!(
        hash,
        "{integrator:?}\n{sensor:?}\n{film:?}\n{sampler:?}\n{shapes:?}\n{bsdfs:?}\n{emitters:?}"
    )
    .expect("hashing does not fail");
    hash.hex()
}

/// The 64-bit FNV-1a hash of the text written to it.
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }

    fn hex(&self) -> String {
        format!("{:016x}", self.0)
    }
}

impl fmt::Write for Fnv1a {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        for &b in text.as_bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fnv1a_hex(text: &str) -> String {
        let mut hash = Fnv1a::new();
        hash.write_str(text).unwrap();
        hash.hex()
    }

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        assert_eq!(fnv1a_hex(""), "cbf29ce484222325");
        assert_eq!(fnv1a_hex("a"), "af63dc4c8601ec8c");
        assert_eq!(fnv1a_hex("foobar"), "85944171f73967e8");
    }

    #[test]
    fn the_fingerprint_follows_content_not_place() {
        let xml = r#"<scene version="3.0.0"><integrator type="path"/><sensor type="perspective"/>
            <shape type="rectangle"/></scene>"#;
        let desc = scene::parse_bytes(xml.as_bytes(), std::path::Path::new("a/s.xml"), &[])
            .expect("a valid scene");
        let mut moved = desc.clone();
        moved.source = "elsewhere/s.xml".into();
        assert_eq!(scene_fingerprint(&desc), scene_fingerprint(&moved));
        let mut nudged = desc.clone();
        let scene::Geometry::Mesh(mesh) = &mut nudged.shapes[0].geometry else {
            panic!("a rectangle is a mesh")
        };
        mesh.positions[2].z = f32::from_bits(mesh.positions[2].z.to_bits() + 1);
        assert_ne!(scene_fingerprint(&desc), scene_fingerprint(&nudged));
    }
}
