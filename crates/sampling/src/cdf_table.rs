//! A discrete distribution sampled by inverting its cumulative distribution, which also hands
//! back the leftover randomness of the uniform number it used.

use crate::distribution::{AliasTableError, validated_total};

/// Index i chosen with probability wᵢ / Σⱼ wⱼ by binary search in the cumulative sums (O(log n)).
///
/// Unlike an [`AliasTable`](crate::AliasTable) it is monotone in `u` and returns `u` remapped to
/// [0, 1) within the chosen interval, so one uniform number can pick an index and then be reused
/// (e.g. a triangle by area, then a point on it) without losing stratification.
#[derive(Clone, Debug)]
pub struct CdfTable {
    /// cdf[i] = Σ_{j<i} pmf[j]; cdf[0] = 0 and cdf[n] = 1 exactly.
    cdf: Vec<f32>,
    pmf: Vec<f32>,
}

impl CdfTable {
    /// The table for `weights` (non-negative and finite, not all zero).
    ///
    /// # Errors
    /// The same conditions as [`AliasTable::new`](crate::AliasTable::new).
    pub fn new(weights: &[f32]) -> Result<Self, AliasTableError> {
        let total = validated_total(weights)?;
        let pmf: Vec<f32> = weights
            .iter()
            .map(|&w| (f64::from(w) / total) as f32)
            .collect();
        let mut cdf = Vec::with_capacity(weights.len() + 1);
        let mut running = 0.0_f64;
        cdf.push(0.0);
        for &w in weights {
            running += f64::from(w);
            cdf.push((running / total) as f32);
        }
        // Intervals that end at 1 (the last non-zero weight and any zeros after it) end exactly at 1.
        let last_positive = weights.iter().rposition(|&w| w > 0.0).unwrap_or(0);
        for c in &mut cdf[last_positive + 1..] {
            *c = 1.0;
        }
        Ok(Self { cdf, pmf })
    }

    /// For `u` in [0, 1): the index i with `cdf[i] ≤ u < cdf[i + 1]`, its probability, and
    /// `(u − cdf[i]) / pmf(i)` in [0, 1). Zero-weight indices are never returned.
    #[inline]
    pub fn sample(&self, u: f32) -> (usize, f32, f32) {
        let n = self.pmf.len();
        let index = (self.cdf.partition_point(|&c| c <= u).max(1) - 1).min(n - 1);
        let width = self.cdf[index + 1] - self.cdf[index];
        let remapped = if width > 0.0 {
            ((u - self.cdf[index]) / width).clamp(0.0, 1.0 - f32::EPSILON / 2.0)
        } else {
            0.0
        };
        (index, self.pmf[index], remapped)
    }

    /// Probability of index `i`.
    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf[i]
    }

    /// Number of indices.
    #[inline]
    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    /// True when the table has no index (never: construction requires a weight).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.pmf.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frequencies_and_remapping_match_the_weights() {
        // Fixed grid of u: each index must get exactly its share, and remapped u must be uniform
        // within it (checked by its mean, 0.5 ± 1/(2·count)).
        let weights = [1.0, 0.0, 3.0, 0.5, 0.0];
        let table = CdfTable::new(&weights).expect("valid weights");
        let n = 45_000;
        let mut counts = [0u32; 5];
        let mut remapped_sums = [0.0f64; 5];
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            let (i, pmf, r) = table.sample(u);
            assert_eq!(pmf, table.pmf(i));
            assert!((0.0..1.0).contains(&r), "u {u}: remapped {r}");
            counts[i] += 1;
            remapped_sums[i] += f64::from(r);
        }
        let total: f32 = weights.iter().sum();
        for (i, &w) in weights.iter().enumerate() {
            let expected = f64::from(w / total) * n as f64;
            assert!(
                (f64::from(counts[i]) - expected).abs() <= 1.0,
                "index {i}: {} hits, expected {expected}",
                counts[i]
            );
            if counts[i] > 0 {
                let mean = remapped_sums[i] / f64::from(counts[i]);
                assert!(
                    (mean - 0.5).abs() < 1.0 / f64::from(counts[i]),
                    "index {i}: mean {mean}"
                );
            }
        }
    }

    #[test]
    fn extremes_of_u_stay_on_positive_weights() {
        let table = CdfTable::new(&[0.0, 2.0, 0.0]).expect("valid weights");
        for u in [0.0, 0.5, 1.0 - f32::EPSILON / 2.0] {
            let (i, pmf, r) = table.sample(u);
            assert_eq!((i, pmf), (1, 1.0), "u {u}");
            assert!((0.0..1.0).contains(&r));
        }
    }

    #[test]
    fn invalid_weights_are_errors() {
        assert_eq!(CdfTable::new(&[]).unwrap_err(), AliasTableError::Empty);
        assert_eq!(
            CdfTable::new(&[0.0, 0.0]).unwrap_err(),
            AliasTableError::ZeroTotal
        );
        assert_eq!(
            CdfTable::new(&[1.0, f32::NAN]).unwrap_err(),
            AliasTableError::NonFinite(1)
        );
        assert_eq!(
            CdfTable::new(&[1.0, -1.0]).unwrap_err(),
            AliasTableError::Negative(1)
        );
    }
}
