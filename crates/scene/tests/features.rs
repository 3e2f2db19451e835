//! Mitsuba defaults and the less common features of the supported subset.

mod common;

use common::{close, data_dir, load, triangle_normal, wrap, write_scene};
use glam::{Vec2, Vec3};
use sampling::SamplerKind;
use scene::{
    BsdfDesc, DirectDesc, EmitterDesc, FilterDesc, FovAxis, Geometry, IntegratorPreset, MeshDesc,
    MicrofacetDistribution, Roughness, SamplerDesc, SceneDesc, SphereDesc,
};

fn ok(name: &str, text: &str) -> SceneDesc {
    load(name, text).unwrap_or_else(|e| panic!("{e}"))
}

fn only_mesh(desc: &SceneDesc) -> &MeshDesc {
    match &desc.shapes[0].geometry {
        Geometry::Mesh(m) => m,
        Geometry::Sphere(_) => panic!("not a mesh"),
    }
}

#[test]
fn mitsuba_defaults() {
    let desc = ok("defaults.xml", &wrap("<shape type=\"sphere\"/>"));
    assert_eq!(desc.integrator.preset, IntegratorPreset::Auto);
    assert_eq!(desc.integrator.direct, None);
    assert_eq!(desc.integrator.max_depth, -1);
    assert_eq!(desc.integrator.rr_depth, 5);
    assert!(!desc.integrator.hide_emitters);
    // 50 mm on 36×24 mm film: diagonal fov 2 atan(43.2666 / 100) = 46.793°.
    assert_eq!(desc.sensor.fov_axis, FovAxis::Diagonal);
    assert!((desc.sensor.fov_deg - 46.793).abs() < 1e-4);
    // On a 768×576 image that diagonal gives a horizontal fov of 38.18484°.
    assert!((desc.sensor.x_fov_deg(768, 576) - 38.18484).abs() < 1e-3);
    assert_eq!(desc.sensor.near_clip, 0.01);
    assert_eq!(desc.sensor.far_clip, 1e4);
    assert_eq!(desc.sensor.principal_point_offset, [0.0, 0.0]);
    assert_eq!(desc.sensor.to_world, glam::Mat4::IDENTITY);
    assert!(desc.sensor.lens.is_none());
    assert_eq!((desc.film.width, desc.film.height), (768, 576));
    assert_eq!(
        (desc.film.full_size, desc.film.crop_offset),
        ([768, 576], [0, 0])
    );
    assert_eq!(desc.film.filter, FilterDesc::Gaussian { stddev: 0.5 });
    assert_eq!(
        desc.sampler,
        SamplerDesc {
            kind: None,
            sample_count: 4,
            mitsuba_sample_count: 4,
            seed: 0
        }
    );
    assert_eq!(
        desc.shapes[0].geometry,
        Geometry::Sphere(SphereDesc {
            center: Vec3::ZERO,
            radius: 1.0,
            flip_normals: false,
            to_local: glam::Mat3::IDENTITY,
        })
    );
    assert_eq!(
        desc.bsdfs[desc.shapes[0].bsdf],
        BsdfDesc::Diffuse {
            reflectance: Vec3::splat(0.5)
        }
    );
    assert!(desc.shapes[0].emitter.is_none());
    assert!(desc.emitters.is_empty());
}

#[test]
fn bsdf_defaults_and_named_iors() {
    let desc = ok(
        "bsdf_defaults.xml",
        &wrap(
            "<bsdf type=\"dielectric\"/>
<bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"Diamond\"/><string name=\"ext_ior\" value=\"vacuum\"/></bsdf>
<bsdf type=\"roughconductor\"/>
<bsdf type=\"roughconductor\"><float name=\"alpha_u\" value=\"0.3\"/><float name=\"alpha_v\" value=\"0.3\"/><boolean name=\"sample_visible\" value=\"false\"/></bsdf>
<bsdf type=\"conductor\"><float name=\"eta\" value=\"1.5\"/><float name=\"k\" value=\"2\"/><spectrum name=\"specular_reflectance\" value=\"0.9\"/></bsdf>
<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>
<bsdf type=\"roughconductor\"><string name=\"material\" value=\"Au\"/></bsdf>",
        ),
    );
    let b = &desc.bsdfs;
    assert_eq!(
        b[0],
        BsdfDesc::Dielectric {
            int_ior: 1.5046,
            ext_ior: 1.000277,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE
        }
    );
    assert!(
        matches!(b[1], BsdfDesc::Dielectric { int_ior, ext_ior, .. } if int_ior == 2.419 && ext_ior == 1.0)
    );
    assert_eq!(
        b[2],
        BsdfDesc::RoughConductor {
            distribution: scene::MicrofacetDistribution::Beckmann,
            alpha: Roughness::isotropic(0.1),
            eta: Vec3::ZERO,
            k: Vec3::ONE,
            specular_reflectance: Vec3::ONE
        }
    );
    assert!(
        matches!(b[3], BsdfDesc::RoughConductor { alpha, .. } if alpha == Roughness::isotropic(0.3))
    );
    assert_eq!(
        b[4],
        BsdfDesc::Conductor {
            eta: Vec3::splat(1.5),
            k: Vec3::splat(2.0),
            specular_reflectance: Vec3::splat(0.9)
        }
    );
    let BsdfDesc::TwoSided { front, back } = &b[5] else {
        panic!("{:?}", b[5])
    };
    assert!(matches!(**front, BsdfDesc::Diffuse { .. }));
    assert!(matches!(**back, BsdfDesc::Conductor { .. }));
    // Gold: Mitsuba's widely quoted RGB constants are eta ≈ (0.143, 0.375, 1.442), k ≈ (3.983, 2.386, 1.603).
    let BsdfDesc::RoughConductor { eta, k, .. } = b[6] else {
        panic!("{:?}", b[6])
    };
    assert!(close(eta, Vec3::new(0.143, 0.375, 1.442), 2e-3), "{eta}");
    assert!(close(k, Vec3::new(3.983, 2.386, 1.603), 2e-3), "{k}");
}

/// `thindielectric` reads Mitsuba's defaults (bk7 in air), named indices and both multipliers;
/// equal indices are allowed (an invisible pane), unlike the solid `dielectric`.
#[test]
fn thin_dielectric_parameters() {
    let desc = ok(
        "thin.xml",
        &wrap(
            "<bsdf type=\"thindielectric\"/>
<bsdf type=\"thindielectric\"><string name=\"int_ior\" value=\"water\"/><rgb name=\"specular_reflectance\" value=\"0.5, 0.6, 0.7\"/><float name=\"specular_transmittance\" value=\"0.25\"/></bsdf>
<bsdf type=\"thindielectric\"><float name=\"int_ior\" value=\"1.2\"/><float name=\"ext_ior\" value=\"1.2\"/></bsdf>",
        ),
    );
    assert_eq!(
        desc.bsdfs[0],
        BsdfDesc::ThinDielectric {
            int_ior: 1.5046,
            ext_ior: 1.000277,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE
        }
    );
    assert_eq!(
        desc.bsdfs[1],
        BsdfDesc::ThinDielectric {
            int_ior: 1.333,
            ext_ior: 1.000277,
            specular_reflectance: Vec3::new(0.5, 0.6, 0.7),
            specular_transmittance: Vec3::splat(0.25)
        }
    );
    assert!(
        matches!(desc.bsdfs[2], BsdfDesc::ThinDielectric { int_ior, ext_ior, .. } if int_ior == 1.2 && ext_ior == 1.2)
    );
}

