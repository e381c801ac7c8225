//! Sub-pixel refinement of the best offset by a least-squares 2-D quadratic (paper 000 §5).

/// Second derivatives of the quadratic fitted to the scores around the best offset.
///
/// # Units
/// Score units per px² (for [`ScoreMap::normalized`](super::ScoreMap::normalized) scores: fraction
/// of disagreeing bits per px²). A sharper, more certain peak has larger curvature; with a score
/// noise σ_s, the offset's standard deviation scales like `σ_s / sqrt(curvature)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curvature {
    /// ∂²f/∂x² (x = column offset, east).
    pub f_xx: f64,
    /// ∂²f/∂x∂y.
    pub f_xy: f64,
    /// ∂²f/∂y² (y = row offset, south).
    pub f_yy: f64,
}

impl Curvature {
    /// Determinant of the Hessian `[[f_xx, f_xy], [f_xy, f_yy]]`; positive with `f_xx > 0` at a
    /// minimum.
    #[must_use]
    pub fn determinant(&self) -> f64 {
        self.f_xx * self.f_yy - self.f_xy * self.f_xy
    }
}

/// Largest sub-pixel correction returned, px: a fit that puts its minimum further away than the
/// neighbouring offsets is extrapolating.
const MAX_SHIFT_PX: f64 = 1.0;

