//! The road under a fixed set of contact points (method §4): all points
//! sampled together, harmonic roads by angle addition from per-point phases
//! and, at consecutive step ends, from the previous step's angles.

use super::surface::{RowBlend, SurfaceGrid};
use super::{Harmonic, OutOfRange, RoadProfile};
use std::f64::consts::TAU;
use std::sync::Arc;

/// The road under a fixed set of points `x_i` shifted by the distance rolled
/// `s`: `z(x_i + s)` and `dz/dx`. For harmonic roads one `sin_cos` per
/// harmonic and step (angle addition from precomputed `sin_cos(κ x_i + φ)`)
/// instead of one per point and harmonic.
#[derive(Debug, Clone)]
pub struct PointsRoad {
    pub profile: Arc<RoadProfile>,
    x_m: Vec<f64>,
    /// `(sin, cos)` of `κ_h x_i + φ_h`, harmonic-major.
    phase: Vec<(f64, f64)>,
    /// Harmonic roads sampled at consecutive step ends.
    stepper: Option<Stepper>,
    /// The rows of a surface each point blends (`None`: outside the grid).
    rows: Vec<Option<RowBlend>>,
    /// Per point of a surface, the cell it was last sampled in at a step
    /// end and its blended cubic ([`SurfaceGrid::blend_cubic`]): a point
    /// crosses a cell in several steps (a 2 mm cell in 13 steps of 0.15
    /// mm), and the cubic is the same numbers whenever it is formed.
    cells: SurfaceCells,
}

/// The points' cells on a surface, one array per field so that the
/// points' fractions and cubics go through the lanes together.
#[derive(Debug, Clone)]
struct SurfaceCells {
    /// The cell's first column `m` (`usize::MAX`: none yet).
    m: Vec<usize>,
    /// The cell's start `L` in columns along the road, unwrapped (`m`
    /// plus whole loops), where the fraction across the cell is `u - L`
    /// (`u`: the point's position in columns); NaN where that is not
    /// known to be exact (before a point's first cell; on a looped grid,
    /// behind its origin or where the fraction was clamped): such a point
    /// takes its cell from [`SurfaceGrid::cell`].
    lo: Vec<f64>,
    /// The cell's cubic in powers of that fraction, by power.
    c: [Vec<f64>; 4],
    /// Scratch: the points' fractions in their cells at this sample.
    frac: Vec<f64>,
}

impl SurfaceCells {
    fn new(p: usize) -> Self {
        SurfaceCells {
            m: vec![usize::MAX; p],
            lo: vec![f64::NAN; p],
            c: std::array::from_fn(|_| vec![0.0; p]),
            frac: vec![0.0; p],
        }
    }
}

/// `(sin, cos)` of `κ_h s_n` at the step ends `s_n = s_0 + n ds` of a
/// harmonic road, advanced by angle addition instead of a `sin_cos` per
/// step (it was 8 % of the paper preset's step). Recomputed directly every
/// [`STEPPER_ANCHOR_EVERY`] steps, after any other sample pattern, and when
/// `ds` changes: the rotations' round-off stays below ~1e-14 of the
/// amplitude.
#[derive(Debug, Clone)]
struct Stepper {
    /// Step index of `cur`.
    n: u64,
    ds_m: f64,
    /// Rotations by `κ_h ds` per harmonic.
    rot: Vec<(f64, f64)>,
    /// `(sin, cos)` of `κ_h s_n` per harmonic.
    cur: Vec<(f64, f64)>,
    since_anchor: u32,
}

/// Steps between direct evaluations of a `Stepper`.
pub const STEPPER_ANCHOR_EVERY: u32 = 32;

