//! Loading Mitsuba's `normalmap` and `bumpmap` BSDF adapters, and the errors for bad ones, each
//! naming the file, the line and the element.

mod common;

use common::{load, wrap, write_scene};
use materials::{AdapterOptions, Bsdf};
use scene::BsdfDesc;
use std::sync::atomic::{AtomicU32, Ordering};

/// A `<texture type="bitmap" name="NAME">` of the crosscheck scenes' 8-bit PNG, copied beside
/// the scene under a name of its own (tests run in parallel), read raw (no sRGB curve) as normal
/// and bump maps are. Four lines.
fn raw_bitmap(name: &str) -> String {
    static COPIES: AtomicU32 = AtomicU32::new(0);
    let file = format!("adapter-{}.png", COPIES.fetch_add(1, Ordering::Relaxed));
    let png = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/crosscheck/texture-rgb.png");
    std::fs::copy(png, write_scene(&file, "")).unwrap();
    format!(
        "<texture type=\"bitmap\" name=\"{name}\">\n<string name=\"filename\" value=\"{file}\"/>\n<boolean name=\"raw\" value=\"true\"/>\n</texture>"
    )
}

/// The runtime BSDF the loader built for the scene's last BSDF (the front of a twosided).
fn built(name: &str, body: &str) -> Bsdf {
    let desc = load(name, &wrap(body)).unwrap_or_else(|e| panic!("{name}: {e}"));
    match desc.bsdfs.last().expect("a BSDF") {
        BsdfDesc::Built(bsdf) => bsdf.clone(),
        BsdfDesc::TwoSided { front, .. } => match &**front {
            BsdfDesc::Built(bsdf) => bsdf.clone(),
            other => panic!("{name}: {other:?}"),
        },
        other => panic!("{name}: {other:?}"),
    }
}

