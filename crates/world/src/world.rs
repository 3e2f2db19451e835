//! Everything light transport needs to know about a scene: geometry, materials and emitters,
//! in flat arrays indexed by shape.

use crate::{CameraRay, RayTally};
use geometry::{Accel, Hit, Ray, SpawnPoint};
use glam::{Affine2, Vec3, Vec3A};
use lights::{Light, LightSample};
use materials::{BitmapTexture, Bsdf, BsdfFlags, SurfacePoint};
use sampling::Frame;
use std::sync::Arc;

/// Index into [`World::materials`].
pub type MaterialId = u32;

/// A material whose one textured parameter is Mitsuba's `checkerboard`: two BSDFs, the
/// material's own where the pattern shows `color0` and `odd` where it shows `color1`. With
/// (u, v) = `to_uv` applied to the hit's surface coordinates, `odd` is chosen where exactly one
/// of the fractional parts of u and v exceeds ½.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checkerboard {
    /// Transformation of the surface coordinates before the pattern (Mitsuba's `to_uv`).
    pub to_uv: Affine2,
    /// The material of the `color1` squares.
    pub odd: MaterialId,
}

impl Checkerboard {
    /// Whether the surface coordinates `uv` fall on a `color1` square.
    #[inline]
    pub fn is_odd(&self, uv: glam::Vec2) -> bool {
        let uv = self.to_uv.transform_point2(uv);
        let fraction = uv - uv.floor();
        (fraction.x > 0.5) != (fraction.y > 0.5)
    }
}

/// A material's textured parameter: how the BSDF a hit sees depends on the surface coordinates.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialTexture {
    /// The material's BSDF on even squares and another material's on odd ones.
    Checkerboard(Checkerboard),
    /// The diffuse albedo ([`Bsdf::with_diffuse_reflectance`]) of the BSDF the hit sees is the
    /// bitmap's value there.
    DiffuseReflectance(Arc<BitmapTexture>),
    /// The blend the hit sees takes bitmaps' values there ([`Bsdf::with_blend_textures`]): its
    /// weight a bitmap's luminance, either BSDF's diffuse reflectance a bitmap's colour, each
    /// where one is given.
    Blend {
        /// The bitmap whose luminance is the weight.
        weight: Option<Arc<BitmapTexture>>,
        /// The bitmaps of the first and the second BSDF's diffuse reflectances.
        reflectances: [Option<Arc<BitmapTexture>>; 2],
    },
    /// The BSDF depends on the surface point itself ([`BsdfFlags::AT_SURFACE`]: a normal or
    /// bump map): [`Bsdf::at_surface`] gives the one a hit sees.
    AtSurface,
}

/// Room for the BSDF of a textured hit, which exists only for that hit: the integrators keep
/// one per path and [`World::intersect`] fills it when the surface it finds is textured, so that
/// untextured hits cost nothing for it.
#[derive(Debug, Default)]
pub struct BsdfSlot(Option<Bsdf>);

/// The renderable scene: one acceleration structure over all shapes, a material per shape, and
/// the lights, some of which are attached to shapes.
pub struct World {
    accel: Accel,
    materials: Vec<Bsdf>,
    /// Per material, its texture if it has one; empty when no material has.
    textures: Vec<Option<MaterialTexture>>,
    shape_material: Vec<MaterialId>,
    shape_light: Vec<Option<u32>>,
    lights: Vec<Light>,
    /// Each light's selection weight (Mitsuba's `sampling_weight`), parallel to `lights`.
    light_weights: Vec<f32>,
    environment: Option<u32>,
    delta_lights: Vec<u32>,
    /// Per material, whether it is anisotropic ([`BsdfFlags::ANISOTROPIC`]); empty when none is,
    /// so that isotropic scenes never build a frame from the surface's tangent.
    anisotropic: Vec<bool>,
}

/// A ray's closest surface hit with what is needed to shade it.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit<'w> {
    /// The geometric hit record.
    pub hit: Hit,
    /// Shading frame around the shading normal `hit.ns`; mirrored (normal `-hit.ns`) when the
    /// ray sees the back of a [`materials::TwoSided`] surface, so `bsdf` sees directions on
    /// its upper side.
    pub frame: Frame,
    /// The BSDF the ray sees: a [`materials::TwoSided`] is resolved to the side facing the ray.
    pub bsdf: &'w Bsdf,
    /// Index into [`World::lights`] when the surface emits.
    pub light: Option<u32>,
}

