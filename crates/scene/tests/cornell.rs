//! The Cornell-box fixture: counts, hand-computed transforms, references and settings.

mod common;

use common::{close, data_dir, triangle_normal};
use glam::{Vec2, Vec3};
use scene::{
    BsdfDesc, EmitterDesc, FilterDesc, FovAxis, Geometry, IntegratorPreset, MeshDesc,
    MicrofacetDistribution, Roughness, SceneDesc, ShapeDesc,
};

/// The fixture as loaded: relative to its camera at (0, 1, 6.8).
fn cornell_from_camera() -> SceneDesc {
    scene::parse_file(&data_dir().join("cornell.xml"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// The fixture with its positions moved back to world space (by the camera's position), where
/// the hand computations below are made.
fn cornell() -> SceneDesc {
    let mut desc = cornell_from_camera();
    let camera = desc.sensor.position.as_vec3();
    for shape in &mut desc.shapes {
        match &mut shape.geometry {
            Geometry::Mesh(mesh) => mesh.positions.iter_mut().for_each(|p| *p += camera),
            Geometry::Sphere(sphere) => sphere.center += camera,
        }
    }
    for emitter in &mut desc.emitters {
        if let EmitterDesc::Point { position, .. } = emitter {
            *position += camera;
        }
    }
    desc
}

#[test]
fn positions_are_relative_to_the_camera() {
    let desc = cornell_from_camera();
    assert_eq!(desc.sensor.position, glam::DVec3::new(0.0, 1.0, 6.8));
    assert_eq!(desc.sensor.to_world.w_axis, glam::Vec4::W);
    // The floor's corner (3, 0, −3) in world space; 6.8 and 9.8 are not exact in binary, so
    // the subtraction in double precision is what makes these the nearest floats.
    let floor = mesh(&desc, "floor");
    assert!(
        floor
            .positions
            .contains(&Vec3::new(3.0, -1.0, (-3.0_f64 - 6.8) as f32)),
        "{:?}",
        floor.positions
    );
    let EmitterDesc::Point { position, .. } = desc.emitters[0] else {
        panic!("a point light")
    };
    assert_eq!(position, Vec3::new(0.0, 0.5, (1.0_f64 - 6.8) as f32));
}

fn shape<'a>(desc: &'a SceneDesc, id: &str) -> &'a ShapeDesc {
    desc.shapes
        .iter()
        .find(|s| s.id.as_deref() == Some(id))
        .unwrap_or_else(|| panic!("no shape {id}"))
}

fn mesh<'a>(desc: &'a SceneDesc, id: &str) -> &'a MeshDesc {
    match &shape(desc, id).geometry {
        Geometry::Mesh(mesh) => mesh,
        other => panic!("{id} is not a mesh: {other:?}"),
    }
}

#[test]
fn counts_shapes_and_triangles() {
    let desc = cornell();
    assert_eq!(desc.shapes.len(), 10);
    let triangles: usize = desc
        .shapes
        .iter()
        .filter_map(|s| match &s.geometry {
            Geometry::Mesh(m) => Some(m.triangles.len()),
            Geometry::Sphere(_) => None,
        })
        .sum();
    // 5 rectangles × 2 + cube 12 + OBJ box of 6 quads 12 + PLY quad and triangle 3 + disk 128.
    assert_eq!(triangles, 10 + 12 + 12 + 3 + 128);
    assert_eq!(desc.emitters.len(), 1);
    assert_eq!(
        desc.shapes.iter().filter(|s| s.emitter.is_some()).count(),
        1
    );
}

#[test]
fn floor_transform_matches_hand_computation() {
    let desc = cornell();
    let floor = mesh(&desc, "floor");
    // (1, 1, 0) → scale (2, 3, 1) → (2, 3, 0) → rotate −90° about x: (x, z, −y) = (2, 0, −3)
    // → translate x + 1 → (3, 0, −3); likewise for the other corners.
    let expected = [
        Vec3::new(3.0, 0.0, -3.0),
        Vec3::new(3.0, 0.0, 3.0),
        Vec3::new(-1.0, 0.0, -3.0),
        Vec3::new(-1.0, 0.0, 3.0),
    ];
    assert_eq!(floor.positions.len(), 4);
    for e in expected {
        assert!(
            floor.positions.iter().any(|p| close(*p, e, 1e-5)),
            "{e} missing from {:?}",
            floor.positions
        );
    }
    for i in 0..floor.triangles.len() {
        assert!(close(triangle_normal(floor, i), Vec3::Y, 1e-5));
    }
    assert!(floor.normals.is_none());
    assert_eq!(floor.uvs.as_ref().map(Vec::len), Some(4));
}

