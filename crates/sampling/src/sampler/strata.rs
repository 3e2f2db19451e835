//! Exact placement of jittered points in strata of [0, 1).

/// `count` equal strata of [0, 1).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Strata {
    count: f64,
    inverse: f64,
}

impl Strata {
    /// Strata of width 1 / `count` (`count` ≥ 1).
    pub(crate) fn new(count: u32) -> Self {
        let count = f64::from(count.max(1));
        Self {
            count,
            inverse: 1.0 / count,
        }
    }

    /// The point `jitter` (in [0, 1)) of the way through stratum `stratum`.
    ///
    /// The result is guaranteed to lie in [stratum / count, (stratum + 1) / count) in exact arithmetic
    /// (and so is never 1.0), even where rounding to `f32` would cross a stratum boundary.
    #[inline]
    pub(crate) fn point(self, stratum: u32, jitter: f32) -> f32 {
        debug_assert!(f64::from(stratum) < self.count && (0.0..1.0).contains(&jitter));
        let lo = f64::from(stratum);
        let mut x = ((lo + f64::from(jitter)) * self.inverse) as f32;
        // `f64::from(x) * count` is exact for count < 2²⁹: this tests the stratum without rounding.
        let scaled = f64::from(x) * self.count;
        if scaled < lo {
            x = x.next_up();
        } else if scaled >= lo + 1.0 {
            x = x.next_down();
        }
        x
    }
}

/// The factorisation `columns × rows` of `count` closest to square, with `columns ≤ rows`.
///
/// A prime `count` gives 1 × `count`.
pub(crate) fn closest_factorisation(count: u32) -> (u32, u32) {
    let count = count.max(1);
    let mut columns = count.isqrt();
    while !count.is_multiple_of(columns) {
        columns -= 1;
    }
    (columns, count / columns)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_stay_inside_their_stratum_at_both_ends() {
        let largest_jitter = 1.0 - f32::EPSILON / 2.0;
        for count in (1..2000).chain([65_535, 1 << 20, 3_000_017]) {
            for stratum in [0, count / 3, count / 2, count - 1] {
                for jitter in [0.0, 0.5, largest_jitter] {
                    let x = Strata::new(count).point(stratum, jitter);
                    let scaled = f64::from(x) * f64::from(count);
                    assert!(
                        scaled >= f64::from(stratum) && scaled < f64::from(stratum) + 1.0,
                        "stratum {stratum} of {count}, jitter {jitter}: {x}"
                    );
                    assert!(x < 1.0);
                }
            }
        }
    }

    #[test]
    fn closest_factorisation_is_the_most_square_divisor_pair() {
        assert_eq!(closest_factorisation(0), (1, 1));
        assert_eq!(closest_factorisation(1), (1, 1));
        assert_eq!(closest_factorisation(12), (3, 4));
        assert_eq!(closest_factorisation(16), (4, 4));
        assert_eq!(closest_factorisation(17), (1, 17));
        assert_eq!(closest_factorisation(18), (3, 6));
        for n in 1..500_u32 {
            let (c, r) = closest_factorisation(n);
            assert_eq!(c * r, n);
            assert!(c <= r);
            assert!((c + 1..=n.isqrt()).all(|d| n % d != 0), "{n}: {c} x {r}");
        }
    }
}
