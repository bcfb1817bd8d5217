//! Dense solves of the contact problem (method §4): the `2|S| × 2|S|`
//! Gauss-point system and the `|S| × |S|` impulse system, with row and column
//! equilibration (rows of `g ~ dt` and `g' ~ 1` differ by orders of magnitude)
//! and LU with partial pivoting. All buffers are sized once; no allocation
//! per solve.

pub mod bordered;
pub mod krylov;

/// Why a solve failed: the smallest pivot after scaling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Singular {
    pub pivot: f64,
}

/// Pivots below this (after scaling to unit row and column maxima) are singular.
pub const PIVOT_TOL: f64 = 1e-11;

/// A reusable scaled dense solver of size up to `cap`.
#[derive(Debug, Clone)]
pub struct DenseSolver {
    cap: usize,
    n: usize,
    a: Vec<f64>,
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
    perm: Vec<usize>,
    /// Explicit inverse of the last factorisation, scalings included
    /// (`n × n` row-major), when [`DenseSolver::form_inverse`] was called.
    inv: Vec<f64>,
    /// Scratch: one column of the inverse, or the right-hand side.
    col: Vec<f64>,
    /// Smallest |pivot| of the last factorisation (after scaling).
    pub min_pivot: f64,
}

impl DenseSolver {
    pub fn new(cap: usize) -> Self {
        DenseSolver {
            cap,
            n: 0,
            a: vec![0.0; cap * cap],
            row_scale: vec![1.0; cap],
            col_scale: vec![1.0; cap],
            perm: vec![0; cap],
            inv: vec![0.0; cap * cap],
            col: vec![0.0; cap],
            min_pivot: 0.0,
        }
    }