#[test]
fn light_faces_down_and_carries_its_radiance() {
    let desc = cornell();
    let light = shape(&desc, "light");
    let Geometry::Mesh(m) = &light.geometry else {
        panic!()
    };
    for p in &m.positions {
        assert!(close(p.abs(), Vec3::new(0.25, 1.99, 0.25), 1e-5), "{p}");
    }
    assert!(close(triangle_normal(m, 0), -Vec3::Y, 1e-5));
    assert_eq!(light.emitter.unwrap().radiance, Vec3::new(17.0, 12.0, 4.0));
    assert_eq!(
        desc.bsdfs[light.bsdf],
        BsdfDesc::Diffuse {
            reflectance: Vec3::ZERO
        }
    );
}

#[test]
fn obj_box_under_a_matrix_with_face_normals() {
    let desc = cornell();
    let tall = mesh(&desc, "tall_box");
    // Row-major matrix: scale (0.6, 1.2, 0.6) then translate (−0.7, 0, −0.5).
    assert!(
        tall.positions
            .iter()
            .any(|p| close(*p, Vec3::new(-0.1, 1.2, 0.1), 1e-5))
    );
    assert!(
        tall.positions
            .iter()
            .any(|p| close(*p, Vec3::new(-0.7, 0.0, -0.5), 1e-5))
    );
    assert!(tall.normals.is_none(), "face_normals drops vertex normals");
    // Every face points away from the box centre.
    let centre = Vec3::new(-0.4, 0.6, -0.2);
    for i in 0..tall.triangles.len() {
        let a = tall.positions[tall.triangles[i][0] as usize];
        assert!(triangle_normal(tall, i).dot(a - centre) > 0.0);
    }
}

#[test]
fn short_box_cube_is_outward_and_scaled() {
    let desc = cornell();
    let cube = mesh(&desc, "short_box");
    let centre = Vec3::new(0.3, 0.3, 0.4);
    for p in &cube.positions {
        assert!(close((*p - centre).abs(), Vec3::splat(0.3), 1e-6));
    }
    for i in 0..cube.triangles.len() {
        let a = cube.positions[cube.triangles[i][0] as usize];
        assert!(triangle_normal(cube, i).dot(a - centre) > 0.0);
    }
}

#[test]
fn sphere_is_placed_in_world_space() {
    let desc = cornell();
    let ball = shape(&desc, "ball");
    let Geometry::Sphere(s) = ball.geometry else {
        panic!()
    };
    // translate(−1, 0, 0) · scale(2) applied to centre (0.5, 0.4, 1), radius 0.2.
    assert!(close(s.center, Vec3::new(0.0, 0.8, 2.0), 1e-6));
    assert!((s.radius - 0.4).abs() < 1e-6);
    assert!(!s.flip_normals);
    assert_eq!(
        desc.bsdfs[ball.bsdf],
        BsdfDesc::Dielectric {
            int_ior: 1.333,
            ext_ior: 1.0,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE
        }
    );
}

#[test]
fn references_share_table_entries() {
    let desc = cornell();
    let white = shape(&desc, "floor").bsdf;
    assert_eq!(shape(&desc, "ceiling").bsdf, white);
    assert_eq!(shape(&desc, "short_box").bsdf, white);
    assert_eq!(
        desc.bsdfs[white],
        BsdfDesc::Diffuse {
            reflectance: Vec3::new(0.725, 0.71, 0.68)
        }
    );
    let green = BsdfDesc::Diffuse {
        reflectance: Vec3::splat(0.3),
    };
    assert_eq!(
        desc.bsdfs[shape(&desc, "right").bsdf],
        BsdfDesc::TwoSided {
            front: Box::new(green.clone()),
            back: Box::new(green.clone())
        }
    );
    // The forward-referenced "green" is stored once even though it is also declared at top level.
    assert_eq!(desc.bsdfs.iter().filter(|b| **b == green).count(), 1);
    assert_eq!(desc.bsdfs.len(), 8);
}