/// `roughdielectric` reads Mitsuba's defaults (Beckmann, α 0.1, bk7 in air, clear), the
/// distribution, roughness, named indices and both multipliers.
#[test]
fn rough_dielectric_parameters() {
    let desc = ok(
        "frosted.xml",
        &wrap(
            "<bsdf type=\"roughdielectric\"/>
<bsdf type=\"roughdielectric\"><string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.3\"/><string name=\"int_ior\" value=\"water\"/><string name=\"ext_ior\" value=\"vacuum\"/><rgb name=\"specular_transmittance\" value=\"0.5, 0.6, 0.7\"/><float name=\"specular_reflectance\" value=\"0.25\"/><boolean name=\"sample_visible\" value=\"false\"/></bsdf>",
        ),
    );
    assert_eq!(
        desc.bsdfs[0],
        BsdfDesc::RoughDielectric {
            distribution: MicrofacetDistribution::Beckmann,
            alpha: Roughness::isotropic(0.1),
            int_ior: 1.5046,
            ext_ior: 1.000277,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        }
    );
    assert_eq!(
        desc.bsdfs[1],
        BsdfDesc::RoughDielectric {
            distribution: MicrofacetDistribution::Ggx,
            alpha: Roughness::isotropic(0.3),
            int_ior: 1.333,
            ext_ior: 1.0,
            specular_reflectance: Vec3::splat(0.25),
            specular_transmittance: Vec3::new(0.5, 0.6, 0.7),
        }
    );
}

/// `plastic` reads Mitsuba's defaults (polypropylene in air, base 0.5, white coating, linear),
/// named indices, both colours and `nonlinear`, and may sit inside `twosided`.
#[test]
fn plastic_parameters() {
    let desc = ok(
        "plastic.xml",
        &wrap(
            "<bsdf type=\"plastic\"/>
<bsdf type=\"plastic\"><string name=\"int_ior\" value=\"water\"/><float name=\"ext_ior\" value=\"1.1\"/><rgb name=\"diffuse_reflectance\" value=\"0.5, 0.6, 0.7\"/><float name=\"specular_reflectance\" value=\"0.25\"/><boolean name=\"nonlinear\" value=\"true\"/></bsdf>
<bsdf type=\"twosided\"><bsdf type=\"plastic\"/></bsdf>",
        ),
    );
    let default = BsdfDesc::Plastic {
        int_ior: 1.49,
        ext_ior: 1.000277,
        diffuse_reflectance: Vec3::splat(0.5),
        specular_reflectance: Vec3::ONE,
        nonlinear: false,
    };
    assert_eq!(desc.bsdfs[0], default);
    assert_eq!(
        desc.bsdfs[1],
        BsdfDesc::Plastic {
            int_ior: 1.333,
            ext_ior: 1.1,
            diffuse_reflectance: Vec3::new(0.5, 0.6, 0.7),
            specular_reflectance: Vec3::splat(0.25),
            nonlinear: true,
        }
    );
    assert_eq!(
        desc.bsdfs[2],
        BsdfDesc::TwoSided {
            front: Box::new(default.clone()),
            back: Box::new(default),
        }
    );
}

/// `blendbsdf` reads its weight and two nested BSDFs (objects or references), and may sit inside
/// `twosided` when both reflect.
#[test]
fn blend_parameters() {
    let desc = ok(
        "blend.xml",
        &wrap(
            "<bsdf type=\"conductor\" id=\"metal\"/>
<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.3\"/><bsdf type=\"diffuse\"/><ref id=\"metal\"/></bsdf>
<bsdf type=\"twosided\"><bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"1\"/><bsdf type=\"diffuse\"/><bsdf type=\"plastic\"/></bsdf></bsdf>",
        ),
    );
    let BsdfDesc::Blend {
        first,
        second,
        weight,
    } = &desc.bsdfs[1]
    else {
        panic!("a blend: {:?}", desc.bsdfs[1]);
    };
    assert_eq!(*weight, 0.3);
    assert_eq!(**first, BsdfDesc::default_diffuse());
    assert_eq!(**second, desc.bsdfs[0]);
    assert!(
        matches!(&desc.bsdfs[2], BsdfDesc::TwoSided { front, .. } if matches!(**front, BsdfDesc::Blend { .. }))
    );
}

/// A `checkerboard` as a diffuse reflectance (nested, or declared at the top level and
/// referenced by id) becomes a checkerboard of two diffuse BSDFs with `to_uv`'s 2D affine part;
/// `twosided` and `blendbsdf` around it are hoisted inside the checkerboard.
#[test]
fn checkerboard_reflectance() {
    let desc = ok(
        "checkerboard.xml",
        &wrap(
            "<texture type=\"checkerboard\" id=\"tiles\"><rgb name=\"color0\" value=\"0.9, 0.8, 0.7\"/><float name=\"color1\" value=\"0.1\"/><transform name=\"to_uv\"><scale x=\"8\" y=\"4\"/><translate x=\"0.5\"/></transform></texture>
<bsdf type=\"diffuse\"><ref name=\"reflectance\" id=\"tiles\"/></bsdf>
<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><texture type=\"checkerboard\" name=\"reflectance\"/></bsdf></bsdf>
<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/><bsdf type=\"conductor\"/><bsdf type=\"diffuse\"><ref name=\"reflectance\" id=\"tiles\"/></bsdf></bsdf>",
        ),
    );
    let diffuse = |v: Vec3| Box::new(BsdfDesc::Diffuse { reflectance: v });
    assert_eq!(
        desc.bsdfs[0],
        BsdfDesc::Checkerboard {
            even: diffuse(Vec3::new(0.9, 0.8, 0.7)),
            odd: diffuse(Vec3::splat(0.1)),
            to_uv: [[8.0, 0.0, 0.5], [0.0, 4.0, 0.0]],
        }
    );
    let two_sided = |v: f32| {
        Box::new(BsdfDesc::TwoSided {
            front: diffuse(Vec3::splat(v)),
            back: diffuse(Vec3::splat(v)),
        })
    };
    assert_eq!(
        desc.bsdfs[1],
        BsdfDesc::Checkerboard {
            even: two_sided(0.4),
            odd: two_sided(0.2),
            to_uv: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        }
    );
    let BsdfDesc::Checkerboard { even, odd, .. } = &desc.bsdfs[2] else {
        panic!("a hoisted blend: {:?}", desc.bsdfs[2]);
    };
    assert!(
        matches!((&**even, &**odd), (BsdfDesc::Blend { second: a, .. }, BsdfDesc::Blend { second: b, .. })
            if **a == *diffuse(Vec3::new(0.9, 0.8, 0.7)) && **b == *diffuse(Vec3::splat(0.1)))
    );
}

