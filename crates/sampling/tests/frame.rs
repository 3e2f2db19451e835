//! Orthonormal frames: orthonormality, handedness (t = n × s) and round trips, including the poles.

use glam::Vec3;
use proptest::prelude::*;
use sampling::Frame;

mod common;

fn check_frame(n: Vec3) {
    let f = Frame::from_normal(n);
    let tolerance = 1e-5;
    assert_eq!(f.n, n);
    for (name, v) in [("s", f.s), ("t", f.t)] {
        assert!(
            (v.length() - 1.0).abs() < tolerance,
            "|{name}| = {} for n = {n}",
            v.length()
        );
        assert!(
            v.dot(n).abs() < tolerance,
            "{name} · n = {} for n = {n}",
            v.dot(n)
        );
    }
    assert!(
        f.s.dot(f.t).abs() < tolerance,
        "s · t = {} for n = {n}",
        f.s.dot(f.t)
    );
    assert!(
        (f.t - n.cross(f.s)).length() < tolerance,
        "t = {} but n × s = {} for n = {n}",
        f.t,
        n.cross(f.s)
    );
    assert!(
        (f.s.cross(f.t) - n).length() < tolerance,
        "s × t ≠ n: right-handed frame"
    );
    assert!((f.to_local(n) - Vec3::Z).length() < tolerance);
    assert!((f.to_world(Vec3::Z) - n).length() < tolerance);
    assert!((f.to_local(f.s) - Vec3::X).length() < tolerance);
    assert!((f.to_local(f.t) - Vec3::Y).length() < tolerance);
}

#[test]
fn axes_and_poles() {
    for n in [
        Vec3::X,
        Vec3::Y,
        Vec3::Z,
        -Vec3::X,
        -Vec3::Y,
        -Vec3::Z,
        Vec3::new(1.0, 0.0, -0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(1e-4, 0.0, -1.0).normalize(),
        Vec3::new(0.0, -1e-4, 1.0).normalize(),
    ] {
        check_frame(n);
    }
}

fn unit_vector() -> impl Strategy<Value = Vec3> {
    (-1.0_f32..=1.0, 0.0_f32..std::f32::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z).normalize()
    })
}

proptest! {
    #![proptest_config(common::fixed_seed(512))]

    #[test]
    fn any_normal_gives_a_right_handed_orthonormal_frame(n in unit_vector()) {
        check_frame(n);
    }

    #[test]
    fn to_world_inverts_to_local(n in unit_vector(), v in prop::array::uniform3(-10.0_f32..10.0)) {
        let f = Frame::from_normal(n);
        let v = Vec3::from(v);
        let back = f.to_world(f.to_local(v));
        prop_assert!((back - v).length() <= 1e-5 * v.length().max(1.0), "{v} -> {back}");
        prop_assert!((f.to_local(v).length() - v.length()).abs() <= 1e-5 * v.length().max(1.0));
    }
}

#[test]
fn tangent_frame_follows_the_tangent_and_falls_back_without_one() {
    let n = Vec3::new(0.36, 0.48, 0.8);
    // A tangent with a component along n, which the frame must remove.
    let dp_du = Vec3::new(2.0, 0.0, 1.0);
    let f = Frame::from_normal_and_tangent(n, dp_du);
    let expected_s = (dp_du - n * n.dot(dp_du)).normalize();
    assert!((f.s - expected_s).length() < 1e-6, "s = {}", f.s);
    assert!((f.t - n.cross(expected_s)).length() < 1e-6, "t = {}", f.t);
    assert!(f.s.dot(n).abs() < 1e-6 && (f.s.length() - 1.0).abs() < 1e-6);
    // The tangent's local coordinates put it on the +x axis of the frame.
    let local = f.to_local(dp_du);
    assert!(
        local.x > 0.0 && local.y.abs() < 1e-6,
        "local tangent {local}"
    );
    for degenerate in [Vec3::ZERO, n * 3.0, n * 3.0 + Vec3::new(1e-7, 0.0, 0.0)] {
        assert_eq!(
            Frame::from_normal_and_tangent(n, degenerate),
            Frame::from_normal(n),
            "tangent {degenerate}"
        );
    }
}
