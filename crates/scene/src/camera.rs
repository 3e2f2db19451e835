//! Mitsuba's `perspective`, `thinlens` and `orthographic` sensors: rays from film positions.

use geometry::{Motion, Ray};
use glam::{Mat4, UVec2, Vec2, Vec3};
use std::sync::Arc;
use world::{CameraConnection, CameraRay, CameraTraits};

use crate::desc::SensorDesc;
use sampling::warp::sample_concentric_disk;

/// A thin lens: rays leave a disc of `aperture_radius` and converge on the plane at
/// `focus_distance` along the view axis (both in world units of the camera's local frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinLens {
    /// Radius of the aperture disc.
    pub aperture_radius: f32,
    /// Distance from the lens to the plane in focus, along the view axis.
    pub focus_distance: f32,
}

/// A pinhole or thin-lens perspective camera, or an orthographic one, with Mitsuba's
/// conventions: it looks down its local +z, local +y is up, local +x is image-left, and image
/// rows run top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    to_world: Mat4,
    to_camera: Mat4,
    /// tan of half the field of view along x and y.
    tan_half_fov: Vec2,
    resolution: Vec2,
    near_clip: f32,
    far_clip: f32,
    /// The principal point's offset from the film's centre, in fractions of the film's size.
    principal_point_offset: Vec2,
    lens: Option<ThinLens>,
    /// Parallel rays from the near plane over x ∈ [−1, 1], y ∈ [−1/aspect, 1/aspect].
    orthographic: bool,
    /// The rendered image's top-left pixel in the whole film (a crop window's offset), pixels.
    crop_offset: Vec2,
    /// The rendered image's size, pixels (the whole film's without a crop window).
    crop_size: Vec2,
    /// How the camera moves while the shutter is open, if it does.
    motion: Option<Arc<Motion>>,
}

impl Camera {
    /// The camera `sensor` describes, over an image of `width` × `height` pixels.
    pub fn new(sensor: &SensorDesc, width: u32, height: u32) -> Self {
        let aspect = width as f32 / height as f32;
        let tan_x = (0.5 * sensor.x_fov_deg(width, height).to_radians()).tan();
        Self {
            to_world: sensor.to_world,
            to_camera: sensor.to_world.inverse(),
            tan_half_fov: Vec2::new(tan_x, tan_x / aspect),
            resolution: Vec2::new(width as f32, height as f32),
            near_clip: sensor.near_clip,
            far_clip: sensor.far_clip,
            principal_point_offset: Vec2::from_array(sensor.principal_point_offset),
            lens: sensor.lens.map(|l| ThinLens {
                aperture_radius: l.aperture_radius,
                focus_distance: l.focus_distance,
            }),
            orthographic: sensor.orthographic,
            crop_offset: Vec2::ZERO,
            crop_size: Vec2::new(width as f32, height as f32),
            motion: sensor
                .motion
                .as_ref()
                .map(|m| Arc::new(Motion::new(m.clone(), sensor.shutter))),
        }
    }

    /// What light paths need to know of it: its lens, its motion.
    pub fn traits(&self) -> CameraTraits {
        CameraTraits {
            has_lens: self.has_lens(),
            moves: self.moves(),
        }
    }

    /// Whether the camera moves while the shutter is open.
    #[inline]
    pub fn moves(&self) -> bool {
        self.motion.as_ref().is_some_and(|m| m.moves())
    }

    /// The camera where it is at `time` (a fraction of the shutter interval, see
    /// [`geometry::Ray::time`]): itself if it does not move.
    pub fn at_time(&self, time: f32) -> Camera {
        match &self.motion {
            Some(motion) => {
                let to_world = motion.at(time).to_world().as_mat4();
                Camera {
                    to_world,
                    to_camera: to_world.inverse(),
                    ..self.clone()
                }
            }
            None => self.clone(),
        }
    }

