//! Choosing one light out of many for a next-event-estimation sample.

use crate::Light;
use sampling::distribution::AliasTable;

/// How a light is chosen for a shadow ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSelection {
    /// Every light with equal probability.
    Uniform,
    /// Proportional to each light's emitted power.
    Power,
}

/// Picks lights with a fixed probability mass function over a scene's lights.
#[derive(Clone, Debug)]
pub enum LightSelector {
    /// Equal probability 1 / `count`.
    Uniform {
        /// Number of lights.
        count: u32,
    },
    /// Probability proportional to power, drawn from an alias table.
    Power(AliasTable),
}

impl LightSelector {
    /// A selector over `lights`; falls back to uniform when no light has positive finite power.
    /// `None` when there are no lights.
    pub fn new(lights: &[Light], selection: LightSelection) -> Option<Self> {
        if lights.is_empty() {
            return None;
        }
        let uniform = LightSelector::Uniform {
            count: lights.len() as u32,
        };
        Some(match selection {
            LightSelection::Uniform => uniform,
            LightSelection::Power => {
                let powers: Vec<f32> = lights.iter().map(Light::power).collect();
                AliasTable::new(&powers).map_or(uniform, LightSelector::Power)
            }
        })
    }

    /// The index of a light and its probability, for `u` uniform in [0, 1).
    #[inline]
    pub fn select(&self, u: f32) -> (usize, f32) {
        match self {
            LightSelector::Uniform { count } => {
                let index = ((u * *count as f32) as u32).min(count - 1);
                (index as usize, 1.0 / *count as f32)
            }
            LightSelector::Power(table) => table.sample(u),
        }
    }

    /// Probability that [`Self::select`] returns `index`.
    #[inline]
    pub fn pmf(&self, index: usize) -> f32 {
        match self {
            LightSelector::Uniform { count } => 1.0 / *count as f32,
            LightSelector::Power(table) => table.pmf(index),
        }
    }
}
