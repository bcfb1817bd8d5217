//! Tests of the per-step kernels: the AVX builds against the scalar code,
//! bit for bit, over every remainder of the lanes, chunks and groups.

use super::*;
use crate::model::convolution::StepColumns;

/// Deterministic values of mixed sign and scale (no RNG needed).
fn vals(n: usize, seed: f64) -> Vec<f64> {
    (0..n)
        .map(|k| ((k as f64 + 1.0) * seed).sin() * 10f64.powi((k % 7) as i32 - 3))
        .collect()
}

fn columns(n: usize) -> StepColumns {
    StepColumns {
        pxx: vals(n, 0.31),
        pxv: vals(n, 0.47),
        pvx: vals(n, 0.53),
        pvv: vals(n, 0.61),
        w1x: vals(n, 0.71),
        w1v: vals(n, 0.83),
        w2x: vals(n, 0.97),
        w2v: vals(n, 1.09),
    }
}

#[test]
fn dispatched_kernels_equal_the_scalar_code_bit_for_bit() {
    // every remainder of the 4-wide lanes, the chunks of states and
    // the groups of eight and four active columns (1 to 20 of them:
    // 8 + 8 + 4, 8 + 4 + 2, ...)
    for ns in [1, 3, 4, 5, 15, 16, 17, 33, 65, 70, 255, 256, 257, 530] {
        for p in [1, 3, 4, 5, 9, 16, 17, 27, 40] {
            let (x, v) = (vals(ns, 1.3), vals(ns, 1.7));
            let out = vals(p * ns, 2.1);
            let (mut u1, mut w1, mut u2, mut w2) =
                (vec![0.0; p], vec![0.0; p], vec![0.0; p], vec![0.0; p]);
            project(&out, p, &x, &v, &mut u1, &mut w1);
            project_body(&out, p, &x, &v, &mut u2, &mut w2);
            let bits = |a: &[f64]| a.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&u1), bits(&u2), "project u, ns {ns}, p {p}");
            assert_eq!(bits(&w1), bits(&w2), "project v, ns {ns}, p {p}");

            let c = columns(ns);
            let inp_t = vals(p * ns, 2.9);
            let (q1, q2) = (vals(p, 3.1), vals(p, 3.7));
            let active: Vec<usize> = (0..p).rev().step_by(2).collect();
            let (mut xa, mut va, mut xb, mut vb) = (x.clone(), v.clone(), x.clone(), v.clone());
            add_gauss_forces(&c, &inp_t, &active, &q1, &q2, &mut xa, &mut va);
            add_gauss_forces_body::<false>(&c, 0, &inp_t, ns, &active, &q1, &q2, &mut xb, &mut vb);
            assert_eq!(bits(&xa), bits(&xb), "forces x, ns {ns}, p {p}");
            assert_eq!(bits(&va), bits(&vb), "forces v, ns {ns}, p {p}");
            // and the forces did something
            assert_ne!(bits(&xa), bits(&x));

            let (mut ox1, mut ov1, mut ox2, mut ov2) =
                (vec![0.0; ns], vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]);
            predict(&c, &x, &v, &mut ox1, &mut ov1);
            predict_body::<false>(&c, 0, &x, &v, &mut ox2, &mut ov2);
            assert_eq!(bits(&ox1), bits(&ox2));
            assert_eq!(bits(&ov1), bits(&ov2));
        }
    }
}