impl World {
    /// Assembles a world. `shape_material[i]` and `shape_light[i]` belong to shape `i` of
    /// `accel`, `light_weights[l]` (positive, finite selection weights) to `lights[l]`; every
    /// index must be in range (checked; the error says which one is not).
    pub fn new(
        accel: Accel,
        materials: Vec<Bsdf>,
        shape_material: Vec<MaterialId>,
        shape_light: Vec<Option<u32>>,
        lights: Vec<Light>,
        light_weights: Vec<f32>,
    ) -> Result<Self, String> {
        if light_weights.len() != lights.len() {
            return Err(format!(
                "{} lights but {} selection weights",
                lights.len(),
                light_weights.len()
            ));
        }
        if let Some(w) = light_weights.iter().find(|w| !(w.is_finite() && **w > 0.0)) {
            return Err(format!(
                "light selection weight {w} is not positive and finite"
            ));
        }
        let shape_count = accel.shape_count();
        if shape_material.len() != shape_count || shape_light.len() != shape_count {
            return Err(format!(
                "{shape_count} shapes but {} material and {} light assignments",
                shape_material.len(),
                shape_light.len()
            ));
        }
        if let Some(m) = shape_material
            .iter()
            .find(|&&m| m as usize >= materials.len())
        {
            return Err(format!(
                "material {m} out of range ({} materials)",
                materials.len()
            ));
        }
        if let Some(l) = shape_light
            .iter()
            .flatten()
            .find(|&&l| l as usize >= lights.len())
        {
            return Err(format!("light {l} out of range ({} lights)", lights.len()));
        }
        let environments: Vec<u32> = (0..lights.len() as u32)
            .filter(|&i| lights[i as usize].is_environment())
            .collect();
        if environments.len() > 1 {
            return Err("more than one environment emitter".to_string());
        }
        let delta_lights = (0..lights.len() as u32)
            .filter(|&i| lights[i as usize].is_delta())
            .collect();
        let is_anisotropic = |m: &Bsdf| m.flags().contains(BsdfFlags::ANISOTROPIC);
        let anisotropic = if materials.iter().any(is_anisotropic) {
            materials.iter().map(is_anisotropic).collect()
        } else {
            Vec::new()
        };
        Ok(Self {
            anisotropic,
            textures: at_surface_textures(&materials, Vec::new()),
            accel,
            materials,
            shape_material,
            shape_light,
            lights,
            light_weights,
            environment: environments.first().copied(),
            delta_lights,
        })
    }

    /// All lights, area lights included.
    #[inline]
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Each light's selection weight (parallel to [`Self::lights`]): it multiplies the
    /// probability with which light sampling chooses the light.
    #[inline]
    pub fn light_weights(&self) -> &[f32] {
        &self.light_weights
    }

    /// Index into [`Self::lights`] of the environment emitter, if the scene has one.
    #[inline]
    pub fn environment(&self) -> Option<u32> {
        self.environment
    }

    /// Indices of the lights that no ray can hit (point lights).
    #[inline]
    pub fn delta_lights(&self) -> &[u32] {
        &self.delta_lights
    }

    /// All materials.
    #[inline]
    pub fn materials(&self) -> &[Bsdf] {
        &self.materials
    }