/// A `bitmap` as a diffuse or plastic reflectance becomes the BSDF with the texture's mean
/// luminance as its albedo and the loaded texture beside it (sRGB decoded, `to_uv` applied);
/// `twosided` goes inside; a checkerboard on a plastic is a checkerboard of two plastics.
#[test]
fn bitmap_reflectance() {
    let png = data_dir().join("../../../../tests/crosscheck/texture-rgb.png");
    std::fs::copy(png, write_scene("features-texture.png", "")).unwrap();
    let bitmap = |extra: &str| {
        format!(
            "<texture type=\"bitmap\" name=\"NAME\"><string name=\"filename\" value=\"features-texture.png\"/>{extra}</texture>"
        )
    };
    let desc = ok(
        "bitmap.xml",
        &wrap(&format!(
            "<bsdf type=\"diffuse\">{}</bsdf>
<bsdf type=\"twosided\"><bsdf type=\"diffuse\">{}</bsdf></bsdf>
<bsdf type=\"plastic\">{}</bsdf>
<bsdf type=\"plastic\"><texture type=\"checkerboard\" name=\"diffuse_reflectance\"/></bsdf>",
            bitmap("<string name=\"filter_type\" value=\"nearest\"/>")
                .replace("NAME", "reflectance"),
            bitmap("<transform name=\"to_uv\"><scale x=\"2\"/></transform>")
                .replace("NAME", "reflectance"),
            bitmap("").replace("NAME", "diffuse_reflectance"),
        )),
    );
    let BsdfDesc::DiffuseBitmap { base, texture } = &desc.bsdfs[0] else {
        panic!("not a bitmap: {:?}", desc.bsdfs[0]);
    };
    let mean = texture.mean_luminance();
    assert!(mean > 0.05 && mean < 0.95, "mean luminance {mean}");
    assert_eq!(
        **base,
        BsdfDesc::Diffuse {
            reflectance: Vec3::splat(mean)
        }
    );
    // Texel (5, 2) of the 32 x 16 image is white, (20, 11) black: nearest lookups at their centres.
    let centre = |x: f32, y: f32| Vec2::new((x + 0.5) / 32.0, (y + 0.5) / 16.0);
    assert_eq!(texture.eval(centre(5.0, 2.0)), Vec3::ONE);
    assert_eq!(texture.eval(centre(20.0, 11.0)), Vec3::ZERO);
    let BsdfDesc::DiffuseBitmap {
        base,
        texture: scaled,
    } = &desc.bsdfs[1]
    else {
        panic!("not a bitmap: {:?}", desc.bsdfs[1]);
    };
    assert!(matches!(**base, BsdfDesc::TwoSided { .. }), "{base:?}");
    // With u scaled by 2, u = 0.25 reads what u = 0.5 reads unscaled.
    let unscaled = &desc.bsdfs[2];
    let BsdfDesc::DiffuseBitmap {
        base,
        texture: plain,
    } = unscaled
    else {
        panic!("not a bitmap: {unscaled:?}");
    };
    assert!(matches!(**base, BsdfDesc::Plastic { .. }), "{base:?}");
    let uv = Vec2::new(0.25, 0.4);
    assert_eq!(scaled.eval(uv), plain.eval(Vec2::new(0.5, 0.4)));
    assert!(
        matches!(&desc.bsdfs[3], BsdfDesc::Checkerboard { even, odd, .. }
            if matches!((&**even, &**odd), (BsdfDesc::Plastic { .. }, BsdfDesc::Plastic { .. })))
    );
}

/// A blend's weight may be a texture: a checkerboard becomes a checkerboard of two blends, the
/// even squares weighted by `color1`'s mean over RGB and the odd ones by `color0`'s (Mitsuba's
/// `eval_1`); a bitmap gives the blend with the texture's mean luminance and the texture.
#[test]
fn blend_weight_textures() {
    let png = data_dir().join("../../../../tests/crosscheck/texture-rgb.png");
    std::fs::copy(png, write_scene("blend-weight.png", "")).unwrap();
    let desc = ok(
        "blend_weight.xml",
        &wrap(
            "<bsdf type=\"blendbsdf\"><texture type=\"checkerboard\" name=\"weight\"><rgb name=\"color0\" value=\"0.9, 0.6, 0.3\"/><float name=\"color1\" value=\"0.2\"/></texture><bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>
<texture type=\"bitmap\" id=\"w\"><string name=\"filename\" value=\"blend-weight.png\"/></texture>
<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><ref name=\"weight\" id=\"w\"/><bsdf type=\"conductor\"/></bsdf>",
        ),
    );
    let weight_of = |b: &BsdfDesc| match b {
        BsdfDesc::Blend { weight, .. } => *weight,
        other => panic!("not a blend: {other:?}"),
    };
    let BsdfDesc::Checkerboard { even, odd, .. } = &desc.bsdfs[0] else {
        panic!("not a checkerboard: {:?}", desc.bsdfs[0]);
    };
    assert!((weight_of(even) - 0.2).abs() < 1e-6);
    assert!((weight_of(odd) - 0.6).abs() < 1e-6);
    let BsdfDesc::TexturedBlend {
        base,
        weight: Some(texture),
        reflectances: [None, None],
    } = &desc.bsdfs[1]
    else {
        panic!("not a bitmap weight: {:?}", desc.bsdfs[1]);
    };
    assert_eq!(weight_of(base), texture.mean_luminance());
    assert!(matches!(&**base, BsdfDesc::Blend { first, second, .. }
        if matches!(**first, BsdfDesc::Diffuse { .. }) && matches!(**second, BsdfDesc::Conductor { .. })));
}

/// `mask` is a blend of `null` (weight 0) and its nested BSDF (weight 1) by `opacity`: ½ by
/// default, a constant, or a texture (a bitmap gives the blend with its mean luminance).
#[test]
fn mask_is_a_blend_with_null() {
    let png = data_dir().join("../../../../tests/crosscheck/texture-rgb.png");
    std::fs::copy(png, write_scene("mask-opacity.png", "")).unwrap();
    let desc = ok(
        "mask.xml",
        &wrap(
            "<bsdf type=\"mask\"><bsdf type=\"conductor\"/></bsdf>
<bsdf type=\"mask\"><float name=\"opacity\" value=\"0.25\"/><bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></bsdf>
<bsdf type=\"mask\"><texture type=\"bitmap\" name=\"opacity\"><string name=\"filename\" value=\"mask-opacity.png\"/></texture><bsdf type=\"diffuse\"/></bsdf>",
        ),
    );
    let null = BsdfDesc::ThinDielectric {
        int_ior: 1.0,
        ext_ior: 1.0,
        specular_reflectance: Vec3::ZERO,
        specular_transmittance: Vec3::ONE,
    };
    let blend = |b: &BsdfDesc| match b {
        BsdfDesc::Blend {
            first,
            second,
            weight,
        } => ((**first).clone(), (**second).clone(), *weight),
        other => panic!("not a blend: {other:?}"),
    };
    let (first, second, weight) = blend(&desc.bsdfs[0]);
    assert_eq!((first, weight), (null.clone(), 0.5));
    assert!(matches!(second, BsdfDesc::Conductor { .. }));
    let (first, second, weight) = blend(&desc.bsdfs[1]);
    assert_eq!((first, weight), (null.clone(), 0.25));
    assert!(matches!(second, BsdfDesc::TwoSided { .. }));
    let BsdfDesc::TexturedBlend {
        base,
        weight: Some(texture),
        reflectances: [None, None],
    } = &desc.bsdfs[2]
    else {
        panic!("not a bitmap opacity: {:?}", desc.bsdfs[2]);
    };
    let (first, second, weight) = blend(base);
    assert_eq!((first, weight), (null, texture.mean_luminance()));
    assert_eq!(second, BsdfDesc::default_diffuse());
}

/// `null` is an invisible surface: a thin slab of equal indices that reflects nothing.
#[test]
fn null_bsdf_is_a_clear_thin_slab() {
    let desc = ok("null.xml", &wrap("<bsdf type=\"null\"/>"));
    assert_eq!(
        desc.bsdfs[0],
        BsdfDesc::ThinDielectric {
            int_ior: 1.0,
            ext_ior: 1.0,
            specular_reflectance: Vec3::ZERO,
            specular_transmittance: Vec3::ONE,
        }
    );
}

/// `roughplastic` reads Mitsuba's defaults (Beckmann, α 0.1, polypropylene in air, base 0.5,
/// white coating, linear) and every parameter, and may sit inside `twosided`.
#[test]
fn rough_plastic_parameters() {
    let desc = ok(
        "rough_plastic.xml",
        &wrap(
            "<bsdf type=\"roughplastic\"/>
<bsdf type=\"twosided\"><bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"GGX\"/><float name=\"alpha\" value=\"0.25\"/><float name=\"int_ior\" value=\"1.6\"/><rgb name=\"diffuse_reflectance\" value=\"0.1, 0.2, 0.3\"/><float name=\"specular_reflectance\" value=\"0.5\"/><boolean name=\"nonlinear\" value=\"true\"/></bsdf></bsdf>",
        ),
    );
    assert_eq!(
        desc.bsdfs[0],
        BsdfDesc::RoughPlastic {
            distribution: MicrofacetDistribution::Beckmann,
            alpha: 0.1,
            int_ior: 1.49,
            ext_ior: 1.000277,
            diffuse_reflectance: Vec3::splat(0.5),
            specular_reflectance: Vec3::ONE,
            nonlinear: false,
        }
    );
    let inner = BsdfDesc::RoughPlastic {
        distribution: MicrofacetDistribution::Ggx,
        alpha: 0.25,
        int_ior: 1.6,
        ext_ior: 1.000277,
        diffuse_reflectance: Vec3::new(0.1, 0.2, 0.3),
        specular_reflectance: Vec3::splat(0.5),
        nonlinear: true,
    };
    assert_eq!(
        desc.bsdfs[1],
        BsdfDesc::TwoSided {
            front: Box::new(inner.clone()),
            back: Box::new(inner),
        }
    );
}

