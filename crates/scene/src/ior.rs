//! Named indices of refraction, as in Mitsuba's `ior.h` (Hecht, Optics; about 589 nm, 0–20 °C).

/// Dielectric materials that `int_ior` and `ext_ior` may name, with their indices of refraction.
pub(crate) const NAMED_IORS: [(&str, f64); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// Conductor presets that `material` may name: (name, eta, k) in linear sRGB.
///
/// These are the sRGB colours of the measured spectra Mitsuba ships (`data/ior/NAME.eta.spd` and
/// `NAME.k.spd`), integrated against the CIE 1931 observer without an illuminant and converted to
/// sRGB exactly as Mitsuba's RGB variants do (`spectrum_list_to_srgb`, unbounded), so a scene that
/// names them renders like Mitsuba's `scalar_rgb`.
pub(crate) const CONDUCTORS: [(&str, [f32; 3], [f32; 3]); 5] = [
    (
        "Ag",
        [0.155276, 0.116728, 0.138388],
        [4.828355, 3.122222, 2.146901],
    ),
    (
        "Al",
        [1.657501, 0.880405, 0.521244],
        [9.223811, 6.269502, 4.837004],
    ),
    (
        "Au",
        [0.143036, 0.375307, 1.442045],
        [3.982997, 2.385557, 1.603359],
    ),
    (
        "Cr",
        [4.369668, 2.916505, 1.654905],
        [5.206547, 4.231306, 3.754699],
    ),
    (
        "Cu",
        [0.201005, 0.923749, 1.102215],
        [3.913262, 2.453045, 2.14209],
    ),
];

/// The RGB (eta, k) of a named conductor (case-sensitive, as in Mitsuba), if known.
pub(crate) fn lookup_conductor(name: &str) -> Option<([f32; 3], [f32; 3])> {
    CONDUCTORS
        .iter()
        .find(|(known, _, _)| *known == name)
        .map(|(_, eta, k)| (*eta, *k))
}

/// The index of refraction of a named dielectric (case-insensitive), if known.
pub(crate) fn lookup_ior(name: &str) -> Option<f64> {
    let lower = name.trim().to_ascii_lowercase();
    NAMED_IORS
        .iter()
        .find(|(known, _)| *known == lower)
        .map(|(_, value)| *value)
}

/// The names accepted by [`lookup_ior`], for error messages.
pub(crate) fn ior_names() -> String {
    NAMED_IORS
        .iter()
        .map(|(name, _)| *name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mitsuba_defaults_are_in_the_table() {
        assert_eq!(lookup_ior("bk7"), Some(1.5046));
        assert_eq!(lookup_ior("Air"), Some(1.000277));
        assert_eq!(lookup_ior("water ice"), Some(1.31));
        assert_eq!(lookup_ior("unobtainium"), None);
    }
}
