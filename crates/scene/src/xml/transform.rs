//! The operations inside `<transform>`: `translate`, `rotate`, `scale`, `lookat` and `matrix`.
//!
//! Each operation is a 4×4 matrix; the caller left-multiplies them in document order
//! (`M = op * M`), as Mitsuba does.

use glam::{DMat3, DMat4, DVec3, DVec4};

use super::attrs::Attrs;
use super::values::{parse_float, parse_floats, parse_vec3, parse_vec3_or_scalar};
use crate::error::{Loc, Result};

/// The operation tags accepted inside `<transform>`.
pub(crate) const TRANSFORM_OPS: [&str; 5] = ["translate", "rotate", "scale", "lookat", "matrix"];

/// The matrix of one transform operation element.
pub(crate) fn operation_matrix(tag: &str, attrs: &Attrs, loc: &Loc) -> Result<DMat4> {
    match tag {
        "translate" => {
            attrs.check(&["x", "y", "z", "value"], &[], loc)?;
            Ok(DMat4::from_translation(xyz_or_value(attrs, 0.0, loc)?))
        }
        "scale" => {
            attrs.check(&["x", "y", "z", "value"], &[], loc)?;
            Ok(DMat4::from_scale(xyz_or_value(attrs, 1.0, loc)?))
        }
        "rotate" => {
            attrs.check(&["x", "y", "z", "value", "angle"], &["angle"], loc)?;
            let axis = xyz_or_value(attrs, 0.0, loc)?;
            if axis == DVec3::ZERO {
                return Err(loc.error("rotation axis cannot be zero"));
            }
            // Mitsuba uses the axis as given, so a non-unit axis there is not a rotation.
            if (axis.length() - 1.0).abs() > 1e-3 {
                return Err(loc.error(format!(
                    "rotation axis {axis} must have unit length (Mitsuba does not normalise it)"
                )));
            }
            let angle = parse_float(attrs.get("angle").unwrap_or_default(), loc)?;
            Ok(DMat4::from_axis_angle(axis.normalize(), angle.to_radians()))
        }
        "lookat" => {
            attrs.check(&["origin", "target", "up"], &["origin", "target"], loc)?;
            let origin = parse_vec3(attrs.get("origin").unwrap_or_default(), loc)?;
            let target = parse_vec3(attrs.get("target").unwrap_or_default(), loc)?;
            let up = match attrs.get("up") {
                Some(text) => parse_vec3(text, loc)?,
                None => DVec3::ZERO,
            };
            look_at(origin, target, up).ok_or_else(|| {
                loc.error(
                    "invalid lookat: origin and target coincide or up is parallel to the view direction",
                )
            })
        }
        "matrix" => {
            attrs.check(&["value"], &["value"], loc)?;
            matrix(attrs.get("value").unwrap_or_default(), loc)
        }
        other => Err(loc.error(format!(
            "unexpected <{other}> inside <transform> (supported: {})",
            TRANSFORM_OPS.join(", ")
        ))),
    }
}

/// A vector given either as `value="v"` / `value="x, y, z"` or by `x`, `y`, `z` attributes, missing
/// components taking `default`.
fn xyz_or_value(attrs: &Attrs, default: f64, loc: &Loc) -> Result<DVec3> {
    if let Some(value) = attrs.get("value") {
        if attrs.get("x").is_some() || attrs.get("y").is_some() || attrs.get("z").is_some() {
            return Err(loc.error("cannot mix \"value\" with \"x\"/\"y\"/\"z\" attributes"));
        }
        return parse_vec3_or_scalar(value, loc);
    }
    let component = |name: &str| match attrs.get(name) {
        Some(text) => parse_float(text, loc),
        None => Ok(default),
    };
    Ok(DVec3::new(
        component("x")?,
        component("y")?,
        component("z")?,
    ))
}

/// Mitsuba's look-at matrix: columns are left, up, view direction and origin, so the camera looks
/// down its local +z and its local +x points to the image's left. `None` when degenerate.
fn look_at(origin: DVec3, target: DVec3, up: DVec3) -> Option<DMat4> {
    let dir = (target - origin).normalize();
    let up = if up == DVec3::ZERO {
        any_perpendicular(dir)
    } else {
        up
    };
    let left = up.cross(dir).normalize();
    let new_up = dir.cross(left);
    let m = DMat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        origin.extend(1.0),
    );
    m.is_finite().then_some(m)
}