/// `envmap` reads its OpenEXR image (here the crosscheck's 64 × 32 sky, whose 2 × 2-texel sun
/// is at rows 6–7, columns 20–21), `scale` and `to_world`; an unreadable file is an error that
/// names it.
#[test]
fn environment_map_parameters() {
    let sky =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/crosscheck/sky.exr");
    let desc = ok(
        "envmap.xml",
        &wrap(&format!(
            "<emitter type=\"envmap\"><string name=\"filename\" value=\"{}\"/><float name=\"scale\" value=\"0.5\"/><transform name=\"to_world\"><rotate y=\"1\" angle=\"90\"/></transform><boolean name=\"mis_compensation\" value=\"true\"/></emitter>",
            sky.display()
        )),
    );
    let EmitterDesc::EnvMap {
        width,
        height,
        texels,
        scale,
        to_world,
        sampling_weight,
    } = &desc.emitters[0]
    else {
        panic!("an environment map: {:?}", desc.emitters[0]);
    };
    assert_eq!(
        (*width, *height, *scale, *sampling_weight),
        (64, 32, 0.5, 1.0)
    );
    assert!(close(
        texels[6 * 64 + 20],
        Vec3::new(120.0, 105.0, 90.0),
        1e-3
    ));
    assert!(close(*to_world * Vec3::X, -Vec3::Z, 1e-6), "{to_world}");
    let not_an_image = write_scene("not_an_image.exr", "plain text");
    let text = wrap(&format!(
        "<emitter type=\"envmap\"><string name=\"filename\" value=\"{}\"/></emitter>",
        not_an_image.display()
    ));
    let path = write_scene("bad_envmap.xml", &text);
    let err = scene::parse_file(&path, &[]).expect_err("not an EXR file");
    assert!(
        err.message.contains("cannot read environment map") && err.message.contains("not_an_image"),
        "{err}"
    );
}

/// `spot` and `directional` read Mitsuba's defaults (cutoff 20°, beam 3/4 of it; +z) and place
/// themselves by `to_world` or `direction`.
#[test]
fn spot_and_directional_parameters() {
    let desc = ok(
        "spot.xml",
        &wrap(
            "<emitter type=\"spot\"/>
<emitter type=\"spot\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/><translate x=\"1\" y=\"2\" z=\"3\"/></transform><float name=\"cutoff_angle\" value=\"40\"/><float name=\"beam_width\" value=\"5\"/><rgb name=\"intensity\" value=\"1, 2, 3\"/></emitter>
<emitter type=\"directional\"/>
<emitter type=\"directional\"><vector name=\"direction\" value=\"0, -3, 0\"/><float name=\"irradiance\" value=\"2\"/></emitter>
<emitter type=\"directional\"><transform name=\"to_world\"><rotate y=\"1\" angle=\"90\"/></transform></emitter>",
        ),
    );
    let e = &desc.emitters;
    assert!(
        matches!(e[0], EmitterDesc::Spot { position, cutoff_angle, beam_width, intensity, .. }
            if position == Vec3::ZERO && cutoff_angle == 20.0 && beam_width == 15.0 && intensity == Vec3::ONE),
        "{:?}",
        e[0]
    );
    let EmitterDesc::Spot {
        position,
        axes,
        cutoff_angle,
        beam_width,
        intensity,
        ..
    } = e[1]
    else {
        panic!("{:?}", e[1])
    };
    assert_eq!(
        (position, cutoff_angle, beam_width),
        (Vec3::new(1.0, 2.0, 3.0), 40.0, 5.0)
    );
    assert_eq!(intensity, Vec3::new(1.0, 2.0, 3.0));
    // Rotating +z by 90 degrees about x points the axis down -y.
    assert!(close(axes.z_axis, Vec3::NEG_Y, 1e-6), "{axes}");
    let direction = |i: usize| match e[i] {
        EmitterDesc::Directional {
            direction,
            irradiance,
            ..
        } => (direction, irradiance),
        ref other => panic!("{other:?}"),
    };
    assert_eq!(direction(2), (Vec3::Z, Vec3::ONE));
    assert_eq!(direction(3), (Vec3::NEG_Y, Vec3::splat(2.0)));
    assert!(close(direction(4).0, Vec3::X, 1e-6), "{:?}", direction(4));
}

/// `direct`'s counts as Mitsuba reads them: `shading_samples` sets both, each may be zero.
#[test]
fn direct_sample_counts() {
    let kind = |body: &str| {
        ok(
            "direct_counts.xml",
            &format!(
                "<scene version=\"3.0.0\"><integrator type=\"direct\">{body}</integrator>\
                 <sensor type=\"perspective\"/></scene>"
            ),
        )
        .integrator
        .direct
    };
    let direct = |emitter_samples, bsdf_samples| {
        Some(DirectDesc {
            emitter_samples,
            bsdf_samples,
        })
    };
    assert_eq!(kind(""), direct(1, 1));
    assert_eq!(
        kind("<integer name=\"shading_samples\" value=\"4\"/>"),
        direct(4, 4)
    );
    assert_eq!(
        kind("<integer name=\"emitter_samples\" value=\"3\"/>"),
        direct(3, 1)
    );
    assert_eq!(
        kind(
            "<integer name=\"emitter_samples\" value=\"0\"/><integer name=\"bsdf_samples\" value=\"5\"/>"
        ),
        direct(0, 5)
    );
}

/// Mitsuba's filters with negative lobes and their parameters.
#[test]
fn filters_with_negative_lobes() {
    let filter = |body: &str| {
        ok(
            "filters.xml",
            &format!(
                "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\">\
                 <film type=\"hdrfilm\">{body}</film></sensor></scene>"
            ),
        )
        .film
        .filter
    };
    assert_eq!(
        filter("<rfilter type=\"mitchell\"/>"),
        FilterDesc::Mitchell {
            b: 1.0 / 3.0,
            c: 1.0 / 3.0
        }
    );
    assert_eq!(
        filter(
            "<rfilter type=\"mitchell\"><float name=\"B\" value=\"0.5\"/><float name=\"C\" value=\"0.25\"/></rfilter>"
        ),
        FilterDesc::Mitchell { b: 0.5, c: 0.25 }
    );
    assert_eq!(
        filter("<rfilter type=\"catmullrom\"/>"),
        FilterDesc::CatmullRom
    );
    assert_eq!(
        filter("<rfilter type=\"lanczos\"/>"),
        FilterDesc::Lanczos { lobes: 3 }
    );
    assert_eq!(
        filter("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"2\"/></rfilter>"),
        FilterDesc::Lanczos { lobes: 2 }
    );
}

/// Spectra as wavelength:value pairs become sRGB as in Mitsuba's RGB variants: a flat reflectance
/// is grey, an emitter's spectrum is not weighted by D65, a spectral reflectance that rises
/// towards the red is reddish.
#[test]
fn spectra_given_by_wavelengths() {
    let desc = ok(
        "spectra.xml",
        "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\"/>
<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"360:0.5, 830:0.5\"/></bsdf></shape>
<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"400:0.1 550:0.3 700:0.9\"/></bsdf>
  <emitter type=\"area\"><spectrum name=\"radiance\" value=\"360:2, 830:2\"/></emitter></shape>
</scene>",
    );
    let reflectance = |i: usize| match &desc.bsdfs[desc.shapes[i].bsdf] {
        BsdfDesc::Diffuse { reflectance } => *reflectance,
        other => panic!("not diffuse: {other:?}"),
    };
    let grey = reflectance(0);
    assert!(
        (grey - Vec3::splat(0.5)).abs().max_element() < 1e-3,
        "{grey}"
    );
    let reddish = reflectance(1);
    assert!(reddish.x > reddish.y && reddish.y > reddish.z, "{reddish}");
    let radiance = desc.shapes[1]
        .emitter
        .as_ref()
        .expect("an emitter")
        .radiance;
    // The equal-energy spectrum, as a uniform <spectrum value="2"/> emission gives it.
    let uniform = ok(
        "uniform.xml",
        "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\"/>
<shape type=\"sphere\"><emitter type=\"area\"><spectrum name=\"radiance\" value=\"2\"/></emitter></shape>
</scene>",
    );
    let expected = uniform.shapes[0]
        .emitter
        .as_ref()
        .expect("an emitter")
        .radiance;
    assert!(
        ((radiance - expected).abs() / expected).max_element() < 5e-3,
        "{radiance} against {expected}"
    );
}

