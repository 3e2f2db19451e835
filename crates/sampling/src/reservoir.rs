//! Weighted reservoir sampling, the selection step of resampled importance sampling (RIS).
//!
//! RIS (Talbot et al. 2005) draws M candidates xᵢ from a source density p, gives each the resampling
//! weight wᵢ = p̂(xᵢ) / p(xᵢ) for a target function p̂ (unnormalised, e.g. the unshadowed contribution of
//! a light sample), and keeps one, y, with probability wᵢ / Σ w. Then f(y) · W is an unbiased estimate
//! of ∫ f wherever p̂ > 0 covers f ≠ 0, with the *unbiased contribution weight*
//!
//! W = (Σᵢ wᵢ) / (M · p̂(y)),
//!
//! which plays the role of 1 / pdf(y). A [`Reservoir`] streams the candidates in O(1) memory.

/// A weighted reservoir holding one selected candidate out of a stream.
///
/// After any sequence of [`Reservoir::update`] calls, each candidate with weight w is the selected one
/// with probability w / [`Reservoir::weight_sum`] (given independent uniform `u`s).
#[derive(Clone, Debug, PartialEq)]
pub struct Reservoir<T> {
    selected: Option<T>,
    weight_sum: f32,
    count: u32,
}

impl<T> Default for Reservoir<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T> Reservoir<T> {
    /// An empty reservoir: no candidate seen, nothing selected.
    #[inline]
    pub fn new() -> Self {
        Self {
            selected: None,
            weight_sum: 0.0,
            count: 0,
        }
    }

    /// Streams one candidate with resampling weight `weight` (≥ 0, finite) through the reservoir and
    /// returns whether it became the selected one; `u` is a fresh uniform number in [0, 1).
    ///
    /// The candidate always counts towards M ([`Reservoir::count`]). A zero, negative, NaN or infinite
    /// weight adds nothing to the weight sum and is never selected (a candidate the source could not
    /// have produced, or a broken weight, must not poison the estimate).
    #[inline]
    pub fn update(&mut self, candidate: T, weight: f32, u: f32) -> bool {
        self.count = self.count.saturating_add(1);
        if !(weight > 0.0 && weight.is_finite()) {
            return false;
        }
        self.weight_sum += weight;
        // Selected with probability weight / weight_sum; the first positive weight always is.
        if u * self.weight_sum < weight {
            self.selected = Some(candidate);
            true
        } else {
            false
        }
    }

    /// [`Reservoir::update`] with one uniform number for the whole stream: `u` decides this
    /// candidate and is then rescaled to a fresh uniform number for the next one (given this
    /// decision, `u` was uniform on the part of [0, 1) that led to it; that part is stretched back
    /// to [0, 1)). So a reservoir fed from one sampler dimension selects each candidate with
    /// probability w / Σ w, as with a uniform number per candidate.
    #[inline]
    pub fn update_reusing(&mut self, candidate: T, weight: f32, u: &mut f32) -> bool {
        self.count = self.count.saturating_add(1);
        if !(weight > 0.0 && weight.is_finite()) {
            return false;
        }
        self.weight_sum += weight;
        let p = weight / self.weight_sum;
        let selected = *u < p;
        *u = if selected {
            *u / p
        } else if p < 1.0 {
            (*u - p) / (1.0 - p)
        } else {
            *u
        };
        *u = u.clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        if selected {
            self.selected = Some(candidate);
        }
        selected
    }

    /// The selected candidate y, or `None` if no candidate had a positive weight.
    #[inline]
    pub fn selected(&self) -> Option<&T> {
        self.selected.as_ref()
    }

    /// The selected candidate, consuming the reservoir.
    #[inline]
    pub fn into_selected(self) -> Option<T> {
        self.selected
    }

    /// Σ wᵢ over the candidates seen so far.
    #[inline]
    pub fn weight_sum(&self) -> f32 {
        self.weight_sum
    }

    /// M: the number of candidates seen so far, including those of weight zero.
    #[inline]
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The unbiased contribution weight W = Σ w / (M · p̂(y)) of the selected candidate y, given
    /// `target_of_selected` = p̂(y); an estimate of ∫ f is then f(y) · W.
    ///
    /// 0 when nothing is selected or p̂(y) is not positive and finite.
    #[inline]
    pub fn contribution_weight(&self, target_of_selected: f32) -> f32 {
        let usable = target_of_selected > 0.0 && target_of_selected.is_finite();
        if self.selected.is_none() || !usable {
            return 0.0;
        }
        self.weight_sum / (self.count as f32 * target_of_selected)
    }
}