/// Some unit vector perpendicular to the unit vector `n` (Duff et al. 2017, as Mitsuba's
/// `coordinate_system`), used when a lookat has no up vector.
fn any_perpendicular(n: DVec3) -> DVec3 {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

/// A row-major 3×3 (linear) or 4×4 (affine) matrix.
fn matrix(text: &str, loc: &Loc) -> Result<DMat4> {
    let count = super::values::tokenize(text).len();
    match count {
        16 => {
            let v = parse_floats(text, 16, loc)?;
            let m = DMat4::from_cols_slice(&v).transpose();
            if m.row(3) != DVec4::new(0.0, 0.0, 0.0, 1.0) {
                return Err(loc.error(
                    "the last matrix row must be \"0 0 0 1\" (only affine transforms are supported)",
                ));
            }
            Ok(m)
        }
        9 => {
            let v = parse_floats(text, 9, loc)?;
            Ok(DMat4::from_mat3(DMat3::from_cols_slice(&v).transpose()))
        }
        n => Err(loc.error(format!("matrix must have 9 or 16 values, got {n}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn op(tag: &str, attrs: &[(&str, &str)]) -> Result<DMat4> {
        let attrs = Attrs::from_pairs(attrs);
        operation_matrix(tag, &attrs, &Loc::file_only(Path::new("t.xml")))
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn rotate_is_right_handed_in_degrees() {
        let m = op("rotate", &[("y", "1"), ("angle", "90")]).unwrap();
        // Rotating +x by 90 degrees about +y gives -z.
        assert!(close(m.transform_vector3(DVec3::X), -DVec3::Z));
        let m = op("rotate", &[("value", "0 0 1"), ("angle", "90")]).unwrap();
        assert!(close(m.transform_vector3(DVec3::X), DVec3::Y));
        assert!(op("rotate", &[("value", "0 0 2"), ("angle", "90")]).is_err());
    }

    #[test]
    fn matrix_is_row_major() {
        let m = op("matrix", &[("value", "1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1")]).unwrap();
        assert!(close(
            m.transform_point3(DVec3::ZERO),
            DVec3::new(5.0, 6.0, 7.0)
        ));
        let m = op("matrix", &[("value", "0 -1 0 1 0 0 0 0 1")]).unwrap();
        assert!(close(m.transform_vector3(DVec3::X), DVec3::Y));
        assert!(op("matrix", &[("value", "1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1")]).is_err());
        assert!(op("matrix", &[("value", "1 2 3")]).is_err());
    }

    #[test]
    fn lookat_maps_local_z_to_view_direction() {
        let m = op(
            "lookat",
            &[
                ("origin", "0, 0, 5"),
                ("target", "0, 0, 0"),
                ("up", "0, 1, 0"),
            ],
        )
        .unwrap();
        assert!(close(m.transform_vector3(DVec3::Z), -DVec3::Z));
        assert!(close(m.transform_vector3(DVec3::Y), DVec3::Y));
        // Local +x is image-left: looking down -z with +y up, the viewer's left is world -x.
        assert!(close(m.transform_vector3(DVec3::X), -DVec3::X));
        assert!(close(
            m.transform_point3(DVec3::ZERO),
            DVec3::new(0.0, 0.0, 5.0)
        ));
    }

    #[test]
    fn lookat_without_up_is_orthonormal() {
        let m = op("lookat", &[("origin", "1 2 3"), ("target", "4 -2 3")]).unwrap();
        let l = DMat3::from_mat4(m);
        assert!(
            (l.transpose() * l - DMat3::IDENTITY)
                .abs()
                .to_cols_array()
                .iter()
                .all(|v| *v < 1e-12)
        );
    }

    #[test]
    fn degenerate_ops_are_errors() {
        assert!(op("lookat", &[("origin", "1 1 1"), ("target", "1 1 1")]).is_err());
        assert!(
            op(
                "lookat",
                &[("origin", "0 0 0"), ("target", "0 1 0"), ("up", "0 2 0")]
            )
            .is_err()
        );
        assert!(op("rotate", &[("angle", "30")]).is_err());
        assert!(op("rotate", &[("x", "1")]).is_err());
        assert!(op("translate", &[("value", "1"), ("x", "2")]).is_err());
        assert!(op("scale", &[("w", "2")]).is_err());
    }

    #[test]
    fn scale_and_translate_defaults() {
        let m = op("scale", &[("x", "2")]).unwrap();
        assert!(close(
            m.transform_vector3(DVec3::ONE),
            DVec3::new(2.0, 1.0, 1.0)
        ));
        let m = op("scale", &[("value", "3")]).unwrap();
        assert!(close(m.transform_vector3(DVec3::ONE), DVec3::splat(3.0)));
        let m = op("translate", &[("z", "-1")]).unwrap();
        assert!(close(
            m.transform_point3(DVec3::ZERO),
            DVec3::new(0.0, 0.0, -1.0)
        ));
    }
}