#[test]
fn principal_point_offset() {
    let desc = ok(
        "offset.xml",
        "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\">\
         <float name=\"principal_point_offset_x\" value=\"0.2\"/>\
         <float name=\"principal_point_offset_y\" value=\"-0.05\"/></sensor></scene>",
    );
    assert_eq!(desc.sensor.principal_point_offset, [0.2, -0.05]);
}

#[test]
fn thin_lens_and_focal_length() {
    let desc = ok(
        "thinlens.xml",
        "<scene version=\"2.1.0\">
<integrator type=\"direct\"><boolean name=\"hide_emitters\" value=\"true\"/></integrator>
<sensor type=\"thinlens\">
  <float name=\"aperture_radius\" value=\"0.05\"/>
  <float name=\"focus_distance\" value=\"4\"/>
  <string name=\"focal_length\" value=\"35mm\"/>
  <float name=\"near_clip\" value=\"0.1\"/>
  <film type=\"hdrfilm\"><rfilter type=\"box\"/></film>
</sensor>
</scene>",
    );
    assert_eq!(
        desc.integrator.direct,
        Some(DirectDesc {
            emitter_samples: 1,
            bsdf_samples: 1
        })
    );
    assert_eq!(desc.integrator.preset, IntegratorPreset::Auto);
    assert_eq!(desc.integrator.max_depth, 2);
    assert!(desc.integrator.hide_emitters);
    let lens = desc.sensor.lens.unwrap();
    assert_eq!(lens.aperture_radius, 0.05);
    assert_eq!(lens.focus_distance, 4.0);
    // 35 mm: 2 atan(43.2666 / 70) = 63.43997° diagonal.
    assert!((desc.sensor.fov_deg - 63.43997).abs() < 1e-3);
    assert_eq!(desc.sensor.fov_axis, FovAxis::Diagonal);
    assert_eq!(desc.sensor.near_clip, 0.1);
    assert_eq!(desc.film.filter, FilterDesc::Box);

    // Without focus_distance the lens focuses at far_clip, as Mitsuba's projective cameras do.
    let desc = ok(
        "thinlens2.xml",
        "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0\"/><float name=\"far_clip\" value=\"50\"/><float name=\"fov\" value=\"30\"/><string name=\"fov_axis\" value=\"Y\"/></sensor></scene>",
    );
    assert_eq!(desc.sensor.lens.unwrap().focus_distance, 50.0);
    assert_eq!(desc.sensor.fov_axis, FovAxis::Y);
    // fov 30° on y of a 4:3 image: x_fov = 2 atan(tan 15° · 4/3) = 39.32012°.
    assert!((desc.sensor.x_fov_deg(800, 600) - 39.32012).abs() < 1e-3);
}

#[test]
fn emitters() {
    let desc = ok(
        "emitters.xml",
        &wrap(
            "<emitter type=\"point\"><transform name=\"to_world\"><translate x=\"1\" y=\"2\" z=\"3\"/></transform></emitter>
<emitter type=\"constant\"><spectrum name=\"radiance\" value=\"2\"/></emitter>
<emitter type=\"constant\"><float name=\"radiance\" value=\"2\"/></emitter>
<emitter type=\"point\"/>
<shape type=\"rectangle\"><emitter type=\"area\"/></shape>",
        ),
    );
    assert_eq!(
        desc.emitters[0],
        EmitterDesc::Point {
            position: Vec3::new(1.0, 2.0, 3.0),
            intensity: Vec3::ONE,
            sampling_weight: 1.0
        }
    );
    // A uniform emission spectrum is 2 · xyz_to_srgb(1, 1, 1) in Mitsuba's RGB variants.
    let EmitterDesc::Constant { radiance, .. } = desc.emitters[1] else {
        panic!()
    };
    assert!(close(
        radiance,
        2.0 * Vec3::new(1.204794, 0.948291, 0.908916),
        1e-5
    ));
    assert_eq!(
        desc.emitters[2],
        EmitterDesc::Constant {
            radiance: Vec3::splat(2.0),
            sampling_weight: 1.0
        }
    );
    assert_eq!(
        desc.emitters[3],
        EmitterDesc::Point {
            position: Vec3::ZERO,
            intensity: Vec3::ONE,
            sampling_weight: 1.0
        }
    );
    assert_eq!(desc.shapes[0].emitter.unwrap().radiance, Vec3::ONE);
}

/// The sampler `plugin` with `sample_count`, as the loader reads it.
fn sampler(plugin: &str, sample_count: u32) -> SamplerDesc {
    ok(
        &format!("sampler-{plugin}-{sample_count}.xml"),
        &format!(
            "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\">\
             <sampler type=\"{plugin}\"><integer name=\"sample_count\" value=\"{sample_count}\"/>\
             </sampler></sensor></scene>"
        ),
    )
    .sampler
}

#[test]
fn mitsuba_samplers_map_to_the_nearest_strata_sampler() {
    // `independent` is Mitsuba's default and carries no intent: no sampler is chosen.
    assert_eq!(sampler("independent", 4).kind, None);
    for plugin in ["stratified", "multijitter", "orthogonal"] {
        assert_eq!(
            sampler(plugin, 4).kind,
            Some(SamplerKind::Stratified),
            "{plugin}"
        );
    }
    assert_eq!(sampler("ldsampler", 4).kind, Some(SamplerKind::Sobol));
    assert_eq!(sampler("stratified", 10).sample_count, 10);
}

/// Every Strata sampler is a `<sampler type>` by its command-line name, read by the same
/// `FromStr` as `--sampler` (`independent`, Mitsuba's default, reads as no choice, which renders
/// independent samples); a name that is neither Strata's nor Mitsuba's is an error naming every
/// sampler there is.
#[test]
fn strata_sampler_names_are_sampler_types() {
    for kind in SamplerKind::ALL {
        let read = sampler(kind.name(), 4);
        assert_eq!(read.kind.unwrap_or_default(), kind, "{kind}");
        assert_eq!(read.mitsuba_sample_count, 4, "{kind}");
    }
    let err = load(
        "sampler-halton.xml",
        "<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\">\
         <sampler type=\"halton\"/></sensor></scene>",
    )
    .expect_err("halton is no sampler");
    assert!(
        err.message.contains("unknown sampler type \"halton\""),
        "{err}"
    );
    let supported = SamplerKind::ALL.map(SamplerKind::name).into_iter().chain([
        "multijitter",
        "orthogonal",
        "ldsampler",
    ]);
    for name in supported {
        assert!(err.message.contains(name), "{err} does not name {name}");
    }
}

#[test]
fn sampler_counts_follow_mitsuba_rounding() {
    let count = |plugin, sample_count| sampler(plugin, sample_count).mitsuba_sample_count;
    assert_eq!(count("independent", 10), 10);
    assert_eq!(count("stratified", 10), 16);
    assert_eq!(count("stratified", 16), 16);
    assert_eq!(count("multijitter", 10), 12);
    assert_eq!(count("ldsampler", 10), 16);
    assert_eq!(count("ldsampler", 17), 64);
    assert_eq!(count("ldsampler", 1), 4);
    // Orthogonal arrays: the square of the next prime (4 is 2², 10 rounds to 5², 26 to 7²).
    for (spp, expected) in [(4, 4), (5, 9), (9, 9), (10, 25), (26, 49)] {
        assert_eq!(count("orthogonal", spp), expected, "orthogonal {spp}");
    }
}

