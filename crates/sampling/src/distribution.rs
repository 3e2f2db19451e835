//! Discrete distributions: choosing index i with probability proportional to a weight wᵢ.

use std::fmt;

pub use crate::cdf_table::CdfTable;

/// Why an [`AliasTable`] could not be built from a list of weights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AliasTableError {
    /// There were no weights.
    Empty,
    /// More weights than a `u32` index can address.
    TooMany,
    /// The weight at this index is NaN or infinite.
    NonFinite(usize),
    /// The weight at this index is negative.
    Negative(usize),
    /// All weights are zero, so no index can be chosen.
    ZeroTotal,
}

impl fmt::Display for AliasTableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "no weights to build a distribution from"),
            Self::TooMany => write!(f, "more than 2^32 weights"),
            Self::NonFinite(i) => write!(f, "weight {i} is NaN or infinite"),
            Self::Negative(i) => write!(f, "weight {i} is negative"),
            Self::ZeroTotal => write!(f, "all weights are zero"),
        }
    }
}

impl std::error::Error for AliasTableError {}

/// The sum of `weights` in f64 after checking they can define a distribution: not empty,
/// addressable by `u32`, each finite and non-negative, not all zero.
pub(crate) fn validated_total(weights: &[f32]) -> Result<f64, AliasTableError> {
    if weights.is_empty() {
        return Err(AliasTableError::Empty);
    }
    if u32::try_from(weights.len()).is_err() {
        return Err(AliasTableError::TooMany);
    }
    let mut total = 0.0_f64;
    for (i, &w) in weights.iter().enumerate() {
        if !w.is_finite() {
            return Err(AliasTableError::NonFinite(i));
        }
        if w < 0.0 {
            return Err(AliasTableError::Negative(i));
        }
        total += f64::from(w);
    }
    if total <= 0.0 {
        return Err(AliasTableError::ZeroTotal);
    }
    Ok(total)
}

/// One column of the table: keep its own index with probability `keep`, else take `alias`.
#[derive(Clone, Copy, Debug)]
struct Column {
    keep: f32,
    alias: u32,
}

/// Walker's alias method, built by Vose's algorithm: O(n) construction, O(1) sampling of an index i
/// with probability mass pmf(i) = wᵢ / Σⱼ wⱼ from a single uniform number.
///
/// Zero weights are allowed and are never returned.
#[derive(Clone, Debug)]
pub struct AliasTable {
    columns: Vec<Column>,
    pmf: Vec<f32>,
}

impl AliasTable {
    /// The table for `weights` (any non-negative finite numbers, not all zero).
    ///
    /// # Errors
    /// [`AliasTableError`] if `weights` is empty, too long, or has a NaN, infinite or negative
    /// weight, or if every weight is zero.
    pub fn new(weights: &[f32]) -> Result<Self, AliasTableError> {
        let total = validated_total(weights)?;
        let n = weights.len();
        let pmf: Vec<f32> = weights
            .iter()
            .map(|&w| (f64::from(w) / total) as f32)
            .collect();
        // Scaled so that the average column holds exactly 1.
        let mut scaled: Vec<f64> = weights
            .iter()
            .map(|&w| f64::from(w) * n as f64 / total)
            .collect();
        let mut columns: Vec<Column> = (0..n as u32)
            .map(|i| Column {
                keep: 1.0,
                alias: i,
            })
            .collect();
        let (mut small, mut large): (Vec<u32>, Vec<u32>) =
            (0..n as u32).partition(|&i| scaled[i as usize] < 1.0);
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            let (si, li) = (s as usize, l as usize);
            columns[si] = Column {
                keep: scaled[si] as f32,
                alias: l,
            };
            // The large entry gives column `s` the mass it lacks.
            scaled[li] -= 1.0 - scaled[si];
            if scaled[li] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // Whatever is left holds 1 up to rounding and keeps its own column (keep = 1, alias = itself).
        Ok(Self { columns, pmf })
    }

    /// An index with probability [`AliasTable::pmf`], and that probability, from `u` in [0, 1).
    ///
    /// `u`'s integer part over the table picks a column, its fraction decides between the column's
    /// index and its alias. Values of `u` outside [0, 1) are clamped into it.
    #[inline]
    pub fn sample(&self, u: f32) -> (usize, f32) {
        let n = self.columns.len();
        let scaled = f64::from(u.clamp(0.0, 1.0)) * n as f64;
        let column = (scaled as usize).min(n - 1);
        let fraction = (scaled - column as f64) as f32;
        let entry = self.columns[column];
        let index = if fraction < entry.keep {
            column
        } else {
            entry.alias as usize
        };
        (index, self.pmf[index])
    }

    /// The probability mass wᵢ / Σⱼ wⱼ of index `i`; 0 for an index outside the table.
    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }

    /// The number of indices (weights) in the table, at least 1.
    #[inline]
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Always false: a table is never empty ([`AliasTable::new`] refuses empty weights).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }
}
