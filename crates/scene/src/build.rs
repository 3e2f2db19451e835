//! Turns a [`SceneDesc`] into the runtime objects that render it: the [`World`] and the
//! [`Camera`].

use crate::camera::Camera;
use crate::features::SceneFeatures;
use crate::plugins::texture::affine_to_uv;
use crate::{
    BsdfDesc, Geometry, LoadError, MicrofacetDistribution, Roughness, SceneDesc, ShapeDesc,
};
use geometry::{Aabb, Accel, Motion, Shape, Sphere, TriangleMesh};
use lights::{Light, MeshAreaLight, MovingLight, SphereAreaLight};
use materials::{
    Blend, Bsdf, ComplexIor, Conductor, Dielectric, Diffuse, Microfacet, MicrofacetKind, Plastic,
    RoughConductor, RoughDielectric, RoughPlastic, ThinDielectric, TwoSided,
};
use world::{Checkerboard, MaterialTexture, World};

/// A scene ready to render: what light transport needs, the camera, and the description's
/// render settings (film, sampler, integrator).
pub struct RenderScene {
    /// Geometry, materials and lights.
    pub world: World,
    /// The camera, sized for `desc.film`.
    pub camera: Camera,
    /// What the scene contains, for choosing techniques.
    pub features: SceneFeatures,
    /// The description it was built from (film, sampler and integrator settings).
    pub desc: SceneDesc,
}

/// Builds the runtime scene from `desc`, in camera-relative world space (see the `rebase` module:
/// the returned `desc` has every position translated by minus the camera's). Errors name the
/// scene file and the shape or BSDF that cannot be built.
pub fn build(mut desc: SceneDesc) -> Result<RenderScene, LoadError> {
    crate::rebase::camera_relative(&mut desc);
    let error = |element: String, message: String| LoadError {
        file: desc.source.clone(),
        line: 0,
        column: 0,
        element,
        message,
    };
    let mut materials = desc
        .bsdfs
        .iter()
        .enumerate()
        .map(|(i, b)| build_bsdf(b).map_err(|m| error(format!("bsdf #{i}"), m)))
        .collect::<Result<Vec<_>, _>>()?;
    // A checkerboard's material is its even BSDF; its odd one goes after the scene's own. A
    // bitmap's material is its base.
    let mut textures = vec![None; materials.len()];
    for (i, bsdf) in desc.bsdfs.iter().enumerate() {
        match bsdf {
            BsdfDesc::Checkerboard { odd, to_uv, .. } => {
                textures[i] = Some(MaterialTexture::Checkerboard(Checkerboard {
                    to_uv: affine_to_uv(to_uv),
                    odd: materials.len() as u32,
                }));
                materials.push(build_bsdf(odd).map_err(|m| error(format!("bsdf #{i}"), m))?);
            }
            BsdfDesc::DiffuseBitmap { texture, .. } => {
                textures[i] = Some(MaterialTexture::DiffuseReflectance(texture.clone()));
            }
            BsdfDesc::TexturedBlend {
                weight,
                reflectances,
                ..
            } => {
                textures[i] = Some(MaterialTexture::Blend {
                    weight: weight.clone(),
                    reflectances: reflectances.clone(),
                });
            }
            _ => {}
        }
    }
    textures.resize(materials.len(), None);

    let mut shapes = Vec::with_capacity(desc.shapes.len());
    let mut moving = Vec::new();
    let mut shape_material = Vec::with_capacity(desc.shapes.len());
    let mut shape_light = Vec::with_capacity(desc.shapes.len());
    let mut lights = Vec::new();
    let mut light_weights = Vec::new();
    // Static shapes first, then the moving ones (the order the acceleration structure numbers
    // them in).
    let (fixed, animated): (Vec<&ShapeDesc>, Vec<&ShapeDesc>) =
        desc.shapes.iter().partition(|shape| shape.motion.is_none());
    for shape in fixed.into_iter().chain(animated) {
        let motion = shape
            .motion
            .as_ref()
            .map(|m| Motion::new(m.clone(), desc.sensor.shutter));
        let light = shape
            .emitter
            .and_then(|emitter| Some((area_light(shape, emitter.radiance)?, emitter)));
        let light = match (light, &motion) {
            (Some((light, emitter)), Some(motion)) => {
                let bounds = object_bounds(&shape.geometry);
                MovingLight::new(light, motion.clone(), &bounds)
                    .map(|light| (Light::Moving(light), emitter))
            }
            (light, _) => light,
        };
        if let Some((light, emitter)) = light {
            shape_light.push(Some(lights.len() as u32));
            lights.push(light);
            light_weights.push(emitter.sampling_weight);
        } else {
            shape_light.push(None);
        }
        shape_material.push(shape.bsdf as u32);
        match motion {
            Some(motion) => moving.push((runtime_shape(shape), motion)),
            None => shapes.push(runtime_shape(shape)),
        }
    }
    let accel = Accel::with_moving(shapes, moving);
    let accel_has_motion = accel.has_motion();
    let bounds = accel.bounds();
    let scene_radius = if bounds.min.is_finite() && bounds.max.is_finite() {
        0.5 * (bounds.max - bounds.min).length()
    } else {
        1.0
    };
    for emitter in &desc.emitters {
        lights.push(
            crate::plugins::emitter::scene_light(emitter, scene_radius)
                .map_err(|m| error("scene".to_string(), m))?,
        );
        light_weights.push(emitter.sampling_weight());
    }
    let camera = camera(&desc);
    let features = SceneFeatures::of(&materials, &lights, accel_has_motion || camera.moves());
    let mut world = World::new(
        accel,
        materials,
        shape_material,
        shape_light,
        lights,
        light_weights,
    )
    .map_err(|m| error("scene".to_string(), m))?;
    world
        .set_textures(textures)
        .map_err(|m| error("scene".to_string(), m))?;
    Ok(RenderScene {
        world,
        camera,
        features,
        desc,
    })
}

