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