/// `cylinder` from `p0` to `p1` with `radius`: its vertices lie on the tube (within the facets'
/// enlargement), its area is 2π r |p1 − p0| and its normals point away from the axis, or
/// towards it with `flip_normals`.
#[test]
fn cylinder_shape() {
    for flip in [false, true] {
        let desc = ok(
            "cylinder.xml",
            &wrap(&format!(
                "<shape type=\"cylinder\"><point name=\"p0\" value=\"1, 2, 3\"/><point name=\"p1\" value=\"1, 2, 5\"/><float name=\"radius\" value=\"0.5\"/><boolean name=\"flip_normals\" value=\"{flip}\"/></shape>"
            )),
        );
        let Geometry::Mesh(mesh) = &desc.shapes[0].geometry else {
            panic!("a mesh: {:?}", desc.shapes[0].geometry);
        };
        let axis_point = |p: Vec3| Vec3::new(1.0, 2.0, p.z);
        let mut area = 0.0;
        for (i, _) in mesh.triangles.iter().enumerate() {
            let n = triangle_normal(mesh, i);
            let [a, b, c] = mesh.triangles[i].map(|v| mesh.positions[v as usize]);
            area += 0.5 * (b - a).cross(c - a).length();
            let centroid = (a + b + c) / 3.0;
            let outward = (centroid - axis_point(centroid)).normalize();
            let expected = if flip { -1.0 } else { 1.0 };
            assert!(
                (n.dot(outward) - expected).abs() < 1e-3,
                "flip {flip}, triangle {i}: {n}"
            );
        }
        assert!(
            (area - std::f32::consts::TAU * 0.5 * 2.0).abs() < 1e-3,
            "area {area}"
        );
        for p in &mesh.positions {
            let r = (*p - axis_point(*p)).length();
            assert!((r - 0.5).abs() < 1e-4 && (3.0..=5.0).contains(&p.z), "{p}");
        }
    }
}

/// A `shapegroup` is drawn only where an `instance` places it: each instance adds the group's
/// shapes moved by its `to_world` (meshes and spheres alike), the group read once.
#[test]
fn shape_groups_and_instances() {
    let desc = ok(
        "instances.xml",
        &wrap(
            "<shape type=\"shapegroup\" id=\"pair\"><shape type=\"rectangle\"/><shape type=\"sphere\"><point name=\"center\" value=\"0, 0, 2\"/><float name=\"radius\" value=\"0.5\"/></shape></shape>
<shape type=\"instance\"><ref id=\"pair\"/><transform name=\"to_world\"><translate x=\"10\"/></transform></shape>
<shape type=\"instance\"><ref id=\"pair\"/><transform name=\"to_world\"><scale value=\"2\"/><translate y=\"-5\"/></transform></shape>",
        ),
    );
    assert_eq!(
        desc.shapes.len(),
        4,
        "two instances of two shapes, the group itself not drawn"
    );
    let Geometry::Mesh(first) = &desc.shapes[0].geometry else {
        panic!("a mesh: {:?}", desc.shapes[0].geometry);
    };
    assert!(
        first
            .positions
            .iter()
            .all(|p| (p.x - 10.0).abs() <= 1.0 && p.z == 0.0)
    );
    let Geometry::Sphere(moved) = &desc.shapes[1].geometry else {
        panic!("a sphere: {:?}", desc.shapes[1].geometry);
    };
    assert!(close(moved.center, Vec3::new(10.0, 0.0, 2.0), 1e-6) && moved.radius == 0.5);
    let Geometry::Sphere(scaled) = &desc.shapes[3].geometry else {
        panic!("a sphere: {:?}", desc.shapes[3].geometry);
    };
    assert!(close(scaled.center, Vec3::new(0.0, -5.0, 4.0), 1e-6) && scaled.radius == 1.0);
}

/// `orthographic` takes to_world (scaling allowed: it sizes the viewing region) and the
/// clipping planes; a field of view is an unknown parameter for it.
#[test]
fn orthographic_sensor() {
    let text = wrap("").replace(
        "<sensor type=\"perspective\"/>",
        "<sensor type=\"orthographic\"><transform name=\"to_world\"><scale x=\"2\" y=\"2\"/><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform><float name=\"near_clip\" value=\"0.1\"/></sensor>",
    );
    let desc = ok("orthographic.xml", &text);
    assert!(desc.sensor.orthographic && desc.sensor.lens.is_none());
    assert_eq!(desc.sensor.near_clip, 0.1);
    let with_fov = wrap("").replace(
        "<sensor type=\"perspective\"/>",
        "<sensor type=\"orthographic\"><float name=\"fov\" value=\"45\"/></sensor>",
    );
    let path = write_scene("orthographic_fov.xml", &with_fov);
    let err = scene::parse_file(&path, &[]).expect_err("fov is not an orthographic parameter");
    assert!(err.message.contains("fov"), "{err}");
}

/// `volpath`, `volpathmis`, `prb` and `prbvolpath` read as the path tracer with the same
/// parameters (Strata reads no media, and without media Mitsuba's volumetric path tracers are its
/// path tracer but for passes through null lobes, which are no path vertices to them; the path
/// replay integrators render `path`'s and `volpath`'s images), the last two with Mitsuba's
/// default depth 6 when the file gives none.
#[test]
fn volumetric_path_tracers_are_the_path_tracer() {
    for plugin in ["volpath", "volpathmis", "prb", "prbvolpath"] {
        let text = wrap("").replace(
            "<integrator type=\"path\"/>",
            &format!(
                "<integrator type=\"{plugin}\"><integer name=\"max_depth\" value=\"7\"/><integer name=\"rr_depth\" value=\"3\"/><boolean name=\"hide_emitters\" value=\"true\"/></integrator>"
            ),
        );
        let desc = ok(&format!("{plugin}.xml"), &text);
        assert_eq!(desc.integrator.preset, IntegratorPreset::Auto, "{plugin}");
        assert_eq!(desc.integrator.direct, None, "{plugin}");
        assert_eq!(
            (
                desc.integrator.max_depth,
                desc.integrator.rr_depth,
                desc.integrator.hide_emitters
            ),
            (7, 3, true),
            "{plugin}"
        );
        let defaults = wrap("").replace(
            "<integrator type=\"path\"/>",
            &format!("<integrator type=\"{plugin}\"/>"),
        );
        let desc = ok(&format!("{plugin}-defaults.xml"), &defaults);
        let depth = if plugin.starts_with("prb") { 6 } else { -1 };
        assert_eq!(desc.integrator.max_depth, depth, "{plugin}");
        assert_eq!(
            desc.integrator.skip_null_vertices,
            plugin != "prb",
            "{plugin}"
        );
    }
    let path = ok("path.xml", &wrap(""));
    assert!(!path.integrator.skip_null_vertices);
}

/// Strata's presets by name in `<integrator type>`, parsed as the command line parses them, with
/// `path`'s parameters; an unknown type is an error naming the element, its line and every
/// supported type.
#[test]
fn strata_presets_are_integrator_types() {
    for preset in IntegratorPreset::ALL {
        let text = wrap("").replace(
            "<integrator type=\"path\"/>",
            &format!(
                "<integrator type=\"{preset}\"><integer name=\"max_depth\" value=\"4\"/><integer name=\"rr_depth\" value=\"2\"/></integrator>"
            ),
        );
        let desc = ok(&format!("preset-{preset}.xml"), &text);
        assert_eq!(desc.integrator.preset, preset);
        assert_eq!(
            (
                desc.integrator.direct,
                desc.integrator.max_depth,
                desc.integrator.rr_depth,
                desc.integrator.hide_emitters,
                desc.integrator.skip_null_vertices
            ),
            (None, 4, 2, false, false),
            "{preset}"
        );
    }
    let text = wrap("").replace("<integrator type=\"path\"/>", "<integrator type=\"bdpt\"/>");
    let err = load("bdpt.xml", &text).unwrap_err();
    assert_eq!(err.line, 2, "{err}");
    let message = err.to_string();
    for name in [
        "bdpt",
        "<integrator",
        "path",
        "direct",
        "reference",
        "nee",
        "mis",
        "ris",
        "auto",
    ] {
        assert!(message.contains(name), "{name}: {message}");
    }
}