impl PointsRoad {
    /// The road under points at `x_m` along and `y_m` across (empty: all on
    /// the centreline; only surfaces depend on `y`).
    /// The profile is shared with the problem it came from (a measured
    /// road may hold millions of rows).
    pub fn new(profile: impl Into<Arc<RoadProfile>>, x_m: &[f64], y_m: &[f64]) -> Self {
        let profile: Arc<RoadProfile> = profile.into();
        let phase = match &*profile {
            RoadProfile::Harmonics(h) => h
                .iter()
                .flat_map(|c| {
                    x_m.iter()
                        .map(move |&x| (TAU / c.wavelength_m * x + c.phase_rad).sin_cos())
                })
                .collect(),
            RoadProfile::Measured { .. }
            | RoadProfile::Gridded { .. }
            | RoadProfile::Surface(_) => Vec::new(),
        };
        let rows = match &*profile {
            RoadProfile::Surface(g) => (0..x_m.len())
                .map(|i| g.rows_at(y_m.get(i).copied().unwrap_or(0.0)))
                .collect(),
            _ => Vec::new(),
        };
        let cells = SurfaceCells::new(rows.len());
        PointsRoad {
            profile,
            x_m: x_m.to_vec(),
            phase,
            stepper: None,
            rows,
            cells,
        }
    }

    /// As [`PointsRoad::sample_all`] at `s_m`, the end of step `n` of
    /// consecutive steps of `ds_m` (m rolled per step): on a harmonic road
    /// from the previous step's angles rotated by `κ ds` (see `Stepper`);
    /// other roads are sampled directly.
    pub fn sample_step(
        &mut self,
        n: u64,
        s_m: f64,
        ds_m: f64,
        z: &mut [f64],
        dz: &mut [f64],
    ) -> Result<(), (usize, OutOfRange)> {
        let h = match &*self.profile {
            RoadProfile::Harmonics(h) => h,
            RoadProfile::Surface(g) => {
                return Self::sample_surface_cached(
                    g,
                    &self.x_m,
                    &self.rows,
                    &mut self.cells,
                    s_m,
                    z,
                    dz,
                );
            }
            _ => return self.sample_all(s_m, false, z, dz),
        };
        let follows = self.stepper.as_ref().is_some_and(|st| {
            st.n + 1 == n && st.ds_m == ds_m && st.since_anchor < STEPPER_ANCHOR_EVERY
        });
        // the same step end again (a step retried by the event loop): the
        // same angles, so the same samples
        let again = self
            .stepper
            .as_ref()
            .is_some_and(|st| st.n == n && st.ds_m == ds_m && st.cur.len() == h.len());
        match &mut self.stepper {
            Some(_) if again => {}
            Some(st) if follows => {
                for (c, r) in st.cur.iter_mut().zip(&st.rot) {
                    // sin(a + b), cos(a + b)
                    *c = rotated(*c, *r);
                }
                st.n = n;
                st.since_anchor += 1;
            }
            _ => {
                let kappa = |c: &Harmonic| TAU / c.wavelength_m;
                let same_ds = self.stepper.as_ref().is_some_and(|st| st.ds_m == ds_m);
                let st = self.stepper.get_or_insert_with(|| Stepper {
                    n,
                    ds_m,
                    rot: Vec::with_capacity(h.len()),
                    cur: Vec::with_capacity(h.len()),
                    since_anchor: 0,
                });
                if !same_ds || st.rot.len() != h.len() {
                    st.rot.clear();
                    st.rot.extend(h.iter().map(|c| (kappa(c) * ds_m).sin_cos()));
                }
                st.cur.clear();
                st.cur.extend(h.iter().map(|c| (kappa(c) * s_m).sin_cos()));
                (st.n, st.ds_m, st.since_anchor) = (n, ds_m, 0);
            }
        }
        let p = self.x_m.len();
        if h.is_empty() {
            z[..p].fill(0.0);
            dz[..p].fill(0.0);
        }
        if let Some(st) = &self.stepper {
            for (k, (c, &sc)) in h.iter().zip(&st.cur).enumerate() {
                let phase_k = &self.phase[k * p..(k + 1) * p];
                Self::add_harmonic(c, phase_k, sc, z, dz, k == 0);
            }
        }
        Ok(())
    }