/// The camera for the description's sensor and film.
fn camera(desc: &SceneDesc) -> Camera {
    let [width, height] = desc.film.full_size;
    Camera::new(&desc.sensor, width, height).cropped(
        glam::UVec2::from_array(desc.film.crop_offset),
        glam::UVec2::new(desc.film.width, desc.film.height),
    )
}

fn runtime_shape(shape: &ShapeDesc) -> Shape {
    match &shape.geometry {
        Geometry::Mesh(mesh) => Shape::Mesh(TriangleMesh {
            positions: mesh.positions.clone(),
            normals: mesh.normals.clone(),
            uvs: mesh.uvs.clone(),
            indices: mesh.triangles.clone(),
        }),
        Geometry::Sphere(s) => Shape::Sphere(Sphere {
            center: s.center,
            radius: s.radius,
            flip_normals: s.flip_normals,
            to_local: s.to_local,
        }),
    }
}

/// The bounds of `geometry` in its own space (world units).
fn object_bounds(geometry: &Geometry) -> Aabb {
    match geometry {
        Geometry::Mesh(mesh) => Aabb::from_points(mesh.positions.iter().copied()),
        Geometry::Sphere(s) => Aabb::new(
            s.center - glam::Vec3::splat(s.radius),
            s.center + glam::Vec3::splat(s.radius),
        ),
    }
}

/// The area light on `shape`, `None` when the shape has no area (it could never be seen).
fn area_light(shape: &ShapeDesc, radiance: glam::Vec3) -> Option<Light> {
    match &shape.geometry {
        Geometry::Mesh(mesh) => {
            let triangles = mesh
                .triangles
                .iter()
                .map(|t| t.map(|i| mesh.positions[i as usize]))
                .collect();
            MeshAreaLight::new(triangles, radiance).map(Light::Mesh)
        }
        Geometry::Sphere(s) => Some(Light::Sphere(SphereAreaLight {
            center: s.center,
            radius: s.radius,
            flip_normals: s.flip_normals,
            radiance,
        })),
    }
}