#[test]
fn preset_names_parse_and_print() {
    for preset in IntegratorPreset::ALL {
        assert_eq!(preset.to_string().parse::<IntegratorPreset>(), Ok(preset));
    }
    assert_eq!(
        "path".parse::<IntegratorPreset>(),
        Ok(IntegratorPreset::Auto)
    );
    assert_eq!(IntegratorPreset::default(), IntegratorPreset::Auto);
    let err = "direct".parse::<IntegratorPreset>().unwrap_err();
    assert_eq!(
        err.to_string(),
        "no integrator called 'direct' (expected reference, nee, mis, ris, auto or path)"
    );
}

#[test]
fn escaped_dollar_and_include_with_forward_reference() {
    write_scene(
        "materials.xml",
        "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\" id=\"cost\\$\"><rgb name=\"reflectance\" value=\"0.2\"/></bsdf>\n</scene>",
    );
    let desc = ok(
        "includes.xml",
        &wrap(
            "<shape type=\"cube\"><ref id=\"cost\\$\"/></shape>\n<include filename=\"materials.xml\"/>",
        ),
    );
    assert_eq!(
        desc.bsdfs[desc.shapes[0].bsdf],
        BsdfDesc::Diffuse {
            reflectance: Vec3::splat(0.2)
        }
    );
}

#[test]
fn ply_binary_endianness_and_ascii_polygons() {
    let load_ply = |file: &str, extra: &str| {
        ok(
            &format!("ply_{}.xml", file.replace('.', "_")),
            &wrap(&format!(
                "<shape type=\"ply\"><string name=\"filename\" value=\"meshes/{file}\"/>{extra}</shape>"
            )),
        )
    };
    let le = load_ply("quad_le.ply", "");
    let be = load_ply("quad_be.ply", "");
    assert_eq!(only_mesh(&le), only_mesh(&be));
    let m = only_mesh(&le);
    assert_eq!(m.positions[4], Vec3::new(0.5, 0.5, 1.0));
    assert_eq!(m.uvs.as_ref().unwrap()[1], Vec2::new(1.0, 0.0));

    let flipped = load_ply(
        "quad_le.ply",
        "<boolean name=\"flip_tex_coords\" value=\"true\"/>",
    );
    assert_eq!(
        only_mesh(&flipped).uvs.as_ref().unwrap()[1],
        Vec2::new(1.0, 1.0)
    );

    let pentagon = load_ply("pentagon.ply", "");
    let m = only_mesh(&pentagon);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    assert_eq!(m.uvs.as_ref().unwrap()[3], Vec2::new(0.5, 1.0));
    // No normals in the file and no face_normals: smooth normals are computed (a flat polygon).
    assert!(
        m.normals
            .as_ref()
            .unwrap()
            .iter()
            .all(|n| close(*n, Vec3::Z, 1e-6))
    );

    let faceted = load_ply(
        "pentagon.ply",
        "<boolean name=\"face_normals\" value=\"true\"/>",
    );
    assert!(only_mesh(&faceted).normals.is_none());
}

#[test]
fn obj_without_normals_gets_angle_weighted_normals() {
    let desc = ok(
        "obj_smooth.xml",
        &wrap("<shape type=\"obj\"><string name=\"filename\" value=\"meshes/box.obj\"/></shape>"),
    );
    let m = only_mesh(&desc);
    assert_eq!(m.triangles.len(), 12);
    let normals = m.normals.as_ref().unwrap();
    // Each corner touches three faces with 90° of angle each: the normal is the diagonal.
    let corner = m.positions.iter().position(|p| *p == Vec3::ONE).unwrap();
    assert!(close(normals[corner], Vec3::ONE.normalize(), 1e-6));
    let origin = m.positions.iter().position(|p| *p == Vec3::ZERO).unwrap();
    assert!(close(normals[origin], -Vec3::ONE.normalize(), 1e-6));
}

#[test]
fn mirrored_mesh_keeps_normals_consistent() {
    let desc = ok(
        "mirror.xml",
        &wrap(
            "<shape type=\"ply\"><string name=\"filename\" value=\"meshes/quad_le.ply\"/>
<transform name=\"to_world\"><scale x=\"-1\"/></transform></shape>",
        ),
    );
    let m = only_mesh(&desc);
    let normals = m.normals.as_ref().unwrap();
    for i in 0..m.triangles.len() {
        let g = triangle_normal(m, i);
        let n = normals[m.triangles[i][0] as usize];
        assert!(g.dot(n) > 0.0, "triangle {i}: geometric {g}, shading {n}");
    }
    // The quad (z = 0) still faces +z after mirroring x.
    assert!(close(triangle_normal(m, 0), Vec3::Z, 1e-6));
    assert_eq!(m.positions[1], Vec3::new(-1.0, 0.0, 0.0));
}

/// Of several sensors the first is rendered, as Mitsuba's `mi.render` and command line do by
/// default.
#[test]
fn the_first_of_several_sensors_is_rendered() {
    let text = wrap("<sensor type=\"perspective\"><float name=\"fov\" value=\"20\"/><film type=\"hdrfilm\"><integer name=\"width\" value=\"32\"/></film></sensor>")
        .replace(
            "<sensor type=\"perspective\"/>",
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"50\"/></sensor>",
        );
    let desc = ok("two_sensors.xml", &text);
    assert_eq!(desc.sensor.fov_deg, 50.0);
    assert_eq!(desc.film.width, 768);
}

/// A crop window renders its own size of the film; its size defaults to the rest of the film.
#[test]
fn film_crop_window() {
    let film = |crop: &str| {
        let text = wrap("").replace(
            "<sensor type=\"perspective\"/>",
            &format!("<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"64\"/><integer name=\"height\" value=\"48\"/>{crop}</film></sensor>"),
        );
        ok("crop.xml", &text).film
    };
    let cropped = film(
        "<integer name=\"crop_offset_x\" value=\"8\"/><integer name=\"crop_offset_y\" value=\"4\"/><integer name=\"crop_width\" value=\"16\"/><integer name=\"crop_height\" value=\"12\"/>",
    );
    assert_eq!((cropped.width, cropped.height), (16, 12));
    assert_eq!((cropped.full_size, cropped.crop_offset), ([64, 48], [8, 4]));
    let rest = film("<integer name=\"crop_offset_x\" value=\"60\"/>");
    assert_eq!(
        (rest.width, rest.height, rest.crop_offset),
        (4, 48, [60, 0])
    );
    let resized = cropped.resized(32, 24);
    assert_eq!(
        (resized.width, resized.full_size, resized.crop_offset),
        (32, [32, 24], [0, 0])
    );
}

#[test]
fn sphere_flip_and_rotation() {
    let desc = ok(
        "sphere.xml",
        &wrap(
            "<shape type=\"sphere\"><boolean name=\"flip_normals\" value=\"true\"/><point name=\"center\" value=\"1\"/>
<transform name=\"to_world\"><rotate z=\"1\" angle=\"90\"/><scale value=\"3\"/></transform></shape>",
        ),
    );
    let Geometry::Sphere(s) = desc.shapes[0].geometry else {
        panic!()
    };
    // (1, 1, 1) rotated 90° about z is (−1, 1, 1), then scaled by 3.
    assert!(close(s.center, Vec3::new(-3.0, 3.0, 3.0), 1e-5));
    assert!((s.radius - 3.0).abs() < 1e-6);
    assert!(s.flip_normals);
    // Its own frame, in which its uv are defined, is turned with it: world +y is its +x.
    assert!(close(s.to_local * Vec3::Y, Vec3::X, 1e-6));
    assert!(close(s.to_local * Vec3::Z, Vec3::Z, 1e-6));
}

