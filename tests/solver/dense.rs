//! A dense solve for the reference computations of the solver tests: the
//! tests' own, independent of the crate's decompositions.

/// Solves `a x = b` (small, dense) by Gaussian elimination with partial
/// pivoting; `None` if a pivot is zero.
pub fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))?;
        if a[p][c] == 0.0 {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..n {
            let f = a[r][c] / a[c][c];
            for k in c..n {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}

/// [`solve`] after scaling each row of `a` and `b` by the row's largest
/// `|a_ij|` (row equilibration: rows of very different magnitude, as in a
/// contact system of mixed units); `None` if a row is zero.
pub fn solve_equilibrated(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    for (row, bi) in a.iter_mut().zip(b.iter_mut()) {
        let s = row.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if s == 0.0 {
            return None;
        }
        for x in row.iter_mut() {
            *x /= s;
        }
        *bi /= s;
    }
    solve(a, b)
}
