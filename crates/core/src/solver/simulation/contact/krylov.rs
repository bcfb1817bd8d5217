//! Restarted GMRES (Saad and Schultz 1986) for the sub-step contact systems
//! of large active sets (method §4.5, "Large active sets"): the operator is
//! applied through the modal states in `O(|S| K)` instead of filling the
//! `|S|²` blocks (`O(|S|² K)`) and factorising them (`O(|S|³)`). The
//! caller passes the preconditioned operator `P⁻¹ M` and right-hand side
//! `P⁻¹ b`; the iteration stops when the preconditioned residual is below a
//! relative tolerance, and reports whether it got there (the caller then
//! falls back to the direct solve). Buffers are sized once.

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Operator applications, the initial residual's included.
    pub applications: usize,
    /// The final residual `‖P⁻¹(b - M x)‖₂` over `‖P⁻¹ b‖₂`.
    pub relative_residual: f64,
    pub converged: bool,
}

/// GMRES(`restart`) over vectors of up to `cap` entries.
#[derive(Debug, Clone)]
pub struct Gmres {
    cap: usize,
    restart: usize,
    /// The Krylov basis, `restart + 1` vectors of `cap`.
    basis: Vec<f64>,
    /// The Hessenberg matrix, column `j` at `j (restart + 1)`.
    h: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    w: Vec<f64>,
}

impl Gmres {
    pub fn new(cap: usize, restart: usize) -> Self {
        let restart = restart.max(1);
        Gmres {
            cap,
            restart,
            basis: vec![0.0; (restart + 1) * cap],
            h: vec![0.0; (restart + 1) * restart],
            cs: vec![0.0; restart],
            sn: vec![0.0; restart],
            g: vec![0.0; restart + 1],
            w: vec![0.0; cap],
        }
    }