    /// The common step end, fused: a single-harmonic road (a sine) sampled
    /// at the end of step `n` right after step `n - 1` (`Stepper` rotation),
    /// written as the road seen by the points past the ramp,
    /// `re_i = z_i - h_i` and `rde_i = V z'_i` (method §4). The same operations
    /// as [`PointsRoad::sample_step`] followed by the offset: bit-identical.
    /// `false` (nothing changed) where it does not apply.
    #[inline]
    pub fn step_end_offset(
        &mut self,
        n: u64,
        ds_m: f64,
        h_m: &[f64],
        vel_mps: f64,
        re: &mut [f64],
        rde: &mut [f64],
    ) -> bool {
        let (RoadProfile::Harmonics(hs), Some(st)) = (&*self.profile, &mut self.stepper) else {
            return false;
        };
        let [c] = hs.as_slice() else {
            return false;
        };
        if st.n + 1 != n
            || st.ds_m != ds_m
            || st.since_anchor >= STEPPER_ANCHOR_EVERY
            || st.cur.len() != 1
            || st.rot.len() != 1
        {
            return false;
        }
        let (cur, r) = (st.cur[0], st.rot[0]);
        let (sn, cs) = rotated(cur, r);
        st.cur[0] = (sn, cs);
        st.n = n;
        st.since_anchor += 1;
        let p = self.x_m.len();
        let (phase, h_m, re, rde) = (&self.phase[..p], &h_m[..p], &mut re[..p], &mut rde[..p]);
        let at = |i: usize| {
            let (zi, dzi) = height_slope(c, phase[i], (sn, cs));
            (zi - h_m[i], dzi * vel_mps)
        };
        // (up to eight points: unrolled loops)
        match p {
            1 => fill::<1>(re, rde, at),
            2 => fill::<2>(re, rde, at),
            3 => fill::<3>(re, rde, at),
            4 => fill::<4>(re, rde, at),
            5 => fill::<5>(re, rde, at),
            6 => fill::<6>(re, rde, at),
            7 => fill::<7>(re, rde, at),
            8 => fill::<8>(re, rde, at),
            _ => {
                for i in 0..p {
                    (re[i], rde[i]) = at(i);
                }
            }
        }
        true
    }

    /// Harmonic `c`'s height and slope at the points (phases `phase_k`,
    /// `(sin, cos)` of `κ s` in `at_s`, angle addition) set into `z`, `dz`
    /// (`set`) or added to them.
    #[inline]
    fn add_harmonic(
        c: &Harmonic,
        phase_k: &[(f64, f64)],
        (sn, cs): (f64, f64),
        z: &mut [f64],
        dz: &mut [f64],
        set: bool,
    ) {
        let p = phase_k.len();
        let (z, dz) = (&mut z[..p], &mut dz[..p]);
        for i in 0..p {
            let (zi, dzi) = height_slope(c, phase_k[i], (sn, cs));
            if set {
                (z[i], dz[i]) = (zi, dzi);
            } else {
                z[i] += zi;
                dz[i] += dzi;
            }
        }
    }

    /// Whether the profile has breakpoints (a measured profile's kinks).
    #[inline]
    pub fn has_kinks(&self) -> bool {
        matches!(*self.profile, RoadProfile::Measured { .. })
    }

    /// The first breakpoint of a measured profile that point `i` meets
    /// strictly inside `(s0, s1)` (as a rolled distance, m); `None` for
    /// smooth roads. Breakpoints within `1e-9 (s1 - s0)` of either end are
    /// ignored.
    pub fn next_kink(&self, i: usize, s0: f64, s1: f64) -> Option<f64> {
        let RoadProfile::Measured { x_m, looped, .. } = &*self.profile else {
            return None;
        };
        let eps = 1e-9 * (s1 - s0);
        let (x0, x1) = (x_m[0], x_m[x_m.len() - 1]);
        let xa = self.x_m[i] + s0;
        let xa = if *looped {
            x0 + (xa - x0).rem_euclid(x1 - x0)
        } else {
            xa
        };
        let k = x_m.partition_point(|&x| x <= xa + eps);
        let xk = *x_m.get(k)?;
        let sk = s0 + (xk - xa);
        (sk < s1 - eps).then_some(sk)
    }