    /// This camera rendering only the crop window of `size` pixels at `offset` in its film
    /// (Mitsuba's `crop_offset_x/y`, `crop_width/height`): film positions given to and returned
    /// by [`Self::generate_ray`] and [`Self::connect`] are then the window's.
    pub fn cropped(self, offset: UVec2, size: UVec2) -> Self {
        Self {
            crop_offset: offset.as_vec2(),
            crop_size: size.as_vec2(),
            ..self
        }
    }

    /// True when the light tracer can connect points to the camera: every camera but the
    /// orthographic one, which sees each point along one direction only (its importance is a
    /// delta in direction).
    #[inline]
    pub fn connects(&self) -> bool {
        !self.orthographic
    }

    /// True when rays depend on a lens sample (a thin lens with a non-zero aperture).
    #[inline]
    pub fn has_lens(&self) -> bool {
        self.lens.is_some_and(|l| l.aperture_radius > 0.0)
    }

    /// The ray through the continuous film position `film` (pixels; (0, 0) is the top-left
    /// corner of the image, pixel centres at half-integers), using `u_lens` ∈ [0, 1)² on the
    /// aperture when the camera has a lens. The ray starts on the near clipping plane and ends
    /// on the far one.
    #[inline]
    pub fn generate_ray(&self, film: Vec2, u_lens: Vec2) -> CameraRay {
        let film = film + self.crop_offset;
        if self.orthographic {
            return self.orthographic_ray(film);
        }
        let ndc = (film / self.resolution + self.principal_point_offset) * 2.0 - Vec2::ONE;
        // Image right is camera -x and image down is camera -y.
        let on_plane = Vec3::new(
            -ndc.x * self.tan_half_fov.x,
            -ndc.y * self.tan_half_fov.y,
            1.0,
        );
        let (origin_local, dir_local) = match self.lens {
            Some(lens) if lens.aperture_radius > 0.0 => {
                let aperture = sample_concentric_disk(u_lens) * lens.aperture_radius;
                let origin = Vec3::new(aperture.x, aperture.y, 0.0);
                let focus = on_plane * lens.focus_distance;
                (origin, focus - origin)
            }
            _ => (Vec3::ZERO, on_plane),
        };
        // Neither direction is unit length yet: `Ray::new` normalises the world one.
        let near = origin_local + dir_local * (self.near_clip / dir_local.z);
        let origin = self.to_world.transform_point3(near);
        // From the near plane to the far one along the (rigidly transformed) direction.
        let length = dir_local.length();
        let t_max = (self.far_clip - self.near_clip) * length / dir_local.z;
        let cos_theta = dir_local.z / length;
        CameraRay {
            ray: Ray::new(origin, self.to_world.transform_vector3(dir_local)),
            t_max,
            pdf_dir: 1.0 / (self.image_plane_area() * cos_theta.powi(3)),
            eye: self.to_world.transform_point3(origin_local),
        }
    }

    /// The orthographic camera's ray through `film`: from (x, y, near) in the camera's frame, with
    /// x = 1 − 2 film.x / width and y = (1 − 2 film.y / height) / aspect (Mitsuba's
    /// `orthographic_projection`), along its +z, ending at the far plane.
    fn orthographic_ray(&self, film: Vec2) -> CameraRay {
        let aspect = self.resolution.x / self.resolution.y;
        let sample = film / self.resolution;
        let local = Vec3::new(
            1.0 - 2.0 * sample.x,
            (1.0 - 2.0 * sample.y) / aspect,
            self.near_clip,
        );
        CameraRay {
            ray: Ray::new(
                self.to_world.transform_point3(local),
                self.to_world.transform_vector3(Vec3::Z),
            ),
            t_max: self.far_clip - self.near_clip,
            pdf_dir: 0.0,
            eye: self.to_world.transform_point3(local),
        }
    }

