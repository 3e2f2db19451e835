//! [`BsdfFlags`]: what kinds of lobes a BSDF has, one set in place of a predicate per question.

use std::fmt;
use std::ops::{BitOr, BitOrAssign};

/// The kinds of lobes a BSDF has and what its sampling needs, as a set of bits
/// ([`crate::Bsdf::flags`]). A BSDF made of others (a twosided, a blend) has the union of their
/// flags, and [`Self::MIXED`] where one side mixes delta and density lobes.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct BsdfFlags(u16);

impl BsdfFlags {
    /// No lobe at all.
    pub const EMPTY: Self = Self(0);
    /// A lobe with a density that varies little with the direction (Lambertian, a plastic's
    /// base).
    pub const DIFFUSE: Self = Self(1 << 0);
    /// A glossy lobe, whose density depends strongly on the direction without being a delta (a
    /// rough conductor, dielectric or plastic): where [`crate::Bsdf::lobe_weight`] is given.
    pub const GLOSSY: Self = Self(1 << 1);
    /// At least one delta lobe (a perfect mirror or refraction), so some samples have
    /// [`crate::BsdfSample::is_delta`] set.
    pub const DELTA: Self = Self(1 << 2);
    /// A null lobe: some sample can have [`crate::BsdfSample::is_null`] set (a thin dielectric,
    /// alone or in a blend).
    pub const NULL: Self = Self(1 << 3);
    /// Light can pass to the other side of the surface (a dielectric, thin, rough or smooth).
    pub const TRANSMISSION: Self = Self(1 << 4);
    /// Anisotropic roughness: the BSDF depends on how the shading frame is turned about the
    /// normal, so the frame must follow the surface's parameterisation (its first tangent along
    /// ∂p/∂u, as Mitsuba's), which isotropic BSDFs do not need.
    pub const ANISOTROPIC: Self = Self(1 << 5);
    /// [`crate::Bsdf::sample`] uses its `u_lobe` number (to choose between lobes); other BSDFs
    /// ignore it.
    pub const LOBE_CHOICE: Self = Self(1 << 6);
    /// One side has delta lobes and lobes with a density at once (a plastic, a blend of a mirror
    /// and a diffuse, or a twosided with such a side): strategies that sample directions without
    /// the BSDF's help must then reach its delta lobes by [`crate::Bsdf::sample_delta`]. A
    /// twosided with a mirror on one side and a diffuse on the other is not mixed.
    pub const MIXED: Self = Self(1 << 7);
    /// The BSDF depends on the surface point ([`crate::Bsdf::at_surface`] gives it there: a
    /// normal or bump map), so the renderer must ask at every hit.
    pub const AT_SURFACE: Self = Self(1 << 8);
    /// The lobes with a density: [`Self::DIFFUSE`] and [`Self::GLOSSY`].
    pub const SMOOTH: Self = Self(Self::DIFFUSE.0 | Self::GLOSSY.0);

    /// Whether every flag of `other` is set.
    #[inline]
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether some flag of `other` is set.
    #[inline]
    pub const fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// The flags set in either.
    #[inline]
    pub const fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// Whether every lobe is a delta (no [`Self::SMOOTH`] lobe: a mirror, smooth glass, a thin
    /// pane): then `eval` and `pdf_solid_angle` are always 0 and light sampling at this surface
    /// is pointless. A twosided is delta only when both sides are; integrators resolve it to the
    /// side a ray sees before asking.
    #[inline]
    pub const fn is_delta(self) -> bool {
        !self.intersects(Self::SMOOTH)
    }

    /// Whether `sample` chooses between a delta lobe and another lobe ([`Self::DELTA`] with
    /// [`Self::LOBE_CHOICE`]: glass, a smooth plastic), where delta splitting applies.
    #[inline]
    pub const fn chooses_delta_lobe(self) -> bool {
        self.contains(Self::DELTA.union(Self::LOBE_CHOICE))
    }
}

impl BitOr for BsdfFlags {
    type Output = Self;

    #[inline]
    fn bitor(self, other: Self) -> Self {
        self.union(other)
    }
}

impl BitOrAssign for BsdfFlags {
    #[inline]
    fn bitor_assign(&mut self, other: Self) {
        *self = self.union(other);
    }
}

impl fmt::Debug for BsdfFlags {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const NAMES: [(BsdfFlags, &str); 9] = [
            (BsdfFlags::DIFFUSE, "DIFFUSE"),
            (BsdfFlags::GLOSSY, "GLOSSY"),
            (BsdfFlags::DELTA, "DELTA"),
            (BsdfFlags::NULL, "NULL"),
            (BsdfFlags::TRANSMISSION, "TRANSMISSION"),
            (BsdfFlags::ANISOTROPIC, "ANISOTROPIC"),
            (BsdfFlags::LOBE_CHOICE, "LOBE_CHOICE"),
            (BsdfFlags::MIXED, "MIXED"),
            (BsdfFlags::AT_SURFACE, "AT_SURFACE"),
        ];
        let set: Vec<&str> = NAMES
            .iter()
            .filter(|(flag, _)| self.contains(*flag))
            .map(|(_, name)| *name)
            .collect();
        write!(f, "BsdfFlags({})", set.join(" | "))
    }
}

#[cfg(test)]
mod tests {
    use super::BsdfFlags;

    #[test]
    fn set_operations() {
        let plastic = BsdfFlags::DIFFUSE | BsdfFlags::DELTA | BsdfFlags::MIXED;
        assert!(plastic.contains(BsdfFlags::DELTA | BsdfFlags::DIFFUSE));
        assert!(!plastic.contains(BsdfFlags::DELTA | BsdfFlags::GLOSSY));
        assert!(plastic.intersects(BsdfFlags::SMOOTH) && !plastic.is_delta());
        assert!((BsdfFlags::DELTA | BsdfFlags::NULL).is_delta());
        assert!(BsdfFlags::EMPTY.is_delta() && BsdfFlags::default() == BsdfFlags::EMPTY);
        assert_eq!(format!("{plastic:?}"), "BsdfFlags(DIFFUSE | DELTA | MIXED)");
    }
}