/// Refine the integer minimum `best = (col, row)` of a row-major score map (`width × height`,
/// lower is better) to sub-pixel precision.
///
/// Fits `f(x, y) = a + b·x + c·y + d·x² + e·x·y + g·y²` by least squares to the 9 scores at
/// `x, y ∈ {−1, 0, 1}` around `best`. On this symmetric grid the normal equations decouple:
/// with `z(x, y)` the scores, `Cₓ = Σ_y z(x, y)` the column sums and `R_y = Σ_x z(x, y)` the row
/// sums,
///
/// - `b = (C₁ − C₋₁) / 6`, `c = (R₁ − R₋₁) / 6`,
/// - `d = (C₋₁ − 2·C₀ + C₁) / 6`, `g = (R₋₁ − 2·R₀ + R₁) / 6`,
/// - `e = (z(1,1) + z(−1,−1) − z(1,−1) − z(−1,1)) / 4`.
///
/// The Hessian is `H = [[2d, e], [e, 2g]]`; where `∇f = 0`,
/// `δx = (e·c − 2g·b) / det H` and `δy = (e·b − 2d·c) / det H`.
///
/// Returns `(δx, δy, curvature)`: the sub-pixel offset of the fitted minimum **relative to
/// `best`**, each component clamped to ±1 px, and the fitted second derivatives
/// (`f_xx = 2d`, `f_xy = e`, `f_yy = 2g`). The refined offset is `best.0 as f64 + δx`,
/// `best.1 as f64 + δy`.
///
/// `None` when `best` is on the border of the score map (no 3×3 neighbourhood), when a score in
/// the neighbourhood is not finite (no comparable bits, see
/// [`ScoreMap::normalized_scores`](super::ScoreMap::normalized_scores)), or when the fitted
/// surface has no minimum (`2d ≤ 0` or `det H ≤ 0`: a ridge, saddle or maximum).
///
/// # Panics
/// If `scores.len() != width * height`.
#[must_use]
pub fn subpixel_peak(
    scores: &[f64],
    width: usize,
    height: usize,
    best: (usize, usize),
) -> Option<(f64, f64, Curvature)> {
    assert_eq!(
        scores.len(),
        width * height,
        "subpixel_peak: scores must hold width × height values"
    );
    let (bx, by) = best;
    if bx == 0 || by == 0 || bx + 1 >= width || by + 1 >= height {
        return None;
    }
    // z[row][col] for row, col ∈ {0, 1, 2} ↔ y, x ∈ {−1, 0, 1}.
    let mut z = [[0.0f64; 3]; 3];
    for (j, row) in z.iter_mut().enumerate() {
        for (i, v) in row.iter_mut().enumerate() {
            *v = scores[(by + j - 1) * width + bx + i - 1];
            if !v.is_finite() {
                return None;
            }
        }
    }
    let col = |i: usize| z[0][i] + z[1][i] + z[2][i];
    let row = |j: usize| z[j][0] + z[j][1] + z[j][2];
    let b = (col(2) - col(0)) / 6.0;
    let c = (row(2) - row(0)) / 6.0;
    let d = (col(0) - 2.0 * col(1) + col(2)) / 6.0;
    let g = (row(0) - 2.0 * row(1) + row(2)) / 6.0;
    let e = (z[2][2] + z[0][0] - z[0][2] - z[2][0]) / 4.0;
    let curvature = Curvature {
        f_xx: 2.0 * d,
        f_xy: e,
        f_yy: 2.0 * g,
    };
    let det = curvature.determinant();
    if !(curvature.f_xx > 0.0 && det > 0.0) {
        return None;
    }
    let dx = (e * c - curvature.f_yy * b) / det;
    let dy = (e * b - curvature.f_xx * c) / det;
    Some((
        dx.clamp(-MAX_SHIFT_PX, MAX_SHIFT_PX),
        dy.clamp(-MAX_SHIFT_PX, MAX_SHIFT_PX),
        curvature,
    ))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A `w × h` map of `q(x − x0, y − y0)` for a positive-definite quadratic `q`.
    fn bowl(w: usize, h: usize, x0: f64, y0: f64, xy: f64) -> Vec<f64> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 - x0, (i / w) as f64 - y0);
                0.2 + 0.03 * x * x + xy * x * y + 0.05 * y * y
            })
            .collect()
    }

    #[test]
    fn recovers_the_minimum_of_an_exact_quadratic() {
        for (x0, y0, xy) in [(4.3, 5.8, 0.0), (4.5, 5.5, 0.01), (3.71, 6.22, -0.02)] {
            let s = bowl(9, 11, x0, y0, xy);
            let best = (x0.round() as usize, y0.round() as usize);
            let (dx, dy, k) = subpixel_peak(&s, 9, 11, best).unwrap();
            assert!((best.0 as f64 + dx - x0).abs() < 1e-12, "{dx}");
            assert!((best.1 as f64 + dy - y0).abs() < 1e-12, "{dy}");
            assert!((k.f_xx - 0.06).abs() < 1e-12 && (k.f_yy - 0.1).abs() < 1e-12);
            assert!((k.f_xy - xy).abs() < 1e-12);
        }
    }

    #[test]
    fn clamps_far_minima_to_one_pixel() {
        let s = bowl(9, 9, 2.0, 7.5, 0.0); // true minimum 2 px west, 3.5 px south of (4, 4)
        let (dx, dy, _) = subpixel_peak(&s, 9, 9, (4, 4)).unwrap();
        assert_eq!((dx, dy), (-1.0, 1.0));
    }

    #[test]
    fn none_at_the_border_without_a_minimum_or_with_missing_scores() {
        let s = bowl(6, 5, 2.0, 2.0, 0.0);
        for best in [(0, 2), (5, 2), (2, 0), (2, 4)] {
            assert!(subpixel_peak(&s, 6, 5, best).is_none());
        }
        let peak: Vec<f64> = s.iter().map(|v| -v).collect();
        assert!(subpixel_peak(&peak, 6, 5, (2, 2)).is_none());
        let saddle = bowl(6, 5, 2.0, 2.0, 0.2); // 0.03·0.05·4 < 0.2²
        assert!(subpixel_peak(&saddle, 6, 5, (2, 2)).is_none());
        let flat = vec![0.3; 30];
        assert!(subpixel_peak(&flat, 6, 5, (2, 2)).is_none());
        let mut holed = s.clone();
        holed[3 * 6 + 3] = f64::INFINITY;
        assert!(subpixel_peak(&holed, 6, 5, (2, 2)).is_none());
        assert!(subpixel_peak(&[], 0, 0, (0, 0)).is_none());
    }
}
