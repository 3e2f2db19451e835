//! Gauss–Legendre quadrature, for the tables that BSDFs compute once when they are built.

/// The nodes and weights of `n`-point Gauss–Legendre quadrature on [0, 1] (the weights sum to
/// 1), exact for polynomials of degree below 2n. Nodes are the roots of the Legendre polynomial
/// Pₙ, found by Newton's method from Tricomi's estimate, in double precision.
pub(crate) fn gauss_legendre_unit(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            // Roots of Pₙ on [−1, 1], largest first.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 0.0;
            for _ in 0..100 {
                let (p, dp) = legendre_with_derivative(n, x);
                derivative = dp;
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-15 {
                    break;
                }
            }
            let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
            (0.5 * (1.0 - x), 0.5 * weight)
        })
        .collect()
}

/// Pₙ(x) and Pₙ′(x) by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    for k in 2..=n {
        let next = ((2 * k - 1) as f64 * x * current - (k - 1) as f64 * previous) / k as f64;
        previous = current;
        current = next;
    }
    let derivative = n as f64 * (x * current - previous) / (x * x - 1.0);
    (current, derivative)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_up_to_degree_2n_minus_1_exactly() {
        for n in [1, 4, 32, 64] {
            let rule = gauss_legendre_unit(n);
            let total: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-13, "n {n}: weights sum to {total}");
            for degree in [1, 2 * n - 1] {
                let integral: f64 = rule.iter().map(|(x, w)| w * x.powi(degree as i32)).sum();
                let exact = 1.0 / (degree as f64 + 1.0);
                assert!(
                    (integral - exact).abs() < 1e-12,
                    "n {n}, x^{degree}: {integral} against {exact}"
                );
            }
            assert!(rule.iter().all(|&(x, _)| x > 0.0 && x < 1.0), "n {n}");
        }
        // One degree more than the rule is exact for is not integrated exactly.
        let rule = gauss_legendre_unit(4);
        let integral: f64 = rule.iter().map(|(x, w)| w * x.powi(8)).sum();
        assert!((integral - 1.0 / 9.0).abs() > 1e-9);
    }
}