    /// The static shapes' world-space bounds with their materials, in shape order (moving
    /// shapes left out).
    pub fn static_shape_materials(&self) -> impl Iterator<Item = (geometry::Aabb, &Bsdf)> + '_ {
        self.accel
            .shapes()
            .iter()
            .zip(&self.shape_material)
            .map(|(shape, &material)| (shape.bounds(), &self.materials[material as usize]))
    }

    /// Gives materials textures, one entry per material (`None` for a plain one); an error when
    /// the count differs, a checkerboard's `odd` material is out of range or textured itself, or
    /// a textured diffuse reflectance belongs to a BSDF without one (see
    /// [`Bsdf::with_diffuse_reflectance`]; a [`materials::TwoSided`] is asked for each side).
    pub fn set_textures(&mut self, textures: Vec<Option<MaterialTexture>>) -> Result<(), String> {
        if textures.len() != self.materials.len() {
            return Err(format!(
                "{} texture entries for {} materials",
                textures.len(),
                self.materials.len()
            ));
        }
        for (i, texture) in textures.iter().enumerate() {
            match texture {
                Some(MaterialTexture::Checkerboard(c)) => {
                    let odd = c.odd as usize;
                    if odd >= self.materials.len() || textures[odd].is_some() {
                        return Err(format!(
                            "material {i}: its checkerboard's material {odd} is invalid"
                        ));
                    }
                }
                Some(
                    texture @ (MaterialTexture::DiffuseReflectance(_)
                    | MaterialTexture::Blend { .. }),
                ) => {
                    let sides = match &self.materials[i] {
                        Bsdf::TwoSided(two_sided) => [two_sided.front(), two_sided.back()],
                        bsdf => [bsdf, bsdf],
                    };
                    let (fits, needed) = match texture {
                        MaterialTexture::Blend { reflectances, .. } => {
                            let values = reflectances
                                .each_ref()
                                .map(|r| r.as_ref().map(|_| Vec3::ONE));
                            (
                                sides
                                    .iter()
                                    .all(|s| s.with_blend_textures(Some(0.5), values).is_some()),
                                "a blend (of BSDFs with diffuse reflectances where textured)",
                            )
                        }
                        _ => (
                            sides
                                .iter()
                                .all(|s| s.with_diffuse_reflectance(Vec3::ONE).is_some()),
                            "a diffuse, plastic or rough plastic BSDF",
                        ),
                    };
                    if !fits {
                        return Err(format!("material {i}: its texture needs {needed}"));
                    }
                }
                Some(MaterialTexture::AtSurface) | None => {}
            }
        }
        let textures = at_surface_textures(&self.materials, textures);
        self.textures = if textures.iter().any(Option::is_some) {
            textures
        } else {
            Vec::new()
        };
        Ok(())
    }

    /// The BSDF a ray along `dir` sees of `material` with shading frame `frame`, and whether it
    /// sees it through the mirrored frame (the back of a [`materials::TwoSided`] faces the ray).
    /// The frame itself is left to the caller to mirror, so that it is not copied through the
    /// returned pair.
    #[inline(always)]
    fn facing(&self, material: MaterialId, frame: &Frame, dir: Vec3) -> (&Bsdf, bool) {
        match &self.materials[material as usize] {
            Bsdf::TwoSided(two_sided) => two_sided.facing(frame.to_local(-dir)),
            bsdf => (bsdf, false),
        }
    }

    /// [`Self::facing`] with `material`'s texture applied at `hit`: a checkerboard's odd
    /// material on an odd square, a bitmap's reflectance put into `slot`. Kept out of line, so
    /// that scenes without textures pay one test per hit for them.
    #[cold]
    #[inline(never)]
    fn textured_facing<'s>(
        &'s self,
        material: MaterialId,
        hit: &Hit,
        frame: &Frame,
        dir: Vec3,
        slot: &'s mut BsdfSlot,
    ) -> (&'s Bsdf, bool) {
        match &self.textures[material as usize] {
            Some(MaterialTexture::Checkerboard(checker)) => {
                let chosen = if checker.is_odd(self.accel.uv(hit)) {
                    checker.odd
                } else {
                    material
                };
                self.facing(chosen, frame, dir)
            }
            Some(MaterialTexture::AtSurface) => {
                let (side, mirrored) = self.facing(material, frame, dir);
                let [dp_du, dp_dv] = self.accel.dp_duv(hit);
                let point = SurfacePoint {
                    uv: self.accel.uv(hit),
                    dp_du: frame.to_local(dp_du),
                    dp_dv: frame.to_local(dp_dv),
                    ng: frame.to_local(hit.ng),
                };
                match side.at_surface(&point) {
                    Some(at_surface) => (slot.0.insert(at_surface), mirrored),
                    None => (side, mirrored),
                }
            }
            Some(bitmap_texture) => {
                let (side, mirrored) = self.facing(material, frame, dir);
                let uv = self.accel.uv(hit);
                let textured = match bitmap_texture {
                    MaterialTexture::DiffuseReflectance(bitmap) => {
                        side.with_diffuse_reflectance(bitmap.eval(uv))
                    }
                    MaterialTexture::Blend {
                        weight,
                        reflectances,
                    } => side.with_blend_textures(
                        weight.as_ref().map(|w| w.eval_luminance(uv)),
                        reflectances
                            .each_ref()
                            .map(|r| r.as_ref().map(|r| r.eval(uv))),
                    ),
                    MaterialTexture::Checkerboard(_) | MaterialTexture::AtSurface => None,
                };
                match textured {
                    Some(textured) => (slot.0.insert(textured), mirrored),
                    None => (side, mirrored),
                }
            }
            None => self.facing(material, frame, dir),
        }
    }

    /// Whether some material chooses its lobe by a random number ([`BsdfFlags::LOBE_CHOICE`]:
    /// a dielectric), so the integrators draw one at every vertex.
    #[inline]
    pub fn has_lobe_choice(&self) -> bool {
        self.materials
            .iter()
            .any(|m| m.flags().contains(BsdfFlags::LOBE_CHOICE))
    }

    /// Whether some material has a null lobe ([`BsdfFlags::NULL`]: a pass straight through).
    #[inline]
    pub fn has_null_lobes(&self) -> bool {
        self.materials
            .iter()
            .any(|m| m.flags().contains(BsdfFlags::NULL))
    }

    /// Whether some shape moves during the shutter: then each camera sample draws a time and
    /// every ray of its path carries it.
    #[inline]
    pub fn has_motion(&self) -> bool {
        self.accel.has_motion()
    }

    /// The acceleration structure over all shapes.
    #[inline]
    pub fn accel(&self) -> &Accel {
        &self.accel
    }

    /// The closest surface along `ray`, told to `tally` as one closest-hit ray; a textured
    /// surface's BSDF is put into `slot`.
    #[inline(always)]
    pub fn intersect<'s>(
        &'s self,
        ray: &Ray,
        tally: &mut impl RayTally,
        slot: &'s mut BsdfSlot,
    ) -> Option<SurfaceHit<'s>> {
        self.intersect_within(ray, f32::INFINITY, tally, slot)
    }

    /// The closest surface along `ray` nearer than `t_max` (world units), told to `tally` as one
    /// closest-hit ray; a textured surface's BSDF is put into `slot`.
    #[inline(always)]
    pub fn intersect_within<'s>(
        &'s self,
        ray: &Ray,
        t_max: f32,
        tally: &mut impl RayTally,
        slot: &'s mut BsdfSlot,
    ) -> Option<SurfaceHit<'s>> {
        tally.closest_ray(ray);
        let hit = self.accel.intersect(ray, t_max)?;
        Some(self.surface(hit, ray.dir, slot))
    }

    /// What shading needs of `hit`, found along the direction `dir`; a textured surface's BSDF
    /// is put into `slot`.
    #[inline(always)]
    fn surface<'s>(&'s self, hit: Hit, dir: Vec3, slot: &'s mut BsdfSlot) -> SurfaceHit<'s> {
        let shape = hit.shape as usize;
        let material = self.shape_material[shape];
        let mut frame = if self.anisotropic.is_empty() || !self.anisotropic[material as usize] {
            Frame::from_normal(hit.ns)
        } else {
            Frame::from_normal_and_tangent(hit.ns, self.accel.dp_du(&hit))
        };
        let (bsdf, mirrored) = if self.textures.is_empty() {
            self.facing(material, &frame, dir)
        } else {
            self.textured_facing(material, &hit, &frame, dir, slot)
        };
        if mirrored {
            frame = frame.mirrored();
        }
        SurfaceHit {
            hit,
            frame,
            bsdf,
            light: self.shape_light[shape],
        }
    }

    /// The first surface along `camera_ray` (within its far clip) that does not emit, passing
    /// through every area emitter in front of it (each one told to `tally` as one more closest-hit
    /// ray): how
    /// Mitsuba 3's `hide_emitters` hides emitters from the camera, so that what lies behind a
    /// hidden light shows (Mitsuba 3's `skip_area_emitters`).
    /// A textured surface's BSDF is put into `slot`.
    #[inline]
    pub fn intersect_past_emitters<'s>(
        &'s self,
        camera_ray: &CameraRay,
        tally: &mut impl RayTally,
        slot: &'s mut BsdfSlot,
    ) -> Option<SurfaceHit<'s>> {
        let mut ray = camera_ray.ray;
        let mut t_max = camera_ray.t_max;
        loop {
            tally.closest_ray(&ray);
            let hit = self.accel.intersect(&ray, t_max)?;
            if self.shape_light[hit.shape as usize].is_none() {
                return Some(self.surface(hit, ray.dir, slot));
            }
            // Mitsuba's rays past an emitter are not clipped again.
            ray = Ray::spawn(hit.p, hit.ng, hit.p_error, ray.dir).at_time(hit.time);
            t_max = f32::INFINITY;
        }
    }

    /// True when nothing blocks the connection of two path vertices: the ray from `origin` in
    /// the unit direction `dir` for `0 < t < t_max` (from [`Ray::between`], given as 16-byte
    /// vectors as [`geometry::Rayx4::lanes`] makes them), told to `tally` as one connection ray.
    /// Static shapes only: not for a world with motion ([`World::has_motion`]).
    #[inline(always)]
    pub fn connection_unoccluded(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_max: f32,
        tally: &mut impl RayTally,
    ) -> bool {
        let ray = Ray {
            origin: origin.into(),
            dir: dir.into(),
            time: 0.0,
        };
        tally.connection_ray(&ray, t_max);
        !self.accel.occluded_wide(origin, dir, t_max)
    }

    /// True when nothing blocks the segment from the surface point `hit` to the point `target`,
    /// which lies on no surface (a camera's lens point), told to `tally` as one shadow ray.
    #[inline(always)]
    pub fn unoccluded(&self, hit: &Hit, target: Vec3, tally: &mut impl RayTally) -> bool {
        let (ray, distance) =
            Ray::spawn_to(hit.p, hit.ng, hit.p_error, target, Vec3::ZERO, Vec3::ZERO);
        let ray = ray.at_time(hit.time);
        self.ray_unoccluded(&ray, distance, tally)
    }

    /// True when nothing blocks the light of `sample` from reaching the surface point `point`:
    /// the segment to its point, or for lights at infinity (the environment, directional
    /// lights) the ray escaping the scene. Told to `tally` as one shadow ray.
    #[inline(always)]
    pub fn light_unoccluded(
        &self,
        point: &SpawnPoint,
        sample: &LightSample,
        tally: &mut impl RayTally,
    ) -> bool {
        let (ray, t_max) = shadow_ray(point, sample);
        self.ray_unoccluded(&ray, t_max, tally)
    }

    /// True when nothing blocks `ray` for `0 < t < t_max`, told to `tally` as one shadow ray.
    #[inline(always)]
    pub fn ray_unoccluded(&self, ray: &Ray, t_max: f32, tally: &mut impl RayTally) -> bool {
        tally.shadow_ray(ray, t_max);
        !self.accel.occluded(ray, t_max)
    }

    /// Radiance emitted by the surface of `surface` towards the unit direction `w`, one-sided by
    /// the geometric normal, as light sampling sees it; with `seen_through_delta` (emission seen
    /// from the camera directly or through delta bounces only, which neither light sampling nor
    /// the light tracer reaches) one-sided by the shading normal, as Mitsuba 3 sees every
    /// emitter, by its shading frame. On a mesh with vertex normals the two sides differ near
    /// silhouettes; elsewhere they are the same.
    #[inline]
    pub fn emitted(&self, surface: &SurfaceHit<'_>, w: Vec3, seen_through_delta: bool) -> Vec3 {
        let normal = if seen_through_delta {
            surface.hit.ns
        } else {
            surface.hit.ng
        };
        surface.light.map_or(Vec3::ZERO, |l| {
            self.lights[l as usize].radiance_towards(normal, w)
        })
    }

    /// Radiance arriving along a ray that escapes the scene in the unit direction `dir`.
    #[inline]
    pub fn background(&self, dir: Vec3) -> Vec3 {
        self.environment.map_or(Vec3::ZERO, |e| {
            self.lights[e as usize].radiance_from_direction(dir)
        })
    }
}

