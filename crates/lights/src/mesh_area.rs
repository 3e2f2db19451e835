//! Area emitters on triangle meshes (Mitsuba's `area` emitter attached to a mesh shape).

use crate::area_sample::{area_pdf_towards, area_sample_towards};
use crate::emission::{EmissionSample, lambertian_emission};
use crate::sample::{LightSample, mean_rgb};
use glam::{Vec2, Vec3};
use sampling::distribution::CdfTable;
use sampling::warp::sample_uniform_triangle;
use std::f32::consts::PI;

/// A triangle mesh emitting constant radiance from the front side of each triangle, the side
/// its geometric normal `(p1 − p0) × (p2 − p0)` points to. Points are sampled uniformly by area.
#[derive(Clone, Debug)]
pub struct MeshAreaLight {
    triangles: Vec<[Vec3; 3]>,
    /// Unit geometric normal of each triangle (zero for degenerate ones, which are never sampled).
    normals: Vec<Vec3>,
    area_distribution: CdfTable,
    total_area: f32,
    radiance: Vec3,
    /// A sphere around every triangle: centre and radius (world units).
    bounds: (Vec3, f32),
}

impl MeshAreaLight {
    /// An emitter over the given world-space triangles with `radiance` (W m⁻² sr⁻¹, RGB).
    /// `None` when the triangles have no area at all (such a light can never be seen).
    pub fn new(triangles: Vec<[Vec3; 3]>, radiance: Vec3) -> Option<Self> {
        let areas: Vec<f32> = triangles.iter().map(triangle_area).collect();
        let total_area: f32 = areas.iter().map(|&a| f64::from(a)).sum::<f64>() as f32;
        let area_distribution = CdfTable::new(&areas).ok()?;
        let normals = triangles
            .iter()
            .map(|[p0, p1, p2]| (*p1 - *p0).cross(*p2 - *p0).normalize_or_zero())
            .collect();
        let (low, high) = triangles.iter().flatten().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(low, high), &p| (low.min(p), high.max(p)),
        );
        let bounds = (0.5 * (low + high), 0.5 * (high - low).length());
        Some(Self {
            triangles,
            normals,
            area_distribution,
            total_area,
            radiance,
            bounds,
        })
    }

    /// Emitted radiance, W m⁻² sr⁻¹ (RGB).
    pub fn radiance(&self) -> Vec3 {
        self.radiance
    }

    /// A sphere (centre, radius in world units) that contains the whole mesh.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        self.bounds
    }

    /// Total surface area, world units squared.
    pub fn area(&self) -> f32 {
        self.total_area
    }

    /// A point uniform by area on the mesh, seen from `p`; `None` when it faces away or
    /// coincides with `p`.
    #[inline]
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let (index, _pmf, u_remapped) = self.area_distribution.sample(u.x);
        let [p0, p1, p2] = self.triangles[index];
        let b = sample_uniform_triangle(Vec2::new(u_remapped, u.y));
        let p_light = p0 * b.x + p1 * b.y + p2 * b.z;
        let n_light = self.normals[index];
        area_sample_towards(p, p_light, n_light, 1.0 / self.total_area, self.radiance)
    }

    /// Density per steradian with which [`Self::sample_li`] from `p` picks the point `p_light`
    /// (geometric normal `n_light`) of this mesh.
    #[inline]
    pub fn pdf_li(&self, p: Vec3, p_light: Vec3, n_light: Vec3) -> f32 {
        area_pdf_towards(p, p_light, n_light, 1.0 / self.total_area)
    }

    /// Light leaving the mesh: a point uniform by area (`u_point`) and a cosine-distributed
    /// direction about its front normal (`u_dir`).
    #[inline]
    pub fn sample_emission(&self, u_point: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        let (index, _pmf, u_remapped) = self.area_distribution.sample(u_point.x);
        let [p0, p1, p2] = self.triangles[index];
        let b = sample_uniform_triangle(Vec2::new(u_remapped, u_point.y));
        let p = p0 * b.x + p1 * b.y + p2 * b.z;
        lambertian_emission(
            p,
            self.normals[index],
            self.radiance,
            self.total_area,
            u_dir,
        )
    }

    /// Emitted power (W, mean over channels): π · area · radiance for a one-sided Lambertian emitter.
    pub fn power(&self) -> f32 {
        PI * self.total_area * mean_rgb(self.radiance)
    }
}

fn triangle_area(t: &[Vec3; 3]) -> f32 {
    let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
    if area.is_finite() { area } else { 0.0 }
}