#[test]
fn normalmap_and_bumpmap_load_with_their_nested_bsdf() {
    let normal = built(
        "normalmap.xml",
        &format!(
            "<bsdf type=\"normalmap\">\n{}\n<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.3\"/></bsdf>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
    );
    let Bsdf::NormalMap(map) = normal else {
        panic!("{normal:?}")
    };
    assert_eq!(
        map.nested(),
        &Bsdf::from(materials::Diffuse::new(glam::Vec3::splat(0.3)))
    );

    // Mitsuba's bump map takes a texture of any name, and a scale.
    let bump = built(
        "bumpmap.xml",
        &format!(
            "<bsdf type=\"bumpmap\">\n<bsdf type=\"roughconductor\"/>\n{}\n<float name=\"scale\" value=\"0.2\"/>\n</bsdf>",
            raw_bitmap("arbitrary")
        ),
    );
    assert!(matches!(bump, Bsdf::BumpMap(_)), "{bump:?}");

    // A twosided around a normal map (its side resolved first at a hit) and a reference.
    let two_sided = built(
        "twosided_normalmap.xml",
        &format!(
            "<bsdf type=\"diffuse\" id=\"base\"/>\n<bsdf type=\"twosided\">\n<bsdf type=\"normalmap\">\n{}\n<ref id=\"base\"/>\n</bsdf>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
    );
    assert!(matches!(two_sided, Bsdf::NormalMap(_)), "{two_sided:?}");
}

/// Mitsuba 3.9's `flip_invalid_normals` and `use_shadowing_function`: true unless given, read
/// by both adapters.
#[test]
fn adapter_options_default_to_mitsubas_and_are_read() {
    let Bsdf::NormalMap(map) = built(
        "normalmap_defaults.xml",
        &format!(
            "<bsdf type=\"normalmap\">\n{}\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
    ) else {
        panic!("not a normal map")
    };
    assert_eq!(map.options(), AdapterOptions::default());
    assert!(map.options().flip_invalid_normals && map.options().shadowing_function);

    let Bsdf::NormalMap(map) = built(
        "normalmap_options.xml",
        &format!(
            "<bsdf type=\"normalmap\">\n{}\n<boolean name=\"flip_invalid_normals\" value=\"false\"/>\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
    ) else {
        panic!("not a normal map")
    };
    assert!(!map.options().flip_invalid_normals && map.options().shadowing_function);

    let Bsdf::BumpMap(bumps) = built(
        "bumpmap_options.xml",
        &format!(
            "<bsdf type=\"bumpmap\">\n{}\n<boolean name=\"use_shadowing_function\" value=\"false\"/>\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            raw_bitmap("height")
        ),
    ) else {
        panic!("not a bump map")
    };
    assert!(bumps.options().flip_invalid_normals && !bumps.options().shadowing_function);

    expect(
        "bumpmap_bad_option.xml",
        &format!(
            "<bsdf type=\"bumpmap\">\n{}\n<float name=\"use_shadowing_function\" value=\"1\"/>\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            raw_bitmap("height")
        ),
        9,
        "use_shadowing_function",
        "must be given as <boolean>",
    );
}

/// Checks the file, line, element and message of the error `body` (starting on line 4) gives.
fn expect(name: &str, body: &str, line: u32, element: &str, message: &str) {
    let err = load(name, &wrap(body)).expect_err(name);
    let shown = err.to_string();
    assert!(err.file.ends_with(name), "{name}: wrong file in {shown}");
    assert_eq!(err.line, line, "{name}: wrong line in {shown}");
    assert!(
        err.element.contains(element),
        "{name}: element not in {shown}"
    );
    assert!(
        err.message.contains(message),
        "{name}: message not in {shown}"
    );
}

#[test]
fn bad_adapters_are_errors_naming_the_element() {
    expect(
        "normalmap_no_bsdf.xml",
        &format!(
            "<bsdf type=\"normalmap\">\n{}\n</bsdf>",
            raw_bitmap("normalmap")
        ),
        4,
        "<bsdf type=\"normalmap\">",
        "needs exactly one nested BSDF",
    );
    expect(
        "normalmap_no_texture.xml",
        "<bsdf type=\"normalmap\">\n<bsdf type=\"diffuse\"/>\n</bsdf>",
        4,
        "<bsdf type=\"normalmap\">",
        "needs a <texture type=\"bitmap\" name=\"normalmap\">",
    );
    expect(
        "bumpmap_two_bsdfs.xml",
        &format!(
            "<bsdf type=\"bumpmap\">\n{}\n<bsdf type=\"diffuse\"/>\n<bsdf type=\"diffuse\"/>\n</bsdf>",
            raw_bitmap("height")
        ),
        4,
        "<bsdf type=\"bumpmap\">",
        "needs exactly one nested BSDF",
    );
    expect(
        "bumpmap_checkerboard.xml",
        "<bsdf type=\"bumpmap\">\n<texture type=\"checkerboard\" name=\"height\"/>\n<bsdf type=\"diffuse\"/>\n</bsdf>",
        4,
        "<bsdf type=\"bumpmap\">",
        "must be a bitmap",
    );
    expect(
        "bumpmap_scale.xml",
        &format!(
            "<bsdf type=\"bumpmap\">\n{}\n<bsdf type=\"diffuse\"/>\n<string name=\"scale\" value=\"big\"/>\n</bsdf>",
            raw_bitmap("height")
        ),
        10,
        "<string name=\"scale\"",
        "must be given as <float>",
    );
    expect(
        "normalmap_in_blend.xml",
        &format!(
            "<bsdf type=\"blendbsdf\">\n<float name=\"weight\" value=\"0.5\"/>\n<bsdf type=\"diffuse\"/>\n<bsdf type=\"normalmap\">\n{}\n<bsdf type=\"diffuse\"/>\n</bsdf>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
        4,
        "<bsdf type=\"blendbsdf\">",
        "of a normalmap or bumpmap is not supported",
    );
    expect(
        "normalmap_nested.xml",
        &format!(
            "<bsdf type=\"normalmap\">\n{0}\n<bsdf type=\"normalmap\">\n{0}\n<bsdf type=\"diffuse\"/>\n</bsdf>\n</bsdf>",
            raw_bitmap("normalmap")
        ),
        9,
        "<bsdf type=\"normalmap\">",
        "around a normalmap or bumpmap",
    );
}