#[test]
fn ply_mesh_and_its_rough_conductor() {
    let desc = cornell();
    let quads = shape(&desc, "quads");
    let Geometry::Mesh(m) = &quads.geometry else {
        panic!()
    };
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]]);
    assert_eq!(m.normals.as_ref().unwrap()[4], Vec3::Z);
    assert_eq!(m.uvs.as_ref().unwrap()[4], Vec2::new(0.5, 0.5));
    assert_eq!(
        desc.bsdfs[quads.bsdf],
        BsdfDesc::RoughConductor {
            distribution: MicrofacetDistribution::Ggx,
            alpha: Roughness::isotropic(0.2),
            eta: Vec3::new(0.2, 0.9, 1.1),
            k: Vec3::new(3.9, 2.4, 2.2),
            specular_reflectance: Vec3::ONE
        }
    );
}

#[test]
fn flipped_disk_faces_down_with_a_mirror() {
    let desc = cornell();
    let disk = desc.shapes.iter().find(|s| s.plugin == "disk").unwrap();
    let Geometry::Mesh(m) = &disk.geometry else {
        panic!()
    };
    for i in 0..m.triangles.len() {
        assert!(close(triangle_normal(m, i), -Vec3::Z, 1e-5));
    }
    assert_eq!(
        desc.bsdfs[disk.bsdf],
        BsdfDesc::Conductor {
            eta: Vec3::ZERO,
            k: Vec3::ONE,
            specular_reflectance: Vec3::ONE
        }
    );
}

#[test]
fn render_settings() {
    let desc = cornell();
    assert_eq!(desc.integrator.preset, IntegratorPreset::Auto);
    assert_eq!(desc.integrator.direct, None);
    assert_eq!(desc.integrator.max_depth, 8);
    assert_eq!(desc.integrator.rr_depth, 3);
    assert!(!desc.integrator.hide_emitters);
    assert_eq!((desc.film.width, desc.film.height), (128, 96));
    assert_eq!(desc.film.filter, FilterDesc::Tent { radius: 1.5 });
    assert_eq!(desc.sampler.kind, Some(sampling::SamplerKind::Stratified));
    assert_eq!(desc.sampler.sample_count, 16);
    assert_eq!(desc.sampler.seed, 7);
    assert_eq!(desc.sensor.fov_axis, FovAxis::Smaller);
    assert!((desc.sensor.fov_deg - 39.3077).abs() < 1e-5);
    // Smaller axis of a 128×96 image is y: x_fov = 2 atan(tan(39.3077°/2) · 4/3) = 50.92675°.
    assert!((desc.sensor.x_fov_deg(128, 96) - 50.92675).abs() < 1e-3);
    let m = desc.sensor.to_world;
    assert_eq!(m.transform_point3(Vec3::ZERO), Vec3::ZERO);
    assert_eq!(desc.sensor.position, glam::DVec3::new(0.0, 1.0, 6.8));
    assert!(close(m.transform_vector3(Vec3::Z), -Vec3::Z, 1e-6));
    assert!(close(m.transform_vector3(Vec3::X), -Vec3::X, 1e-6));
    assert!(desc.sensor.lens.is_none());
    assert_eq!(
        desc.emitters[0],
        EmitterDesc::Point {
            position: Vec3::new(0.0, 1.5, 1.0),
            intensity: Vec3::splat(2.0),
            sampling_weight: 1.0
        }
    );
}

#[test]
fn overrides_beat_defaults_and_reach_type_attributes() {
    let path = data_dir().join("cornell.xml");
    let overrides = vec![
        ("spp".to_string(), "64".to_string()),
        ("res".to_string(), "200".to_string()),
    ];
    let desc = scene::parse_file(&path, &overrides).unwrap();
    assert_eq!(desc.sampler.sample_count, 64);
    assert_eq!(desc.film.width, 200);

    // `$wall` sits in a type attribute: switching the plugin makes its reflectance unsupported.
    let overrides = vec![("wall".to_string(), "dielectric".to_string())];
    let err = scene::parse_file(&path, &overrides).unwrap_err();
    assert!(
        err.message
            .contains("unsupported parameter \"reflectance\""),
        "{err}"
    );
    assert!(
        err.message
            .contains("<bsdf type=\"dielectric\" id=\"white\">"),
        "{err}"
    );
    assert_eq!(err.line, 34);

    let overrides = vec![("unused_name".to_string(), "1".to_string())];
    let err = scene::parse_file(&path, &overrides).unwrap_err();
    assert!(err.message.contains("unused_name"), "{err}");

    // Two values for one name: neither may win silently.
    let overrides = vec![
        ("spp".to_string(), "64".to_string()),
        ("spp".to_string(), "16".to_string()),
    ];
    let err = scene::parse_file(&path, &overrides).unwrap_err();
    assert!(
        err.message.contains("spp=64") && err.message.contains("spp=16"),
        "{err}"
    );
}