    /// Whether point `i` sits on a breakpoint at rolled distance `s` (within `eps` m).
    pub fn at_kink(&self, i: usize, s: f64, eps: f64) -> bool {
        self.next_kink(i, s - eps, s + eps).is_some()
    }

    /// `z_i`, `dz/dx_i` at `x_i + s_m` (slopes after or before a
    /// breakpoint, see [`RoadProfile::sample_side`]); on a measured profile's edge, the
    /// point index and the range error.
    #[inline]
    pub fn sample_all(
        &self,
        s_m: f64,
        after: bool,
        z: &mut [f64],
        dz: &mut [f64],
    ) -> Result<(), (usize, OutOfRange)> {
        match &*self.profile {
            RoadProfile::Harmonics(h) => {
                // one sin_cos per harmonic
                let p = self.x_m.len();
                if h.is_empty() {
                    z[..p].fill(0.0);
                    dz[..p].fill(0.0);
                }
                for (k, c) in h.iter().enumerate() {
                    let sc = (TAU / c.wavelength_m * s_m).sin_cos();
                    let phase_k = &self.phase[k * p..(k + 1) * p];
                    Self::add_harmonic(c, phase_k, sc, z, dz, k == 0);
                }
                Ok(())
            }
            RoadProfile::Surface(g) => {
                for (i, &x) in self.x_m.iter().enumerate() {
                    let xs = x + s_m;
                    let Some(rows) = self.rows[i] else {
                        return Err((i, Self::off_the_grid(g, xs)));
                    };
                    (z[i], dz[i]) = g.sample_blend(rows, xs).map_err(|e| (i, e))?;
                }
                Ok(())
            }
            RoadProfile::Measured { .. } | RoadProfile::Gridded { .. } => {
                for (i, &x) in self.x_m.iter().enumerate() {
                    (z[i], dz[i]) = self
                        .profile
                        .sample_side(x + s_m, after)
                        .map_err(|e| (i, e))?;
                }
                Ok(())
            }
        }
    }