    /// Area of the rendered image's part of the image plane at unit distance: the whole plane's,
    /// 4 tan(fov_x / 2) tan(fov_y / 2), times the share the rendered image (a crop window) takes.
    /// Light paths stand for pixel samples of the rendered image, not of the film.
    fn image_plane_area(&self) -> f32 {
        let plane_area = 4.0 * self.tan_half_fov.x * self.tan_half_fov.y;
        plane_area * self.crop_size.element_product() / self.resolution.element_product()
    }

    /// Where the world point `p` appears to this camera through the point of its aperture that
    /// `u_lens` ∈ [0, 1)² picks (as [`Camera::generate_ray`] does; ignored for a pinhole): the
    /// film position of the camera rays that pass through that aperture point and `p`, the end
    /// of a ray to the camera, and the camera's importance there (see [`CameraConnection`]).
    /// `None` for points outside the clipping planes or more than `margin` pixels off the film (a
    /// reconstruction filter's radius: camera samples of the edge pixels reach that far).
    /// Assumes a rigid (or uniformly scaled) camera transform, as `lookat` gives. `None` for the
    /// orthographic camera (see [`Camera::connects`]).
    ///
    /// With a thin lens every ray through the aperture point `a` and `p` comes from the film
    /// position whose pinhole ray meets the focus plane where the line from `a` through `p`
    /// does; choosing `a` uniformly on the aperture and weighting by the importance below is
    /// pbrt-v4's `PerspectiveCamera::SampleWi`, whose lens area cancels out.
    pub fn connect(&self, p: Vec3, margin: f32, u_lens: Vec2) -> Option<CameraConnection> {
        if self.orthographic {
            return None;
        }
        let local = self.to_camera.transform_point3(p);
        if !(local.z > self.near_clip && local.z <= self.far_clip && local.is_finite()) {
            return None;
        }
        // The aperture point, the direction from it to `p`, the pinhole ray's point on the plane
        // z = 1 for the film position, and the connection's end on the near plane.
        let (aperture, to_p, on_plane, near) = match self.lens {
            Some(lens) if lens.aperture_radius > 0.0 => {
                let a = sample_concentric_disk(u_lens) * lens.aperture_radius;
                let aperture = Vec3::new(a.x, a.y, 0.0);
                let to_p = local - aperture;
                let focus = aperture + to_p * (lens.focus_distance / to_p.z);
                let near = aperture + to_p * (self.near_clip / to_p.z);
                (aperture, to_p, focus / focus.z, near)
            }
            _ => {
                let on_plane = local / local.z;
                (Vec3::ZERO, local, on_plane, on_plane * self.near_clip)
            }
        };
        let ndc = Vec2::new(
            -on_plane.x / self.tan_half_fov.x,
            -on_plane.y / self.tan_half_fov.y,
        );
        let film = ((ndc + Vec2::ONE) * 0.5 - self.principal_point_offset) * self.resolution
            - self.crop_offset;
        let margin = Vec2::splat(margin);
        if !(film.cmpge(-margin).all() && film.cmplt(self.crop_size + margin).all()) {
            return None;
        }
        let eye = self.to_world.transform_point3(aperture);
        let distance_squared = (p - eye).length_squared();
        let cos_theta = to_p.z / to_p.length();
        let importance = 1.0 / (self.image_plane_area() * cos_theta.powi(3) * distance_squared);
        importance.is_finite().then(|| CameraConnection {
            film,
            target: self.to_world.transform_point3(near),
            importance,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::desc::FovAxis;

    /// A camera at (1, 2, 3) looking down world −z, 40° horizontal field of view, clipped at 0.5
    /// and 20, with the given principal point offset, on a 64 × 48 film.
    fn camera(offset: [f32; 2]) -> Camera {
        let sensor = SensorDesc {
            // Mitsuba's lookat from (1, 2, 3) towards −z with +y up: local +x is world −x.
            to_world: Mat4::from_cols(
                glam::Vec4::NEG_X,
                glam::Vec4::Y,
                glam::Vec4::NEG_Z,
                glam::Vec4::new(1.0, 2.0, 3.0, 1.0),
            ),
            position: glam::DVec3::ZERO,
            fov_deg: 40.0,
            fov_axis: FovAxis::X,
            near_clip: 0.5,
            far_clip: 20.0,
            lens: None,
            principal_point_offset: offset,
            orthographic: false,
            shutter: [0.0, 0.0],
            motion: None,
        };
        Camera::new(&sensor, 64, 48)
    }

    #[test]
    fn a_crop_window_renders_its_part_of_the_film() {
        let full = camera([0.0, 0.0]);
        let cropped = full.clone().cropped(UVec2::new(20, 10), UVec2::new(16, 12));
        let at = Vec2::new(3.25, 7.5);
        let whole = full.generate_ray(at + Vec2::new(20.0, 10.0), Vec2::ZERO);
        let window = cropped.generate_ray(at, Vec2::ZERO);
        assert!((whole.ray.dir - window.ray.dir).length() < 1e-6);
        assert!((whole.ray.origin - window.ray.origin).length() < 1e-6);
        // A point the window sees connects to the window's pixel, with the importance of one
        // of its light paths: the film has 64 x 48 / (16 x 12) = 16 times as many pixels.
        let p = whole.ray.at(5.0);
        let (from_full, from_window) = (
            full.connect(p, 0.0, Vec2::ZERO).unwrap(),
            cropped.connect(p, 0.0, Vec2::ZERO).unwrap(),
        );
        assert!(
            (from_window.film - at).length() < 1e-3,
            "{}",
            from_window.film
        );
        assert!((from_window.importance / from_full.importance - 16.0).abs() < 1e-3);
        // What the film shows outside the window is not connected.
        let outside = full
            .generate_ray(Vec2::new(5.0, 40.0), Vec2::ZERO)
            .ray
            .at(5.0);
        assert!(full.connect(outside, 0.0, Vec2::ZERO).is_some());
        assert!(cropped.connect(outside, 0.0, Vec2::ZERO).is_none());
    }

    #[test]
    fn an_offset_principal_point_shifts_the_film() {
        let (centred, shifted) = (camera([0.0, 0.0]), camera([0.25, -0.1]));
        for film in [
            Vec2::new(10.5, 3.25),
            Vec2::new(32.0, 24.0),
            Vec2::new(0.0, 47.9),
        ] {
            let expected =
                centred.generate_ray(film + Vec2::new(0.25 * 64.0, -0.1 * 48.0), Vec2::ZERO);
            let ray = shifted.generate_ray(film, Vec2::ZERO);
            assert!(
                ray.ray.dir.abs_diff_eq(expected.ray.dir, 1e-6)
                    && ray.ray.origin.abs_diff_eq(expected.ray.origin, 1e-5),
                "film {film}: {ray:?} against {expected:?}"
            );
            // The light tracer's connection finds the same film position again.
            let p = ray.ray.at(7.0);
            let connection = shifted.connect(p, 0.0, Vec2::ZERO).expect("p is in view");
            assert!(
                connection.film.abs_diff_eq(film, 1e-3),
                "{} against {film}",
                connection.film
            );
        }
    }

    /// The importance a camera ray reports at a point it reaches is the one the light tracer's
    /// connection through the same aperture point gives (their MIS weights compare the two),
    /// for a pinhole, a thin lens, and a crop window, off the view axis too.
    #[test]
    fn a_camera_rays_importance_is_its_connections() {
        let pinhole = camera([0.0, 0.0]);
        let lens = Camera {
            lens: Some(ThinLens {
                aperture_radius: 0.2,
                focus_distance: 6.0,
            }),
            ..pinhole.clone()
        };
        let cropped = pinhole
            .clone()
            .cropped(UVec2::new(20, 10), UVec2::new(16, 12));
        for (name, camera) in [("pinhole", pinhole), ("lens", lens), ("crop", cropped)] {
            for (film, u_lens) in [
                (Vec2::new(8.0, 6.0), Vec2::new(0.3, 0.9)),
                (Vec2::new(0.5, 11.5), Vec2::new(0.8, 0.1)),
                (Vec2::new(15.5, 0.5), Vec2::new(0.5, 0.5)),
            ] {
                let ray = camera.generate_ray(film, u_lens);
                for t in [1.0, 4.0, 9.0] {
                    let p = ray.ray.at(t);
                    let connection = camera.connect(p, 0.0, u_lens).expect("p is in view");
                    let ratio = ray.importance_at(p) / connection.importance;
                    assert!(
                        (ratio - 1.0).abs() < 1e-4,
                        "{name}, film {film}, t {t}: the ray's importance is {ratio} times the \
                         connection's"
                    );
                }
            }
        }
    }

    #[test]
    fn camera_rays_end_on_the_far_clipping_plane() {
        let camera = camera([0.1, 0.0]);
        for film in [
            Vec2::new(0.5, 0.5),
            Vec2::new(32.0, 24.0),
            Vec2::new(63.5, 40.0),
        ] {
            let ray = camera.generate_ray(film, Vec2::ZERO);
            // The camera looks down world −z from z = 3: local depth is 3 − z.
            let depth = |t: f32| 3.0 - ray.ray.at(t).z;
            assert!(
                (depth(0.0) - 0.5).abs() < 1e-5,
                "film {film}: starts at depth {}",
                depth(0.0)
            );
            assert!(
                (depth(ray.t_max) - 20.0).abs() < 1e-4,
                "film {film}: ends at depth {}",
                depth(ray.t_max)
            );
            assert!(
                camera
                    .connect(ray.ray.at(ray.t_max * 0.99), 0.0, Vec2::ZERO)
                    .is_some()
            );
            assert!(
                camera
                    .connect(ray.ray.at(ray.t_max * 1.01), 0.0, Vec2::ZERO)
                    .is_none()
            );
        }
    }

    #[test]
    fn orthographic_rays_are_parallel_over_mitsubas_region() {
        // A 2:1 film; to_world scales the region by 3 and turns the camera to look down −x.
        let to_world = Mat4::from_cols(
            glam::Vec4::new(0.0, 0.0, 3.0, 0.0),
            glam::Vec4::new(0.0, 3.0, 0.0, 0.0),
            glam::Vec4::new(-1.0, 0.0, 0.0, 0.0),
            glam::Vec4::new(5.0, 0.0, 0.0, 1.0),
        );
        let sensor = SensorDesc {
            to_world,
            position: glam::DVec3::ZERO,
            fov_deg: 90.0,
            fov_axis: FovAxis::X,
            near_clip: 0.5,
            far_clip: 20.0,
            lens: None,
            principal_point_offset: [0.0, 0.0],
            orthographic: true,
            shutter: [0.0, 0.0],
            motion: None,
        };
        let camera = Camera::new(&sensor, 64, 32);
        assert!(!camera.connects() && !camera.has_lens());
        for (film, local) in [
            // The top-left corner is local (+1, +1/aspect), the centre (0, 0), the bottom-right
            // corner (−1, −1/aspect), all on the near plane.
            (Vec2::ZERO, Vec3::new(1.0, 0.5, 0.5)),
            (Vec2::new(32.0, 16.0), Vec3::new(0.0, 0.0, 0.5)),
            (Vec2::new(64.0, 32.0), Vec3::new(-1.0, -0.5, 0.5)),
        ] {
            let ray = camera.generate_ray(film, Vec2::new(0.3, 0.7));
            let origin = to_world.transform_point3(local);
            assert!(ray.ray.origin.abs_diff_eq(origin, 1e-5), "{film}: {ray:?}");
            assert!(
                ray.ray.dir.abs_diff_eq(Vec3::NEG_X, 1e-6),
                "{film}: {ray:?}"
            );
            assert_eq!(ray.t_max, 19.5);
        }
        assert!(
            camera
                .connect(Vec3::new(0.0, 0.0, 0.0), 1.0, Vec2::ZERO)
                .is_none()
        );
    }
}
