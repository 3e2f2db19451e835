//! Adaptive cubature over rectangles, for integrating pdfs over the bins of a chi-square grid.

/// Three-point Gauss–Legendre nodes on [−1, 1]: √(3/5) · (−1, 0, 1).
const GAUSS_NODES: [f64; 3] = [-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4];
/// Their weights: (5, 8, 5) / 9.
const GAUSS_WEIGHTS: [f64; 3] = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
/// Where the error-estimating rule's outer nodes sit on [−1, 1]: just inside the edges (0.05 % of the
/// half-width), so that a jump *exactly* on an edge is never seen, while one that passes between the
/// Gauss nodes and the edge is.
const EDGE_NODE: f64 = 0.999;
/// Nodes −c, 0, c with the weights that integrate cubics exactly: 1 / (3c²) outside, 2 − 2 / (3c²) in
/// the centre (Simpson's rule for c = 1).
const EDGE_WEIGHTS: [f64; 3] = [
    1.0 / (3.0 * EDGE_NODE * EDGE_NODE),
    2.0 - 2.0 / (3.0 * EDGE_NODE * EDGE_NODE),
    1.0 / (3.0 * EDGE_NODE * EDGE_NODE),
];

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

/// Two estimates of ∫∫ f over `r`: the 3 × 3 Gauss–Legendre product rule (exact for polynomials of
/// degree 5 in each variable; the value used) and a 3 × 3 Simpson-like rule with nodes next to the
/// edges and corners (sharing the centre node; used only to estimate the error).
///
/// Neither rule evaluates f on the rectangle's boundary, so a pdf that jumps exactly on a bin edge (a
/// hemisphere pdf at cos θ = 0) is integrated as if it were smooth. A jump that passes between the Gauss
/// nodes and an edge makes the two rules disagree, and the cell is refined.
fn estimates(f: &impl Fn(f64, f64) -> f64, r: Rect) -> (f64, f64) {
    let (ha, ca) = (0.5 * (r.a1 - r.a0), 0.5 * (r.a1 + r.a0));
    let (hb, cb) = (0.5 * (r.b1 - r.b0), 0.5 * (r.b1 + r.b0));
    let centre = f(ca, cb);
    let (mut gauss, mut edge) = (0.0, 0.0);
    for i in 0..3 {
        for j in 0..3 {
            let (g, s) = if i == 1 && j == 1 {
                (centre, centre)
            } else {
                let (ta, tb) = ((i as f64 - 1.0) * EDGE_NODE, (j as f64 - 1.0) * EDGE_NODE);
                (
                    f(ca + ha * GAUSS_NODES[i], cb + hb * GAUSS_NODES[j]),
                    f(ca + ha * ta, cb + hb * tb),
                )
            };
            gauss += GAUSS_WEIGHTS[i] * GAUSS_WEIGHTS[j] * g;
            edge += EDGE_WEIGHTS[i] * EDGE_WEIGHTS[j] * s;
        }
    }
    (gauss * ha * hb, edge * ha * hb)
}

/// How deep [`integrate`] refines: always `min` times, at most `max` times.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Depth {
    pub(crate) min: u32,
    pub(crate) max: u32,
}

/// ∫∫ f over `rect` by the Gauss rule, splitting cells into quarters at least `depth.min` times and
/// then (at most `depth.max` times in all) wherever the two estimates of a cell differ by
/// more than `tolerance` (absolute, for the whole rectangle; halved at each level).
///
/// `tolerance` is a function of a first, coarse estimate, so that callers can ask for an accuracy
/// relative to what the rectangle holds.
pub(crate) fn integrate(
    f: &impl Fn(f64, f64) -> f64,
    rect: Rect,
    tolerance: impl Fn(f64) -> f64,
    depth: Depth,
) -> f64 {
    let (coarse, _) = estimates(f, rect);
    refine(f, rect, tolerance(coarse), 0, depth)
}

fn refine(
    f: &impl Fn(f64, f64) -> f64,
    rect: Rect,
    tolerance: f64,
    level: u32,
    depth: Depth,
) -> f64 {
    if level >= depth.min {
        let (gauss, edge) = estimates(f, rect);
        if level >= depth.max || (gauss - edge).abs() <= tolerance {
            return gauss;
        }
    }
    rect.quarters()
        .iter()
        .map(|&q| refine(f, q, 0.5 * tolerance, level + 1, depth))
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
    fn both_rules_integrate_cubics_exactly() {
        let f = |a: f64, b: f64| 1.0 + a * a * a - 2.0 * a * b * b + b * b;
        let (gauss, edge) = estimates(&f, UNIT);
        // ∫∫ 1 + a³ − 2ab² + b² = 1 + 1/4 − 1/3 + 1/3.
        assert!((gauss - 1.25).abs() < 1e-14, "{gauss}");
        assert!((edge - 1.25).abs() < 1e-14, "{edge}");
    }

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
        assert!((fine - exact).abs() < 1e-4, "{fine} vs {exact}");
        assert!(
            (fine - exact).abs() < 0.02 * (coarse - exact).abs(),
            "coarse {coarse}"
        );
    }

    #[test]
    fn sees_a_jump_between_the_gauss_nodes_and_an_edge() {
        // A step just above a cell boundary at depth 2 (b = 0.984375), below every Gauss node of that
        // cell: the Gauss rule alone would count the sliver [0.984375, 0.985) as inside.
        let f = |_: f64, b: f64| f64::from(b >= 0.985);
        let got = integrate(&f, UNIT, |_| 1e-7, Depth { min: 2, max: 9 });
        assert!((got - 0.015).abs() < 1.5e-4, "{got}");
    }

    #[test]
    fn a_jump_on_an_edge_is_integrated_exactly() {
        let f = |a: f64, _: f64| f64::from(a >= 0.5);
        let got = integrate(&f, UNIT, |_| 1e-9, Depth { min: 1, max: 12 });
        assert!((got - 0.5).abs() < 1e-12, "{got}");
    }
}