    /// Factorises the `n × n` matrix given by `entry(r, c)`.
    pub fn factor(
        &mut self,
        n: usize,
        entry: impl Fn(usize, usize) -> f64,
    ) -> Result<(), Singular> {
        self.factor_filled(n, |a| {
            for (r, row) in a.chunks_exact_mut(n).enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    *x = entry(r, c);
                }
            }
        })
    }

    /// Factorises the `n × n` matrix that `fill` writes row-major into the
    /// slice it is given (every entry), as [`DenseSolver::factor`] does
    /// with the same values.
    pub fn factor_filled(
        &mut self,
        n: usize,
        fill: impl FnOnce(&mut [f64]),
    ) -> Result<(), Singular> {
        assert!(n <= self.cap, "contact system larger than its buffers");
        self.n = n;
        let a = &mut self.a[..n * n];
        fill(a);
        // Row, then column equilibration to unit max-norm.
        let row_scale = &mut self.row_scale[..n];
        for (row, rs) in a.chunks_exact_mut(n).zip(row_scale.iter_mut()) {
            let m = row.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let s = if m > 0.0 && m.is_finite() {
                1.0 / m
            } else {
                1.0
            };
            *rs = s;
            for x in row.iter_mut() {
                *x *= s;
            }
        }
        for c in 0..n {
            let m = a[c..]
                .iter()
                .step_by(n)
                .map(|x| x.abs())
                .fold(0.0, f64::max);
            let s = if m > 0.0 && m.is_finite() {
                1.0 / m
            } else {
                1.0
            };
            self.col_scale[c] = s;
            for x in a[c..].iter_mut().step_by(n) {
                *x *= s;
            }
        }
        let mut min_pivot = f64::INFINITY;
        for k in 0..n {
            let (mut p, mut best) = (k, a[k * n + k].abs());
            for r in k + 1..n {
                let v = a[r * n + k].abs();
                if v > best {
                    p = r;
                    best = v;
                }
            }
            self.perm[k] = p;
            min_pivot = min_pivot.min(best);
            if best.is_nan() || best <= PIVOT_TOL {
                self.min_pivot = best;
                return Err(Singular { pivot: best });
            }
            if p != k {
                for c in 0..n {
                    a.swap(k * n + c, p * n + c);
                }
            }
            let (top, below) = a.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n + k..];
            let piv = pivot_row[0];
            for row in below.chunks_exact_mut(n) {
                let f = row[k] / piv;
                row[k] = f;
                if f != 0.0 {
                    for (x, y) in row[k + 1..].iter_mut().zip(&pivot_row[1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        self.min_pivot = min_pivot;
        Ok(())
    }

    /// Forms the explicit inverse of the last factorisation (`n` solves,
    /// `O(n³)`), for a factorisation reused over many right-hand sides: a
    /// solve by [`DenseSolver::solve_by_inverse`] is then a product with no
    /// chain of divisions (the Gauss-point system is equilibrated, so the
    /// product is as accurate as the triangular solves to a few ulp).
    pub fn form_inverse(&mut self) {
        let n = self.n;
        for c in 0..n {
            let mut col = std::mem::take(&mut self.col);
            col[..n].fill(0.0);
            col[c] = 1.0;
            self.solve(&mut col[..n]);
            for r in 0..n {
                self.inv[r * n + c] = col[r];
            }
            self.col = col;
        }
    }

    /// The inverse formed by [`DenseSolver::form_inverse`] (`n × n`
    /// row-major).
    pub fn inverse(&self) -> &[f64] {
        &self.inv[..self.n * self.n]
    }

    /// `b ← A⁻¹ b` with the inverse formed by [`DenseSolver::form_inverse`]
    /// after the last factorisation.
    pub fn solve_by_inverse(&mut self, b: &mut [f64]) {
        // (fixed sizes for up to five points on the road: unrolled products)
        match self.n {
            2 => self.solve_by_inverse_n::<2>(b),
            4 => self.solve_by_inverse_n::<4>(b),
            6 => self.solve_by_inverse_n::<6>(b),
            8 => self.solve_by_inverse_n::<8>(b),
            10 => self.solve_by_inverse_n::<10>(b),
            n => {
                let (inv, col) = (&self.inv[..n * n], &mut self.col[..n]);
                let b = &mut b[..n];
                col.copy_from_slice(b);
                for (r, row) in inv.chunks_exact(n).enumerate() {
                    b[r] = dot_in_order(row, col);
                }
            }
        }
    }

    /// [`DenseSolver::solve_by_inverse`] with `n = N` known at compile time.
    #[inline(always)]
    fn solve_by_inverse_n<const N: usize>(&mut self, b: &mut [f64]) {
        let Ok(b) = <&mut [f64; N]>::try_from(&mut b[..N]) else {
            return;
        };
        let x = *b;
        for (br, row) in b.iter_mut().zip(self.inv[..N * N].chunks_exact(N)) {
            *br = dot_in_order(row, &x);
        }
    }

    /// Solves `A x = b` in place with the last factorisation.
    pub fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        let a = &self.a[..n * n];
        for r in 0..n {
            b[r] *= self.row_scale[r];
        }
        for k in 0..n {
            b.swap(k, self.perm[k]);
        }
        for r in 0..n {
            let mut s = b[r];
            for c in 0..r {
                s -= a[r * n + c] * b[c];
            }
            b[r] = s;
        }
        for r in (0..n).rev() {
            let mut s = b[r];
            for c in r + 1..n {
                s -= a[r * n + c] * b[c];
            }
            b[r] = s / a[r * n + r];
        }
        for c in 0..n {
            b[c] *= self.col_scale[c];
        }
    }
}

/// `Σ a_k x_k` summed from 0 in index order.
#[inline(always)]
fn dot_in_order(a: &[f64], x: &[f64]) -> f64 {
    let mut s = 0.0;
    for (a, x) in a.iter().zip(x) {
        s += a * x;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_badly_scaled_system() {
        // rows of scale 1e-5 and 1, as in the Gauss-point system at dt = 1e-5
        let m = [[2e-5, 1e-5, 3e-6], [0.5, -1.0, 0.2], [1e3, 2e2, 5e3]];
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = m
            .iter()
            .map(|r| r.iter().zip(&x).map(|(a, b)| a * b).sum())
            .collect();
        let mut s = DenseSolver::new(4);
        s.factor(3, |r, c| m[r][c]).unwrap();
        s.solve(&mut b);
        for k in 0..3 {
            assert!((b[k] - x[k]).abs() < 1e-12, "{b:?}");
        }
    }

    #[test]
    fn inverse_solves_as_the_factorisation_does() {
        let m = [[2e-5, 1e-5, 3e-6], [0.5, -1.0, 0.2], [1e3, 2e2, 5e3]];
        let mut s = DenseSolver::new(4);
        s.factor(3, |r, c| m[r][c]).unwrap();
        s.form_inverse();
        for x in [[1.0, -2.0, 0.5], [0.0, 3.0, -1e-3]] {
            let mut b: Vec<f64> = m
                .iter()
                .map(|r| r.iter().zip(&x).map(|(a, b)| a * b).sum())
                .collect();
            s.solve_by_inverse(&mut b);
            for k in 0..3 {
                assert!((b[k] - x[k]).abs() < 1e-12, "{b:?}");
            }
        }
    }

    #[test]
    fn reports_singular() {
        let mut s = DenseSolver::new(2);
        assert!(s.factor(2, |r, _| if r == 0 { 1.0 } else { 2.0 }).is_err());
    }
}
