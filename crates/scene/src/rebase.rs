//! Camera-relative world space: the scene is translated so that the camera sits at the origin
//! before anything is built from it.
//!
//! Radiance does not change under a translation of the whole scene, but single-precision
//! arithmetic does: 1e5 units from the origin, `f32` positions are 0.008 apart, and every bound
//! on intersection and offset error grows with the coordinates. Measured from the camera, the
//! coordinates of everything the camera sees well are as small as the scene allows, so a scene
//! far from the origin renders like the same scene at the origin.
//!
//! The loader already places everything relative to the camera, in double precision (see
//! [`crate::SceneDesc`]); this pass moves what a description built by hand still has in world
//! space, in `f32`.

use crate::desc::{EmitterDesc, Geometry, SceneDesc};
use glam::{Mat4, Vec3};

/// Translates every position of `desc` (mesh vertices, sphere centres, point and spot lights and the
/// sensor) by minus the translation of the sensor's `to_world`, which moves into its `position`.
pub(crate) fn camera_relative(desc: &mut SceneDesc) {
    let offset = desc.sensor.to_world.w_axis.truncate();
    if offset == Vec3::ZERO || !offset.is_finite() {
        return;
    }
    desc.sensor.position += offset.as_dvec3();
    desc.sensor.to_world = Mat4::from_translation(-offset) * desc.sensor.to_world;
    desc.sensor.to_world.w_axis = glam::Vec4::W;
    if let Some(motion) = &mut desc.sensor.motion {
        *motion = motion.translated(-offset.as_dvec3());
    }
    for shape in &mut desc.shapes {
        if let Some(motion) = &mut shape.motion {
            // Its geometry is in object space: the motion moves instead.
            *motion = motion.translated(-offset.as_dvec3());
            continue;
        }
        match &mut shape.geometry {
            Geometry::Mesh(mesh) => mesh.positions.iter_mut().for_each(|p| *p -= offset),
            Geometry::Sphere(sphere) => sphere.center -= offset,
        }
    }
    for position in desc
        .emitters
        .iter_mut()
        .filter_map(EmitterDesc::position_mut)
    {
        *position -= offset;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn everything_moves_with_the_camera_and_directions_do_not() {
        let xml = r#"<scene version="3.0.0"><integrator type="path"/>
            <sensor type="perspective"><transform name="to_world">
                <rotate y="1" angle="30"/><translate x="1e5" y="-2" z="3"/></transform></sensor>
            <shape type="sphere"><point name="center" value="1e5, 0, 3"/></shape>
            <shape type="rectangle"><transform name="to_world">
                <translate x="1e5" y="-2" z="3"/></transform></shape>
            <emitter type="point"><point name="position" value="1e5, -2, 4"/></emitter>
        </scene>"#;
        let path = std::env::temp_dir().join(format!("strata-rebase-{}.xml", std::process::id()));
        std::fs::write(&path, xml).expect("temporary scene file");
        let mut desc = crate::parse_file(&path, &[]).expect("a valid scene");
        let _ = std::fs::remove_file(&path);
        let rotation = desc.sensor.to_world.x_axis;
        let loaded = desc.clone();
        camera_relative(&mut desc);
        assert_eq!(desc, loaded, "the loader centres the scene on the camera");
        // As if built by hand in world space: the camera's translation back in its to_world,
        // every position in world space.
        let position = desc.sensor.position.as_vec3();
        desc.sensor.to_world.w_axis = position.extend(1.0);
        desc.sensor.position = glam::DVec3::ZERO;
        for shape in &mut desc.shapes {
            match &mut shape.geometry {
                Geometry::Mesh(mesh) => mesh.positions.iter_mut().for_each(|p| *p += position),
                Geometry::Sphere(sphere) => sphere.center += position,
            }
        }
        if let EmitterDesc::Point { position: p, .. } = &mut desc.emitters[0] {
            *p += position;
        }
        camera_relative(&mut desc);
        assert_eq!(desc.sensor.position, glam::DVec3::new(1e5, -2.0, 3.0));
        assert_eq!(desc.sensor.to_world.w_axis, glam::Vec4::W);
        assert_eq!(
            desc.sensor.to_world.x_axis, rotation,
            "directions are unchanged"
        );
        let Geometry::Sphere(sphere) = &desc.shapes[0].geometry else {
            panic!("a sphere")
        };
        assert_eq!(sphere.center, Vec3::new(0.0, 2.0, 0.0));
        let Geometry::Mesh(mesh) = &desc.shapes[1].geometry else {
            panic!("a mesh")
        };
        assert!(
            mesh.positions
                .iter()
                .all(|p| p.z == 0.0 && p.x.abs() == 1.0 && p.y.abs() == 1.0)
        );
        let EmitterDesc::Point { position, .. } = desc.emitters[0] else {
            panic!("a point light")
        };
        assert_eq!(position, Vec3::Z);
    }
}