/// The gathered rows (any order, repeats, every count modulo the six
/// rows a pass takes) give, bit for bit, [`dot2`] of each row alone,
/// through both the scattered and the packed outputs.
#[test]
fn gathered_rows_equal_each_row_alone_bit_for_bit() {
    let bits = |a: &[f64]| a.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for ns in [1usize, 3, 4, 5, 17, 36, 70] {
        let p = 15;
        let (x, v) = (vals(ns, 1.3), vals(ns, 1.7));
        let out = vals(p * ns, 2.1);
        for count in 0..=13 {
            // rows in a scrambled order with one repeat
            let rows: Vec<usize> = (0..count).map(|k| (7 * k + 3) % p).collect();
            let alone: Vec<(f64, f64)> = rows
                .iter()
                .map(|&i| dot2(&out[i * ns..(i + 1) * ns], &x, &v))
                .collect();
            let (mut pu, mut pv) = (vec![0.0; count], vec![0.0; count]);
            project_rows_packed(&out, ns, &rows, &x, &v, &mut pu, &mut pv);
            let (au, av): (Vec<f64>, Vec<f64>) = alone.iter().copied().unzip();
            assert_eq!(
                (bits(&pu), bits(&pv)),
                (bits(&au), bits(&av)),
                "packed, ns {ns}, {count} rows"
            );
            let (mut u, mut w) = (vec![f64::NAN; p], vec![f64::NAN; p]);
            project_rows(&out, ns, &rows, &x, &v, &mut u, &mut w);
            for (k, &i) in rows.iter().enumerate() {
                assert_eq!(
                    (u[i].to_bits(), w[i].to_bits()),
                    (au[k].to_bits(), av[k].to_bits())
                );
            }
        }
    }
}

/// The kernels over the pieces of any split of the rows or states
/// give, bit for bit, what they give over the whole: the property the
/// threads' fixed partition relies on. Changing a piece's operations
/// by its position (a sum carried across pieces, a block that starts
/// elsewhere) fails it.
#[test]
fn kernels_over_pieces_equal_the_whole_bit_for_bit() {
    let bits = |a: &[f64]| a.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for ns in [4, 17, 36, 70, 300] {
        let p = 13;
        let (x, v) = (vals(ns, 1.3), vals(ns, 1.7));
        let out = vals(p * ns, 2.1);
        let cols = columns(ns);
        let inp_t = vals(p * ns, 2.9);
        let (q1, q2) = (vals(p, 3.1), vals(p, 3.7));
        let active: Vec<usize> = vec![7, 2, 11, 0, 5];
        // the whole
        let (mut u, mut w) = (vec![0.0; p], vec![0.0; p]);
        project(&out, p, &x, &v, &mut u, &mut w);
        let (mut xa, mut va) = (x.clone(), v.clone());
        add_gauss_forces(&cols, &inp_t, &active, &q1, &q2, &mut xa, &mut va);
        let (mut ox, mut ov) = (vec![0.0; ns], vec![0.0; ns]);
        predict(&cols, &x, &v, &mut ox, &mut ov);
        for cut in 1..p {
            let (mut u2, mut w2) = (vec![0.0; p], vec![0.0; p]);
            for r in [0..cut, cut..p] {
                project(
                    &out[r.start * ns..r.end * ns],
                    r.len(),
                    &x,
                    &v,
                    &mut u2[r.clone()],
                    &mut w2[r],
                );
            }
            assert_eq!(
                (bits(&u), bits(&w)),
                (bits(&u2), bits(&w2)),
                "rows cut {cut}"
            );
        }
        for cut in 1..ns {
            let (mut xb, mut vb) = (x.clone(), v.clone());
            let (mut ox2, mut ov2) = (vec![0.0; ns], vec![0.0; ns]);
            for r in [0..cut, cut..ns] {
                add_gauss_forces_range(
                    &cols,
                    r.start,
                    &inp_t,
                    ns,
                    &active,
                    &q1,
                    &q2,
                    &mut xb[r.clone()],
                    &mut vb[r.clone()],
                );
                predict_range(
                    &cols,
                    r.start,
                    &x[r.clone()],
                    &v[r.clone()],
                    &mut ox2[r.clone()],
                    &mut ov2[r],
                );
            }
            assert_eq!(
                (bits(&xa), bits(&va)),
                (bits(&xb), bits(&vb)),
                "states cut {cut}"
            );
            assert_eq!(
                (bits(&ox), bits(&ov)),
                (bits(&ox2), bits(&ov2)),
                "states cut {cut}"
            );
        }
    }
}