/// The microfacet distribution of a rough BSDF, or why it cannot be built.
fn microfacet(
    distribution: MicrofacetDistribution,
    alpha: Roughness,
) -> Result<Microfacet, String> {
    let kind = match distribution {
        MicrofacetDistribution::Beckmann => MicrofacetKind::Beckmann,
        MicrofacetDistribution::Ggx => MicrofacetKind::Ggx,
    };
    Microfacet::anisotropic(kind, alpha.u, alpha.v).map_err(|e| e.to_string())
}

/// The renderer's BSDF for `desc`, or why it cannot be built.
pub(crate) fn build_bsdf(desc: &BsdfDesc) -> Result<Bsdf, String> {
    Ok(match desc {
        BsdfDesc::Diffuse { reflectance } => Diffuse::new(*reflectance).into(),
        BsdfDesc::Conductor {
            eta,
            k,
            specular_reflectance,
        } => Conductor::new(ComplexIor::new(*eta, *k), *specular_reflectance).into(),
        BsdfDesc::RoughConductor {
            distribution,
            alpha,
            eta,
            k,
            specular_reflectance,
        } => RoughConductor::new(
            microfacet(*distribution, *alpha)?,
            ComplexIor::new(*eta, *k),
            *specular_reflectance,
        )
        .into(),
        BsdfDesc::RoughDielectric {
            distribution,
            alpha,
            int_ior,
            ext_ior,
            specular_reflectance,
            specular_transmittance,
        } => RoughDielectric::new(
            microfacet(*distribution, *alpha)?,
            *int_ior,
            *ext_ior,
            *specular_reflectance,
            *specular_transmittance,
        )
        .map_err(|e| e.to_string())?
        .into(),
        BsdfDesc::Dielectric {
            int_ior,
            ext_ior,
            specular_reflectance,
            specular_transmittance,
        } => Dielectric::new(
            *int_ior,
            *ext_ior,
            *specular_reflectance,
            *specular_transmittance,
        )
        .map_err(|e| e.to_string())?
        .into(),
        BsdfDesc::ThinDielectric {
            int_ior,
            ext_ior,
            specular_reflectance,
            specular_transmittance,
        } => ThinDielectric::new(
            *int_ior,
            *ext_ior,
            *specular_reflectance,
            *specular_transmittance,
        )
        .map_err(|e| e.to_string())?
        .into(),
        BsdfDesc::Plastic {
            int_ior,
            ext_ior,
            diffuse_reflectance,
            specular_reflectance,
            nonlinear,
        } => Plastic::new(
            *int_ior,
            *ext_ior,
            *diffuse_reflectance,
            *specular_reflectance,
            *nonlinear,
        )
        .map_err(|e| e.to_string())?
        .into(),
        BsdfDesc::RoughPlastic {
            distribution,
            alpha,
            int_ior,
            ext_ior,
            diffuse_reflectance,
            specular_reflectance,
            nonlinear,
        } => RoughPlastic::new(
            microfacet(*distribution, Roughness::isotropic(*alpha))?,
            *int_ior,
            *ext_ior,
            *diffuse_reflectance,
            *specular_reflectance,
            *nonlinear,
        )
        .map_err(|e| e.to_string())?
        .into(),
        BsdfDesc::Blend {
            first,
            second,
            weight,
        } => Blend::new(build_bsdf(first)?, build_bsdf(second)?, *weight)
            .map_err(|e| e.to_string())?
            .into(),
        // Building it checks both; the scene takes the even one as the material itself.
        BsdfDesc::Checkerboard { even, odd, .. } => {
            build_bsdf(odd)?;
            build_bsdf(even)?
        }
        BsdfDesc::DiffuseBitmap { base, .. } | BsdfDesc::TexturedBlend { base, .. } => {
            build_bsdf(base)?
        }
        BsdfDesc::Built(bsdf) => bsdf.clone(),
        BsdfDesc::TwoSided { front, back } => Bsdf::TwoSided(
            TwoSided::with_sides(build_bsdf(front)?, build_bsdf(back)?)
                .map_err(|e| e.to_string())?,
        ),
    })
}