#[test]
fn fixture_directory_is_resolved_relative_to_the_scene() {
    // Loading from another working directory must still find meshes next to the scene file.
    let desc = scene::parse_file(&data_dir().join("cornell.xml"), &[]).unwrap();
    assert!(desc.source.ends_with("cornell.xml"));
}

/// A document type declaration and comments holding `--` are read as Mitsuba reads them.
#[test]
fn doctype_and_dashes_in_comments_are_accepted() {
    let desc = ok(
        "doctype.xml",
        "<?xml version=\"1.0\"?>\n<!DOCTYPE scene>\n<!-- render with --spp 64 --->\n<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\"/><shape type=\"cube\"/></scene>",
    );
    assert_eq!(desc.shapes.len(), 1);
}

#[test]
fn byte_order_mark_is_accepted() {
    let desc = ok(
        "bom.xml",
        "\u{feff}<scene version=\"3.0.0\"><integrator type=\"path\"/><sensor type=\"perspective\"/></scene>",
    );
    assert!(desc.shapes.is_empty());
}

#[test]
fn emitting_shapes_without_a_bsdf_reflect_nothing() {
    // Mitsuba gives an emitter without a BSDF a black one; a plain shape gets diffuse 0.5.
    let desc = ok(
        "black_emitter.xml",
        &wrap(
            "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n\
             <shape type=\"sphere\"/>",
        ),
    );
    let black = BsdfDesc::Diffuse {
        reflectance: Vec3::ZERO,
    };
    assert_eq!(desc.bsdfs[desc.shapes[0].bsdf], black);
    assert_eq!(desc.bsdfs[desc.shapes[1].bsdf], BsdfDesc::default_diffuse());
}

/// `serialized` reads the meshes of `tests/crosscheck/meshes.serialized` by `shape_index` with the
/// counts Mitsuba 3.9.1 reports for them (169 vertices and 288 faces with normals and texture
/// coordinates; 6 and 8 without either, so normals are computed); `face_normals` drops normals;
/// a mirroring `to_world` keeps the file's winding (Mitsuba's face normals then turn), and an
/// index past the file's meshes is an error naming the element.
#[test]
fn serialized_meshes() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/crosscheck/meshes.serialized");
    std::fs::copy(file, write_scene("meshes.serialized", "")).unwrap();
    let shape = |index: u32, extra: &str| {
        format!(
            "<shape type=\"serialized\"><string name=\"filename\" value=\"meshes.serialized\"/><integer name=\"shape_index\" value=\"{index}\"/>{extra}</shape>"
        )
    };
    let desc = ok(
        "serialized.xml",
        &wrap(&format!(
            "{}{}{}",
            shape(0, ""),
            shape(1, "<boolean name=\"face_normals\" value=\"true\"/>"),
            shape(
                1,
                "<transform name=\"to_world\"><scale x=\"-1\"/></transform>"
            )
        )),
    );
    let mesh = |i: usize| match &desc.shapes[i].geometry {
        Geometry::Mesh(m) => m.clone(),
        Geometry::Sphere(_) => panic!("not a mesh"),
    };
    let grid = mesh(0);
    assert_eq!((grid.positions.len(), grid.triangles.len()), (169, 288));
    assert!(grid.normals.is_some() && grid.uvs.is_some());
    let flat = mesh(1);
    assert_eq!((flat.positions.len(), flat.triangles.len()), (6, 8));
    assert!(flat.normals.is_none() && flat.uvs.is_none());
    let mirrored = mesh(2);
    assert_eq!(mirrored.triangles, flat.triangles);
    assert_eq!(mirrored.positions[0], -flat.positions[0]);
    let err = load("serialized_index.xml", &wrap(&shape(2, ""))).unwrap_err();
    assert_eq!(err.line, 4, "{err}");
    assert!(err.message.contains("out of range"), "{err}");
}

/// `<path value="...">` adds a folder (relative to the scene file) where `filename`s and
/// includes are looked for first, as Mitsuba's file resolver does; a folder that does not exist
/// is an error naming the element.
#[test]
fn path_elements_add_search_folders() {
    std::fs::create_dir_all(write_scene("assets", "").with_file_name("assets-dir")).unwrap();
    let assets = write_scene(
        "assets-dir/part.xml",
        "<bsdf type=\"conductor\" id=\"metal\"/>",
    );
    let box_obj = data_dir().join("meshes/box.obj");
    std::fs::copy(box_obj, assets.with_file_name("crate.obj")).unwrap();
    let desc = ok(
        "search_path.xml",
        &wrap(
            "<path value=\"assets-dir\"/>
<include filename=\"part.xml\"/>
<shape type=\"obj\"><string name=\"filename\" value=\"crate.obj\"/><ref id=\"metal\"/></shape>",
        ),
    );
    assert_eq!(only_mesh(&desc).triangles.len(), 12);
    assert!(matches!(desc.bsdfs[0], BsdfDesc::Conductor { .. }));
    let err = load(
        "search_path_missing.xml",
        &wrap("<path value=\"no-such-dir\"/>"),
    )
    .unwrap_err();
    assert_eq!(err.line, 4, "{err}");
    assert!(
        err.message.contains("folder \"no-such-dir\" not found"),
        "{err}"
    );
}

/// A file named in an included file that is not beside it is looked for beside the scene, as
/// Mitsuba's resolver (which knows the scene's folder, not the included file's) finds it.
#[test]
fn included_files_find_files_beside_the_scene() {
    std::fs::create_dir_all(write_scene("x", "").with_file_name("fragments")).unwrap();
    write_scene(
        "fragments/mesh.xml",
        "<shape type=\"obj\"><string name=\"filename\" value=\"meshes/box.obj\"/></shape>",
    );
    let desc = ok(
        "include_scene_dir.xml",
        &wrap("<include filename=\"fragments/mesh.xml\"/>"),
    );
    assert_eq!(only_mesh(&desc).triangles.len(), 12);
}

/// Mitsuba's `moment` integrator renders its nested integrator's image (and adds moments as
/// extra channels, which Strata does not write); it needs exactly one nested integrator.
#[test]
fn moment_integrator_reads_its_nested_integrator() {
    let text = wrap("").replace(
        "<integrator type=\"path\"/>",
        "<integrator type=\"moment\"><integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"3\"/></integrator></integrator>",
    );
    let desc = ok("moment.xml", &text);
    assert!(matches!(
        desc.integrator.direct,
        Some(DirectDesc {
            emitter_samples: 3,
            ..
        })
    ));
    let empty = wrap("").replace(
        "<integrator type=\"path\"/>",
        "<integrator type=\"moment\"/>",
    );
    let err = load("moment_empty.xml", &empty).unwrap_err();
    assert!(
        err.message.contains("exactly one nested <integrator>"),
        "{err}"
    );
}

/// An area emitter declared at the top level with an id emits from the shape that references
/// it, as in Mitsuba's documentation scenes.
#[test]
fn area_emitters_referenced_by_id() {
    let desc = ok(
        "emitter_ref.xml",
        &wrap(
            "<emitter type=\"area\" id=\"glow\"><rgb name=\"radiance\" value=\"2, 3, 4\"/></emitter>
<shape type=\"rectangle\"><ref id=\"glow\"/><bsdf type=\"diffuse\"/></shape>",
        ),
    );
    assert_eq!(desc.shapes.len(), 1);
    let emitter = desc.shapes[0].emitter.as_ref().expect("the shape emits");
    assert!(
        format!("{emitter:?}").contains("2.0, 3.0, 4.0"),
        "{emitter:?}"
    );
    assert!(desc.emitters.is_empty());
}
