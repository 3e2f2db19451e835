//! Adaptive cubature over rectangles, for integrating pdfs over the bins of a chi-square grid.

/// Three-point Gauss–Legendre nodes on [−1, 1]: √(3/5) · (−1, 0, 1).
const NODES: [f64; 3] = [-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4];
/// Their weights: (5, 8, 5) / 9.
const WEIGHTS: [f64; 3] = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];

/// An axis-aligned rectangle [a0, a1) × [b0, b1) in a domain's parameter square.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rect {
    pub(crate) a0: f64,
    pub(crate) a1: f64,
    pub(crate) b0: f64,
    pub(crate) b1: f64,
}

impl Rect {
    fn quarters(self) -> [Rect; 4] {
        let am = 0.5 * (self.a0 + self.a1);
        let bm = 0.5 * (self.b0 + self.b1);
        [
            Rect {
                a1: am,
                b1: bm,
                ..self
            },
            Rect {
                a0: am,
                b1: bm,
                ..self
            },
            Rect {
                a1: am,
                b0: bm,
                ..self
            },
            Rect {
                a0: am,
                b0: bm,
                ..self
            },
        ]
    }
}

/// The 3 × 3 Gauss–Legendre product rule: exact for polynomials of degree 5 in each variable.
///
/// Its nodes are strictly inside the rectangle, so a pdf that jumps exactly on a bin edge (a hemisphere
/// pdf at cos θ = 0, say) is integrated as if it were smooth.
fn gauss(f: &impl Fn(f64, f64) -> f64, r: Rect) -> f64 {
    let (ha, ca) = (0.5 * (r.a1 - r.a0), 0.5 * (r.a1 + r.a0));
    let (hb, cb) = (0.5 * (r.b1 - r.b0), 0.5 * (r.b1 + r.b0));
    let mut sum = 0.0;
    for (xa, wa) in NODES.iter().zip(WEIGHTS) {
        for (xb, wb) in NODES.iter().zip(WEIGHTS) {
            sum += wa * wb * f(ca + ha * xa, cb + hb * xb);
        }
    }
    sum * ha * hb
}

/// How deep [`integrate`] refines: always `min` times, at most `max` times.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Depth {
    pub(crate) min: u32,
    pub(crate) max: u32,
}

/// ∫∫ f over `rect`, splitting it into quarters at least `depth.min` times and then (at most
/// `depth.max` times in all) wherever the quarters' sum differs from the whole's estimate by more than
/// `tolerance` (absolute, for the whole rectangle; halved at each level).
///
/// `tolerance` is a function of the first, coarse estimate, so that callers can ask for an accuracy
/// relative to what the rectangle holds. The forced levels keep features a little smaller than the
/// rectangle (a discontinuity clipping one corner) from slipping between all the nodes unnoticed.
pub(crate) fn integrate(
    f: &impl Fn(f64, f64) -> f64,
    rect: Rect,
    tolerance: impl Fn(f64) -> f64,
    depth: Depth,
) -> f64 {
    let coarse = gauss(f, rect);
    refine(f, rect, coarse, tolerance(coarse), 0, depth)
}

fn refine(
    f: &impl Fn(f64, f64) -> f64,
    rect: Rect,
    whole: f64,
    tolerance: f64,
    level: u32,
    depth: Depth,
) -> f64 {
    let quarters = rect.quarters();
    let parts = quarters.map(|q| gauss(f, q));
    let fine: f64 = parts.iter().sum();
    let converged = level >= depth.min && (fine - whole).abs() <= tolerance;
    if level >= depth.max || converged {
        return fine;
    }
    quarters
        .iter()
        .zip(parts)
        .map(|(&q, part)| refine(f, q, part, 0.5 * tolerance, level + 1, depth))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: Rect = Rect {
        a0: 0.0,
        a1: 1.0,
        b0: 0.0,
        b1: 1.0,
    };

    #[test]
    fn exact_for_low_degree_polynomials() {
        let f = |a: f64, b: f64| a.powi(5) * b * b + 3.0 * a * b.powi(4);
        // ∫∫ a⁵b² + 3ab⁴ = 1/18 + 3/10.
        let got = integrate(&f, UNIT, |_| 0.0, Depth { min: 0, max: 0 });
        assert!((got - (1.0 / 18.0 + 0.3)).abs() < 1e-14, "{got}");
    }

    #[test]
    fn refines_along_a_discontinuity() {
        // The indicator of the disc of radius 0.4 around the centre: area 0.16 π.
        let f = |a: f64, b: f64| f64::from((a - 0.5).powi(2) + (b - 0.5).powi(2) < 0.16);
        let coarse = integrate(&f, UNIT, |_| f64::INFINITY, Depth { min: 0, max: 0 });
        let fine = integrate(&f, UNIT, |_| 1e-6, Depth { min: 2, max: 9 });
        let exact = 0.16 * std::f64::consts::PI;
        assert!((fine - exact).abs() < 5e-4, "{fine} vs {exact}");
        assert!(
            (fine - exact).abs() < 0.02 * (coarse - exact).abs(),
            "coarse {coarse}"
        );
    }
}