/// The shadow ray from the surface point `point` to the light of `sample`, and the `t_max` to
/// trace it with: the segment to its point, or for lights at infinity (the environment,
/// directional lights) the ray escaping the scene.
#[inline(always)]
pub fn shadow_ray(point: &SpawnPoint, sample: &LightSample) -> (Ray, f32) {
    if sample.distance.is_finite() {
        point.spawn_to(sample.p_light, sample.n_light, sample.p_light_error)
    } else {
        (point.spawn(sample.wi), f32::INFINITY)
    }
}

/// `textures` (one entry per material, or empty for none) with [`MaterialTexture::AtSurface`] for
/// each material without a texture of its own that depends on the surface point; empty when no
/// material has a texture.
fn at_surface_textures(
    materials: &[Bsdf],
    mut textures: Vec<Option<MaterialTexture>>,
) -> Vec<Option<MaterialTexture>> {
    let at_surface = |m: &Bsdf| m.flags().contains(BsdfFlags::AT_SURFACE);
    if !materials.iter().any(at_surface) {
        return textures;
    }
    textures.resize(materials.len(), None);
    for (texture, material) in textures.iter_mut().zip(materials) {
        if texture.is_none() && at_surface(material) {
            *texture = Some(MaterialTexture::AtSurface);
        }
    }
    textures
}