    /// [`PointsRoad::sample_all`] on a surface through the points' cached
    /// cells: the fraction `u - m` of every point in its cell, then the
    /// cell and its cubic again only where that fraction left `[0, 1)`,
    /// then the cubics at the fractions. Where a point stays in its cell,
    /// `u - m` is exact and is the fraction [`SurfaceGrid::cell`] gives
    /// (which takes the same `u` and subtracts the same `m`): the same
    /// numbers as sampling each point directly, bit for bit, with the
    /// first and last loops in lanes.
    #[inline]
    fn sample_surface_cached(
        g: &SurfaceGrid,
        x_m: &[f64],
        rows: &[Option<RowBlend>],
        cells: &mut SurfaceCells,
        s_m: f64,
        z: &mut [f64],
        dz: &mut [f64],
    ) -> Result<(), (usize, OutOfRange)> {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx") {
                #[target_feature(enable = "avx")]
                fn wide(
                    g: &SurfaceGrid,
                    x_m: &[f64],
                    rows: &[Option<RowBlend>],
                    cells: &mut SurfaceCells,
                    s_m: f64,
                    z: &mut [f64],
                    dz: &mut [f64],
                ) -> Result<(), (usize, OutOfRange)> {
                    PointsRoad::surface_cells_body(g, x_m, rows, cells, s_m, z, dz)
                }
                // SAFETY: the CPU supports AVX (checked just above).
                return unsafe { wide(g, x_m, rows, cells, s_m, z, dz) };
            }
        }
        Self::surface_cells_body(g, x_m, rows, cells, s_m, z, dz)
    }

    /// [`PointsRoad::sample_surface_cached`]'s work, built once for the
    /// baseline CPU and once with AVX (no FMA: the same values either way).
    #[inline(always)]
    fn surface_cells_body(
        g: &SurfaceGrid,
        x_m: &[f64],
        rows: &[Option<RowBlend>],
        cells: &mut SurfaceCells,
        s_m: f64,
        z: &mut [f64],
        dz: &mut [f64],
    ) -> Result<(), (usize, OutOfRange)> {
        let p = x_m.len();
        let (x0, dx) = (g.x0_m, g.dx_m);
        let (rows, cm) = (&rows[..p], &mut cells.m[..p]);
        let (lo, frac) = (&mut cells.lo[..p], &mut cells.frac[..p]);
        let [c0, c1, c2, c3] = &mut cells.c;
        let (c0, c1, c2, c3) = (&mut c0[..p], &mut c1[..p], &mut c2[..p], &mut c3[..p]);
        let (z, dz) = (&mut z[..p], &mut dz[..p]);
        // the fractions in the cached cells (the operations of
        // `SurfaceGrid::cell`: `u = (x + s - x0) / dx`, then `u - m`), and
        // how many left their cell (or have none: NaN)
        let mut moved = 0usize;
        for i in 0..p {
            let f = (x_m[i] + s_m - x0) / dx - lo[i];
            frac[i] = f;
            moved += usize::from(!(0.0..1.0).contains(&f));
        }
        if moved > 0 {
            for i in 0..p {
                let f = frac[i];
                if (0.0..1.0).contains(&f) {
                    continue;
                }
                let xs = x_m[i] + s_m;
                let (m, m1, fr) = match g.cell(xs) {
                    Ok(cell) => cell,
                    // (off the grid across is said first, as `sample_all` does)
                    Err(e) => {
                        return Err((i, rows[i].map_or_else(|| Self::off_the_grid(g, xs), |_| e)));
                    }
                };
                if cm[i] != m {
                    // (a point off the grid across never has a cell)
                    let Some(rows) = rows[i] else {
                        return Err((i, Self::off_the_grid(g, xs)));
                    };
                    let c = g.blend_cubic(rows, m, m1);
                    (c0[i], c1[i], c2[i], c3[i]) = (c[0], c[1], c[2], c[3]);
                    cm[i] = m;
                }
                lo[i] = Self::cell_start(g, xs, m, fr);
                frac[i] = fr;
            }
        }
        // the cubics at the fractions (`SurfaceGrid::cubic_at`)
        for i in 0..p {
            let s = frac[i];
            z[i] = ((c3[i] * s + c2[i]) * s + c1[i]) * s + c0[i];
            dz[i] = ((3.0 * c3[i] * s + 2.0 * c2[i]) * s + c1[i]) / dx;
        }
        Ok(())
    }

    /// The start `L` of a point's cell `m` along the road, in columns and
    /// unwrapped ([`SurfaceCells::lo`]), from the point at `xs_m` and its
    /// fraction `frac` there. Where `u` is past the origin and inside the
    /// cell, `u - L` for a later `u` in the same cell is exact, and so is
    /// the fraction [`SurfaceGrid::cell`] gives (`u` less whole loops,
    /// exactly, then less `m`): the same number. On a looped grid NaN (no
    /// shortcut) behind the origin and where the fraction was clamped; on
    /// one that is not looped `m` itself (`u - m` outside `[0, 1)` sends
    /// the point to [`SurfaceGrid::cell`]).
    #[inline]
    fn cell_start(g: &SurfaceGrid, xs_m: f64, m: usize, frac: f64) -> f64 {
        if !g.looped {
            // (inside the cell `u - m` is the fraction, unclamped)
            return m as f64;
        }
        let u = (xs_m - g.x0_m) / g.dx_m;
        let start = u - frac;
        let whole = (0.0..4_503_599_627_370_496.0).contains(&start) && start as i64 as f64 == start;
        if whole && u - start == frac {
            start
        } else {
            f64::NAN
        }
    }

    /// The error of a point outside a surface's grid across.
    #[cold]
    fn off_the_grid(g: &SurfaceGrid, xs: f64) -> OutOfRange {
        let (lo, hi) = g.y_range_m().unwrap_or((0.0, 0.0));
        OutOfRange {
            x_m: xs,
            min_m: lo,
            max_m: hi,
        }
    }
}