    /// Solves `A x = b` for `A` given by `apply(v, out)` (`out ← A v`),
    /// from the guess in `x`, to `‖b - A x‖ ≤ tol ‖b‖` or `max_applications`.
    pub fn solve(
        &mut self,
        n: usize,
        mut apply: impl FnMut(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        tol: f64,
        max_applications: usize,
    ) -> Outcome {
        assert!(n <= self.cap, "system larger than the Krylov buffers");
        let (m, cap) = (self.restart, self.cap);
        let b_norm = norm(&b[..n]);
        let mut out = Outcome {
            applications: 0,
            relative_residual: 0.0,
            converged: true,
        };
        if b_norm == 0.0 {
            x[..n].fill(0.0);
            return out;
        }
        let target = tol * b_norm;
        loop {
            // r = b - A x into the first basis vector
            let (v0, _) = self.basis.split_at_mut(cap);
            apply(&x[..n], &mut self.w[..n]);
            out.applications += 1;
            for ((r, bi), ax) in v0[..n].iter_mut().zip(&b[..n]).zip(&self.w[..n]) {
                *r = bi - ax;
            }
            let beta = norm(&v0[..n]);
            out.relative_residual = beta / b_norm;
            if !beta.is_finite() {
                out.converged = false;
                return out;
            }
            if beta <= target {
                out.converged = true;
                return out;
            }
            if out.applications >= max_applications {
                out.converged = false;
                return out;
            }
            v0[..n].iter_mut().for_each(|r| *r /= beta);
            self.g.fill(0.0);
            self.g[0] = beta;
            let mut k = 0;
            while k < m {
                // w = A v_k, orthogonalised against v_0..v_k (modified Gram–Schmidt)
                let (head, tail) = self.basis.split_at_mut((k + 1) * cap);
                apply(&head[k * cap..k * cap + n], &mut tail[..n]);
                out.applications += 1;
                let w = &mut tail[..n];
                let col = &mut self.h[k * (m + 1)..(k + 1) * (m + 1)];
                for i in 0..=k {
                    let vi = &head[i * cap..i * cap + n];
                    let hik: f64 = vi.iter().zip(w.iter()).map(|(a, b)| a * b).sum();
                    col[i] = hik;
                    w.iter_mut().zip(vi).for_each(|(wj, vj)| *wj -= hik * vj);
                }
                let hk = norm(w);
                col[k + 1] = hk;
                if hk > 0.0 {
                    w.iter_mut().for_each(|wj| *wj /= hk);
                }
                // the previous rotations on column k, then the new one
                for i in 0..k {
                    let (c, s) = (self.cs[i], self.sn[i]);
                    let (a, b) = (col[i], col[i + 1]);
                    col[i] = c * a + s * b;
                    col[i + 1] = -s * a + c * b;
                }
                let (a, b) = (col[k], col[k + 1]);
                let r = a.hypot(b);
                let (c, s) = if r == 0.0 { (1.0, 0.0) } else { (a / r, b / r) };
                (self.cs[k], self.sn[k]) = (c, s);
                col[k] = r;
                col[k + 1] = 0.0;
                self.g[k + 1] = -s * self.g[k];
                self.g[k] *= c;
                k += 1;
                let resid = self.g[k].abs();
                if resid <= target || hk == 0.0 || out.applications >= max_applications {
                    break;
                }
            }
            // y = H⁻¹ g (upper triangular, k × k), x += V y
            for i in (0..k).rev() {
                let mut s = self.g[i];
                for j in i + 1..k {
                    s -= self.h[j * (m + 1) + i] * self.g[j];
                }
                self.g[i] = s / self.h[i * (m + 1) + i];
            }
            for j in 0..k {
                let yj = self.g[j];
                let vj = &self.basis[j * cap..j * cap + n];
                x[..n].iter_mut().zip(vj).for_each(|(xi, v)| *xi += yj * v);
            }
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matvec(a: &[f64], n: usize) -> impl Fn(&[f64], &mut [f64]) + '_ {
        move |v, out| {
            for (o, row) in out[..n].iter_mut().zip(a.chunks_exact(n)) {
                *o = row.iter().zip(v).map(|(x, y)| x * y).sum();
            }
        }
    }

    /// A non-symmetric system near the identity plus a coupling of norm
    /// `c`: GMRES converges to the tolerance, and across restarts, and the
    /// solution satisfies the system.
    #[test]
    fn converges_on_nonsymmetric_systems_across_restarts() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for (n, c, restart) in [(1, 0.3, 5), (7, 0.5, 3), (40, 0.9, 10), (120, 0.7, 30)] {
            let mut a: Vec<f64> = (0..n * n).map(|_| rnd() * c / (n as f64).sqrt()).collect();
            for i in 0..n {
                a[i * n + i] += 1.0;
            }
            let x_true: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut b = vec![0.0; n];
            matvec(&a, n)(&x_true, &mut b);
            let mut x = vec![0.0; n];
            let mut g = Gmres::new(n + 3, restart);
            let out = g.solve(n, matvec(&a, n), &b, &mut x, 1e-13, 10 * n + 50);
            assert!(out.converged, "n {n}: {out:?}");
            let mut ax = vec![0.0; n];
            matvec(&a, n)(&x, &mut ax);
            let r = ax
                .iter()
                .zip(&b)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f64>()
                .sqrt();
            let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(r <= 2e-13 * bn, "n {n}: residual {r:e} of {bn:e}");
            let err = x
                .iter()
                .zip(&x_true)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(err < 1e-11, "n {n}: error {err:e}");
        }
    }

    /// An operator GMRES cannot solve in the allowed applications is
    /// reported as not converged (the caller's fallback), not as a
    /// solution.
    #[test]
    fn reports_no_convergence() {
        // a rotation-like operator: no progress within a short restart
        let n = 30;
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            a[i * n + (i + 1) % n] = 1.0;
        }
        let b: Vec<f64> = (0..n).map(|i| if i == 0 { 1.0 } else { 0.0 }).collect();
        let mut x = vec![0.0; n];
        let out = Gmres::new(n, 4).solve(n, matvec(&a, n), &b, &mut x, 1e-12, 20);
        assert!(!out.converged && out.relative_residual > 0.5, "{out:?}");
    }
}
