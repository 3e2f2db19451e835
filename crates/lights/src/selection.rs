//! Choosing one light out of many for a next-event-estimation sample.

use crate::Light;
use sampling::distribution::AliasTable;

/// How the light for a next-event-estimation sample (a shadow ray) is chosen: by a fixed
/// probability mass function ([`LightSelector`]), or by resampling candidates drawn from one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSelection {
    /// Every light equally likely.
    Uniform,
    /// Proportional to emitted power.
    Power,
    /// Resampled importance sampling: `candidates` lights are drawn power-proportionally (by the
    /// [`LightSelector`] of `Power`), one is kept with probability proportional to the
    /// irradiance it could deliver at the shading point (a weighted reservoir), weighted by the
    /// unbiased contribution weight, and a point is sampled on it.
    Ris {
        /// Number of candidates M (at least 1).
        candidates: u32,
    },
    /// No choice: every light gets a light sample at every vertex, all from the vertex's one
    /// point number (each light's estimate is unbiased alone, so their sum is), for one shadow
    /// ray per light. No variance from the choice, at the cost of the rays: for scenes with a
    /// few lights of similar importance.
    All,
}

/// Picks lights with a fixed probability mass function over a scene's lights.
#[derive(Clone, Debug)]
pub enum LightSelector {
    /// Equal probability 1 / `count`.
    Uniform {
        /// Number of lights.
        count: u32,
    },
    /// Probability proportional to a weight per light (power, selection weight or both), drawn
    /// from an alias table.
    Weighted(AliasTable),
    /// Every light with a positive weight sampled at every vertex ([`LightSelection::All`]).
    Every {
        /// Indices of the lights sampled, ascending.
        sampled: Box<[u32]>,
    },
}

impl LightSelector {
    /// A selector over `lights` with selection weights `weights` (parallel to `lights`,
    /// non-negative; Mitsuba's `sampling_weight`, or 0 for a light that light sampling leaves
    /// alone): each light is chosen with probability proportional to its weight (`Uniform`) or
    /// to its power times its weight (`Power`, and `Ris`, whose candidates come from this
    /// selector). Falls back to the weights alone when no light has positive finite power, and
    /// to uniform when they are all equal. `None` when no light has a positive weight.
    pub fn new(lights: &[Light], weights: &[f32], selection: LightSelection) -> Option<Self> {
        let powers: Vec<f32> = lights.iter().map(Light::power).collect();
        Self::with_powers(&powers, weights, selection)
    }

    /// [`Self::new`] for lights of power `powers` (W, mean over channels; parallel to
    /// `weights`), where the power light sampling sees differs from [`Light::power`] (an
    /// environment map sampled by its excess over its mean).
    pub fn with_powers(powers: &[f32], weights: &[f32], selection: LightSelection) -> Option<Self> {
        debug_assert_eq!(powers.len(), weights.len());
        let sampled: Box<[u32]> = (0..weights.len() as u32)
            .filter(|&i| weights[i as usize] > 0.0)
            .collect();
        if sampled.is_empty() {
            return None;
        }
        let by_weight = || {
            let uniform = LightSelector::Uniform {
                count: weights.len() as u32,
            };
            if weights.iter().all(|&w| w == weights[0]) {
                uniform
            } else {
                AliasTable::new(weights)
                    .ok()
                    .map_or(uniform, LightSelector::Weighted)
            }
        };
        Some(match selection {
            LightSelection::All => LightSelector::Every { sampled },
            LightSelection::Uniform => by_weight(),
            LightSelection::Power | LightSelection::Ris { .. } => {
                let powers: Vec<f32> = powers
                    .iter()
                    .zip(weights)
                    .map(|(&power, &weight)| power * weight)
                    .collect();
                AliasTable::new(&powers)
                    .ok()
                    .map_or_else(by_weight, LightSelector::Weighted)
            }
        })
    }

    /// The index of a light and its probability, for `u` uniform in [0, 1) ([`LightSelector::Every`],
    /// which never needs to choose, chooses uniformly among the lights it samples).
    #[inline]
    pub fn select(&self, u: f32) -> (usize, f32) {
        match self {
            LightSelector::Uniform { count } => {
                let index = ((u * *count as f32) as u32).min(count - 1);
                (index as usize, 1.0 / *count as f32)
            }
            LightSelector::Every { sampled } => {
                let count = sampled.len() as u32;
                let index = ((u * count as f32) as u32).min(count - 1);
                (sampled[index as usize] as usize, 1.0 / count as f32)
            }
            LightSelector::Weighted(table) => table.sample(u),
        }
    }

    /// The lights that light sampling samples, by index: every light [`Self::pmf`] is positive
    /// for, ascending.
    pub fn sampled(&self) -> Vec<u32> {
        match self {
            LightSelector::Uniform { count } => (0..*count).collect(),
            LightSelector::Every { sampled } => sampled.to_vec(),
            LightSelector::Weighted(table) => (0..table.len() as u32)
                .filter(|&i| table.pmf(i as usize) > 0.0)
                .collect(),
        }
    }

    /// Expected light samples light `index` gets per vertex, what MIS weighs its density by:
    /// the probability that [`Self::select`] returns it, or for [`LightSelector::Every`] 1 for
    /// the lights it samples and 0 for the others.
    #[inline]
    pub fn pmf(&self, index: usize) -> f32 {
        match self {
            LightSelector::Every { sampled } => {
                f32::from(u8::from(sampled.binary_search(&(index as u32)).is_ok()))
            }
            LightSelector::Uniform { count } => 1.0 / *count as f32,
            LightSelector::Weighted(table) => table.pmf(index),
        }
    }
}