/// `(re_i, rde_i) = at(i)` for the `N` points (`N` the slices' length).
#[inline(always)]
fn fill<const N: usize>(re: &mut [f64], rde: &mut [f64], at: impl Fn(usize) -> (f64, f64)) {
    if let (Ok(re), Ok(rde)) = (
        <&mut [f64; N]>::try_from(re),
        <&mut [f64; N]>::try_from(rde),
    ) {
        for i in 0..N {
            (re[i], rde[i]) = at(i);
        }
    }
}

/// `(sin, cos)` of `a + b` from those of `a` (`c`) and `b` (`r`).
#[inline]
fn rotated(c: (f64, f64), r: (f64, f64)) -> (f64, f64) {
    (c.0 * r.1 + c.1 * r.0, c.1 * r.1 - c.0 * r.0)
}

/// Height `a sin(θ0 + κ s)` (m) and slope `a κ cos(θ0 + κ s)` of harmonic
/// `c` at a point of phase `(sin θ0, cos θ0)`, with `(sin κs, cos κs)`.
#[inline]
fn height_slope(c: &Harmonic, (s0, c0): (f64, f64), (sn, cs): (f64, f64)) -> (f64, f64) {
    let (a, ak) = (c.amplitude_m, c.amplitude_m * TAU / c.wavelength_m);
    (a * (s0 * cs + c0 * sn), ak * (c0 * cs - s0 * sn))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stepped_harmonics_equal_direct_sampling() {
        let h = vec![
            Harmonic {
                amplitude_m: 1e-3,
                wavelength_m: 0.1,
                phase_rad: 0.3,
            },
            Harmonic {
                amplitude_m: 2e-4,
                wavelength_m: 0.037,
                phase_rad: -1.0,
            },
        ];
        let xs = [-0.05, -0.025, 0.0, 0.025, 0.05];
        let mut road = PointsRoad::new(RoadProfile::Harmonics(h), &xs, &[]);
        let (mut z1, mut d1, mut z2, mut d2) = ([0.0; 5], [0.0; 5], [0.0; 5], [0.0; 5]);
        let (dt, mut vel, mut offset) = (1e-5, 10.0, 0.0);
        let (mut worst_z, mut worst_dz, mut rotated) = (0.0f64, 0.0f64, 0);
        for n in 1..20_000u64 {
            if n == 7_000 {
                // a speed change keeps the distance continuous
                offset += (vel - 3.0) * (n - 1) as f64 * dt;
                vel = 3.0;
            }
            let s = vel * n as f64 * dt + offset;
            // skipped samples (steps with events) re-anchor
            if n % 997 == 0 {
                continue;
            }
            road.sample_step(n, s, vel * dt, &mut z1, &mut d1).unwrap();
            rotated += road.stepper.as_ref().unwrap().since_anchor.min(1);
            road.sample_all(s, false, &mut z2, &mut d2).unwrap();
            for i in 0..5 {
                worst_z = worst_z.max((z1[i] - z2[i]).abs());
                worst_dz = worst_dz.max((d1[i] - d2[i]).abs());
            }
        }
        // amplitudes 1.2e-3 m, slopes ~0.1: round-off level, and mostly rotated
        assert!(worst_z < 1e-15, "height differs by {worst_z:e} m");
        assert!(worst_dz < 1e-13, "slope differs by {worst_dz:e}");
        assert!(rotated > 18_000, "only {rotated} samples rotated");
    }

    #[test]
    fn a_repeated_step_end_gives_the_same_samples_and_sequence() {
        let h = vec![Harmonic {
            amplitude_m: 1e-3,
            wavelength_m: 0.1,
            phase_rad: 0.3,
        }];
        let xs = [-0.05, 0.0, 0.05];
        let (dt, vel) = (1e-5, 10.0);
        let mut once = PointsRoad::new(RoadProfile::Harmonics(h.clone()), &xs, &[]);
        let mut twice = PointsRoad::new(RoadProfile::Harmonics(h), &xs, &[]);
        let (mut za, mut da, mut zb, mut db) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
        for n in 1..200u64 {
            let s = vel * n as f64 * dt;
            once.sample_step(n, s, vel * dt, &mut za, &mut da).unwrap();
            // the event loop retrying a step samples its end again
            if n % 3 == 0 {
                twice.sample_step(n, s, vel * dt, &mut zb, &mut db).unwrap();
                zb.fill(f64::NAN);
            }
            twice.sample_step(n, s, vel * dt, &mut zb, &mut db).unwrap();
            let bits = |x: &[f64; 3]| x.map(f64::to_bits);
            assert_eq!(bits(&za), bits(&zb), "height at step {n}");
            assert_eq!(bits(&da), bits(&db), "slope at step {n}");
            // and the repeats did not re-anchor (a direct sin_cos would
            // differ from the rotated angles in the last bits)
            let since = |r: &PointsRoad| r.stepper.as_ref().map(|st| st.since_anchor);
            assert_eq!(since(&once), since(&twice), "anchor count at step {n}");
        }
    }

    /// A surface sampled at step ends through the per-point cell cubics
    /// equals the direct sampling bit for bit: rolling forward by steps
    /// shorter and longer than a cell, backwards, across a looped grid's
    /// wrap (many times) and from behind its origin, along a grid that is
    /// not looped up to its last column, and on points that blend two
    /// rows, one row or sit on a row.
    #[test]
    fn cached_surface_cells_equal_direct_sampling() {
        use super::super::surface::SurfaceGrid;
        use rand_chacha::ChaCha8Rng;
        use rand_chacha::rand_core::{RngCore, SeedableRng};
        for (looped, nx) in [(true, 37), (false, 900)] {
            let (ny, dx, dy) = (5, 0.002, 0.01);
            let mut rng = ChaCha8Rng::seed_from_u64(3);
            let z: Vec<f64> = (0..nx * ny)
                .map(|_| (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2e-3)
                .collect();
            let g = SurfaceGrid::from_heights((0.0, dx, nx), (0.0, dy, ny), looped, z);
            // (on the grid that is not looped, the points start inside it)
            let shift = if looped { 0.0 } else { 0.031 };
            let xs = [-0.03, -0.011, 0.0, 0.0013, 0.02, 0.05].map(|x| x + shift);
            let ys = [0.0, 0.004, 0.01, 0.0375, 0.04, 0.017];
            let profile = Arc::new(RoadProfile::Surface(Arc::new(g)));
            let mut cached = PointsRoad::new(profile.clone(), &xs, &ys);
            let direct = PointsRoad::new(profile, &xs, &ys);
            let (mut z1, mut d1, mut z2, mut d2) = ([0.0; 6], [0.0; 6], [0.0; 6], [0.0; 6]);
            let mut s = 0.0;
            // (the grid that is not looped is 1.798 m long: its last
            // column is reached by the end)
            let (steps, every) = if looped {
                (3_000u64, 500)
            } else {
                (2_480, 1_000)
            };
            for n in 1..steps {
                s += match n % every {
                    0 => -0.013,
                    1..=99 => 1.5e-4,
                    100..=199 => {
                        if looped {
                            2.7e-3
                        } else {
                            5e-3
                        }
                    }
                    _ => 4e-5,
                };
                let last = !looped && n + 1 == steps;
                if last {
                    // exactly onto the last column: the fraction 1 of the last cell
                    s = 1.798 - xs[5];
                }
                cached.sample_step(n, s, 1.5e-4, &mut z1, &mut d1).unwrap();
                direct.sample_all(s, false, &mut z2, &mut d2).unwrap();
                for i in 0..6 {
                    assert_eq!(
                        z1[i].to_bits(),
                        z2[i].to_bits(),
                        "height, point {i}, step {n}, looped {looped}"
                    );
                    assert_eq!(
                        d1[i].to_bits(),
                        d2[i].to_bits(),
                        "slope, point {i}, step {n}, looped {looped}"
                    );
                }
            }
            if !looped {
                // past the end: refused, as when sampled directly
                let past = 1.8 - xs[5] + 0.01;
                assert!(
                    cached
                        .sample_step(steps, past, 1.5e-4, &mut z1, &mut d1)
                        .is_err()
                );
                assert!(direct.sample_all(past, false, &mut z2, &mut d2).is_err());
            }
        }
    }
}
