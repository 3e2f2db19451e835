//! Multiple importance sampling weights (Veach 1997) for combining two sampling techniques f and g.
//!
//! A sample drawn by technique f (`n_f` samples with density `pdf_f`, the other technique taking `n_g`
//! samples with density `pdf_g` *at the same point*, both densities in the same measure) gets weight
//! w_f; the weights of the two techniques at one point sum to 1, which keeps the combination unbiased.
//!
//! The weights are defined for every pdf in [0, ∞], and always finite in [0, 1]:
//! - pdf_f = 0 (or NaN, or n_f = 0): f could not have drawn the point, weight 0;
//! - pdf_f = ∞ (a delta lobe or delta light) and pdf_g finite: weight 1; pdf_g = ∞ and pdf_f finite: 0;
//! - both infinite: the limit of scaling both pdfs together, n_f^β / (n_f^β + n_g^β);
//! - pdf_g = 0 (or NaN): weight 1 whenever pdf_f > 0.
//!
//! Products that would overflow or underflow in the textbook formula (pdfs near 1e±20 for the power
//! heuristic) are handled by computing the ratio r = (n_g pdf_g) / (n_f pdf_f) first: w_f = 1 / (1 + r^β).

/// The balance heuristic n_f p_f / (n_f p_f + n_g p_g): provably close to optimal (Veach's theorem 9.2).
#[inline]
pub fn balance_heuristic(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    heuristic(n_f, pdf_f, n_g, pdf_g, |r| r)
}

/// The power heuristic with β = 2, (n_f p_f)² / ((n_f p_f)² + (n_g p_g)²): sharper than the balance
/// heuristic where one technique is much better, which usually lowers variance further.
#[inline]
pub fn power_heuristic(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    heuristic(n_f, pdf_f, n_g, pdf_g, |r| r * r)
}

/// 1 / (1 + power(r)) for r = (n_g p_g) / (n_f p_f), with the limits above.
#[inline]
fn heuristic(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32, power: impl Fn(f32) -> f32) -> f32 {
    let f = n_f * pdf_f;
    let g = n_g * pdf_g;
    if f.is_nan() || f <= 0.0 {
        return 0.0;
    }
    if g.is_nan() || g <= 0.0 {
        return 1.0;
    }
    match (f.is_infinite(), g.is_infinite()) {
        (true, true) => {
            let (a, b) = (power(n_f), power(n_g));
            a / (a + b)
        }
        (true, false) => 1.0,
        (false, true) => 0.0,
        (false, false) => 1.0 / (1.0 + power(g / f)),
    }
}
