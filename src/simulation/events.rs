//! Events inside the step (method §4, "where we go beyond the paper"): the
//! `Located` scheme's step, inelastic multi-point impacts, and the Hermite
//! location of landings. Compliant contact (`compliant.rs`) takes the same
//! step: its landings and releases are located alike, a landing adds the
//! point to the springs in compression with no impulse.

use super::{GA, GB, Simulation, Table};
use crate::error::SolverError;

impl Simulation {
    /// A step with events located inside it (method §4, "Events inside the step").
    /// `after_steady`: [`Simulation::steady_step`] was tried first from the
    /// same state and handed the step over; its free prediction over the
    /// whole step (`free`, road at the step end; the free end values in
    /// `uh`, `vh`, or swapped into `ue`, `ve` when no point was on the road)
    /// is this loop's first prediction, which is then not repeated.
    ///
    /// With tread springs (compliant contact) the step is the same but for
    /// what an event does: a landing adds the point to the active set (a
    /// massless spring takes no impulse; its force starts from zero), a
    /// free point left compressed at the step start joins it there, the
    /// Gauss-point solves are the compliant ones, and a cascade of events
    /// ends with the compliant step-end rule. Breakpoints of a measured
    /// road do not split its steps (no impulse at a kink of the road).
    pub(super) fn located_step(
        &mut self,
        t_start: f64,
        after_steady: bool,
    ) -> Result<(u32, u32), SolverError> {
        let dt = self.dt_s;
        let mut t = t_start;
        let mut remaining = dt;
        let (mut events, mut solves) = (0u32, 0u32);
        let compliant = !self.tread_k_n_m.is_empty();
        // the active set carries over: points in contact at the step start
        let p = self.p;
        let (contact, u, r) = (&self.contact[..p], &self.u[..p], &self.r[..p]);
        self.active.clear();
        // a point left below the road by the last step lands now (a spring
        // left compressed is in contact from now)
        let mut deepest: Option<(usize, f64)> = None;
        for i in 0..p {
            if contact[i] {
                self.active.push(i);
            } else {
                let g = u[i] - r[i];
                if g < -self.pen_tol_m {
                    if compliant {
                        self.active.push(i);
                        events += 1;
                    } else if deepest.is_none_or(|(_, d)| g < d) {
                        deepest = Some((i, g));
                    }
                }
            }
        }
        // the steady attempt's prediction holds while nothing changed the
        // state: no landing at the step start (the first sub-step is then the
        // whole step: the steady path runs only on roads without breakpoints
        // under active points, and a step without them has none to stop at)
        let mut predicted = after_steady && deepest.is_none();
        if predicted && self.active.is_empty() {
            // (the steady attempt without active points swapped the free end
            // values into `ue`, `ve`)
            std::mem::swap(&mut self.ue, &mut self.uh);
            std::mem::swap(&mut self.ve, &mut self.vh);
        }
        if let Some((i, _)) = deepest {
            solves += self.impact(t, i)?;
            events += 1;
        }
        let mut sel;
        while remaining > 1e-12 * dt {
            if events > self.max_events {
                // Zeno-like cascade: finish the step with the paper's rule
                // (or the compliant step-end rule).
                self.prepare_sub(remaining);
                solves += if compliant {
                    self.compliant_substep(t, remaining, Table::Sub)?
                } else {
                    self.paper_substep(t, remaining, Table::Sub)?
                };
                break;
            }
            // An active point on a breakpoint where the road turns upward
            // is hit by it: an inelastic impulse (a downward turn releases
            // it in the trial below).
            if !compliant && let Some(i) = self.kinked_up(t)? {
                solves += self.impact(t, i)?;
                events += 1;
            }
            // The sub-step ends at the step end or where an active point meets
            // a kink of the road (a measured profile's breakpoint: the road
            // velocity jumps there, which no smooth force can follow).
            let span = if compliant {
                remaining
            } else {
                self.kink_limit(t, remaining)
            };
            if span == dt {
                sel = Table::Full;
            } else {
                if self.sub.tau_s != span {
                    self.prepare_sub(span);
                }
                sel = Table::Sub;
            }
            if predicted && sel == Table::Full && t == t_start {
                predicted = false;
            } else {
                predicted = false;
                self.predict(t, span, sel)?;
            }
            self.solve_contact(t + span, sel)?;
            solves += !self.active.is_empty() as u32;
            // releases: the linear force ends negative (release where it crosses
            // zero) or is negative on average from the start (release now)
            let mut release: Option<(usize, f64, f64)> = None; // (k, θ, end value)
            for (k, &j) in self.active.iter().enumerate() {
                let (q1, q2) = (self.q1[j], self.q2[j]);
                let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
                if qe < 0.0 || qs + qe < 0.0 {
                    // (a tread spring the sub-step does not resolve: released
                    // only if it pulls on average, and at once)
                    let unresolved = compliant && self.spring_unresolved(j, span);
                    if unresolved && qs + qe >= 0.0 {
                        continue;
                    }
                    let th = if qs > 0.0 && !unresolved {
                        span * qs / (qs - qe)
                    } else {
                        0.0
                    };
                    let better = match release {
                        None => true,
                        Some((_, t2, e2)) => th < t2 || (th == t2 && qe < e2),
                    };
                    if better {
                        release = Some((k, th, qe));
                    }
                }
            }
            if let Some((k, th, _)) = release
                && th <= 0.0
            {
                let j = self.active.remove(k);
                self.released[j] = true;
                events += 1;
                continue;
            }
            // impacts: first root of the Hermite cubic of the gap of a free point
            let mut impact: Option<(usize, f64)> = None;
            let p = self.p;
            let (u, v, r, rd) = (&self.u[..p], &self.v[..p], &self.r[..p], &self.rd[..p]);
            let (ue, ve, re, rde) = (&self.ue[..p], &self.ve[..p], &self.re[..p], &self.rde[..p]);
            let released = &self.released[..p];
            for i in 0..p {
                // (a compressed spring is not on the road: its gap is far
                // from the cheap rejection, so active points are skipped first)
                if compliant && self.active.contains(&i) {
                    continue;
                }
                let (g0, d0) = (u[i] - r[i], v[i] - rd[i]);
                let (g1, d1) = (ue[i] - re[i], ve[i] - rde[i]);
                // a point released in this step lands again only after it rose
                // clear of the road (no cycling at the release instant)
                let rise = released[i];
                // (active points are skipped only past the cheap rejection,
                // which most points of most steps take)
                if let Some(y) = first_crossing(g0, d0 * span, g1, d1 * span, self.pen_tol_m, rise)
                    && !self.active.contains(&i)
                {
                    let th = y * span;
                    if impact.is_none_or(|(_, t2)| th < t2) {
                        impact = Some((i, th));
                    }
                }
            }
            let th_rel = release.map_or(f64::INFINITY, |r| r.1);
            let th_imp = impact.map_or(f64::INFINITY, |r| r.1);
            let th = th_rel.min(th_imp);
            if !th.is_finite() {
                self.commit(span, sel);
                t += span;
                remaining -= span;
                continue;
            }
            // advance to the event
            if th >= span * (1.0 - 1e-12) {
                self.commit(span, sel);
                t += span;
                remaining -= span;
            } else if th > 1e-9 * span {
                // (an event within 1e-9 of the sub-step start happens at its start:
                // no degenerate sub-step is solved)
                // Up to a release: the trial forces restricted to [0, θ]
                // (they stay >= 0 up to the crossing; active points stay on the
                // road to O(θ⁴)). Up to an impact: re-solved so that the active
                // points are exactly on the road at the impact. A point whose
                // force dips below zero at the start and would pull on average
                // over [0, θ] is released now instead.
                let f = th / span;
                let pulling = self.active.iter().position(|&j| {
                    let (qs, qe) = (
                        GA * self.q1[j] - GB * self.q2[j],
                        -GB * self.q1[j] + GA * self.q2[j],
                    );
                    let mean = qs + 0.5 * (qe - qs) * f;
                    mean < -1e-9 * (qs.abs() + qe.abs())
                });
                if let Some(k) = pulling {
                    let j = self.active.remove(k);
                    self.released[j] = true;
                    events += 1;
                    continue;
                }
                let (ya, yb) = (0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt());
                for &j in &self.active {
                    let (q1, q2) = (self.q1[j], self.q2[j]);
                    let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
                    self.rq1[j] = qs + (qe - qs) * f * ya;
                    self.rq2[j] = qs + (qe - qs) * f * yb;
                }
                self.prepare_sub(th);
                sel = Table::Sub;
                self.predict(t, th, sel)?;
                let mut restricted = th_imp > th_rel;
                if !restricted {
                    self.solve_contact(t + th, sel)?;
                    solves += !self.active.is_empty() as u32;
                    // a re-solve that would pull somewhere keeps the trial's forces
                    restricted = self.active.iter().any(|&j| {
                        let (q1, q2) = (self.q1[j], self.q2[j]);
                        q1 + q2 < -1e-9 * (q1.abs() + q2.abs())
                    });
                }
                if restricted {
                    for &j in &self.active {
                        (self.q1[j], self.q2[j]) = (self.rq1[j], self.rq2[j]);
                    }
                    self.end_values_sub();
                }
                self.commit(th, sel);
                t += th;
                remaining -= th;
            }
            events += 1;
            if th_imp <= th_rel {
                let (i, _) = impact.unwrap_or((0, 0.0));
                if !compliant {
                    solves += self.impact(t, i)?;
                } else if !self.active.contains(&i) {
                    // a spring lands with zero force: no impulse
                    self.active.push(i);
                }
            } else if let Some((k, _, _)) = release {
                let j = self.active.remove(k);
                self.released[j] = true;
            }
        }
        Ok((events, solves))
    }

    /// The Gauss-point solve of `active` over `sel` for the contact law:
    /// rigid ([`Simulation::solve_active`]) or tread springs
    /// ([`Simulation::solve_compliant`]).
    #[inline]
    fn solve_contact(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        if self.tread_k_n_m.is_empty() {
            self.solve_active(t_end, sel)
        } else {
            self.solve_compliant(t_end, sel)
        }
    }

    /// At a breakpoint of a measured road under an active point: the road
    /// rates become those after it, and the point whose road now rises
    /// faster than it moves (the road turns up into it) is returned.
    fn kinked_up(&mut self, t: f64) -> Result<Option<usize>, SolverError> {
        let vel = self.scene.speed_mps;
        if vel <= 0.0 || !self.road.has_kinks() {
            return Ok(None);
        }
        let s = vel * t + self.x_offset_m;
        let eps = 1e-9 * vel * self.dt_s;
        let Some(&i) = self.active.iter().find(|&&i| self.road.at_kink(i, s, eps)) else {
            return Ok(None);
        };
        // from here on the road's rate is the one after the breakpoint
        self.road_at(t, true)?;
        self.r.copy_from_slice(&self.re);
        self.rd.copy_from_slice(&self.rde);
        let scale = self.rde.iter().fold(1e-6, |m: f64, x| m.max(x.abs()));
        let up = self
            .active
            .iter()
            .any(|&j| self.rde[j] > self.v[j] + 1e-9 * scale);
        Ok(up.then_some(i))
    }

    /// Length of the next sub-step from `t`: `remaining`, or less where an
    /// active point reaches a breakpoint of a measured road first.
    fn kink_limit(&self, t: f64, remaining: f64) -> f64 {
        let vel = self.scene.speed_mps;
        if vel <= 0.0 || self.active.is_empty() || !self.road.has_kinks() {
            return remaining;
        }
        let s0 = vel * t + self.x_offset_m;
        let s1 = s0 + vel * remaining;
        let mut span = remaining;
        for &i in &self.active {
            if let Some(sk) = self.road.next_kink(i, s0, s1) {
                span = span.min((sk - s0) / vel);
            }
        }
        span
    }

    /// Perfectly inelastic impact of point `i` at `t`: impulses on all points on
    /// the road together so that their velocities equal the road's; a point
    /// whose impulse would pull is thrown off (monotone, most negative first).
    fn impact(&mut self, t: f64, i: usize) -> Result<u32, SolverError> {
        self.road_at(t, true)?;
        self.r.copy_from_slice(&self.re);
        self.rd.copy_from_slice(&self.rde);
        if !self.active.contains(&i) {
            self.active.push(i);
        }
        let p = self.p;
        // With residual flexibility every point on the road meets it through
        // the dropped modes' static compliance `C`, which has no mass: an
        // inelastic landing takes no impulse. The velocity mismatch becomes
        // the force rate of the next sub-step (`v = v_kept + C q'`), whose
        // solve puts the points on the road in position and velocity at its
        // end. A kept-mode impulse instead treats the points as rigid: it
        // throws neighbours off whose force was holding them on the road
        // through `C q`; that deflection vanishes at once, they are below the
        // road again and land, and so on to the event limit in every step.
        // Only where `C` is singular on the points on the road (fewer
        // dropped modes than such points) is a rigid impact left.
        if !self.residual.is_empty()
            && super::residual::compliant_on(&self.residual, p, &self.active, &mut self.gss)
        {
            return Ok(0);
        }
        let mut solves = 0;
        while !self.active.is_empty() {
            let n = self.active.len();
            let act = &self.active;
            let jump = &self.jump;
            if let Err(s) = self.solver.factor(n, |r, c| jump[act[r] * p + act[c]]) {
                return Err(SolverError::SingularContactSystem {
                    t_s: t,
                    points: self.active.clone(),
                    pivot: s.pivot,
                });
            }
            for (k, &j) in act.iter().enumerate() {
                self.rhs[k] = self.rd[j] - self.v[j];
            }
            self.solver.solve(&mut self.rhs[..n]);
            solves += 1;
            // Velocity a pulling impulse stands for; below v_tol it is round-off
            // or the tail of a converged impact cascade, and the point stays on.
            let v_tol = 1e-9
                * act
                    .iter()
                    .map(|&j| self.rd[j].abs().max(self.v[j].abs()))
                    .fold(1e-6, f64::max);
            let worst = (0..n)
                .map(|k| (k, self.rhs[k] * self.jump[act[k] * p + act[k]]))
                .filter(|&(_, dv)| dv < -v_tol)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match worst {
                Some((k, _)) => {
                    // Thrown off with a positive relative velocity: it may land
                    // again later in this step (a located event). Only the landing
                    // point itself, if it cannot land, is kept off until the next step.
                    let j = self.active.remove(k);
                    if j == i {
                        self.released[j] = true;
                    }
                }
                None => break,
            }
        }
        let n = self.active.len();
        self.q1.fill(0.0);
        for k in 0..n {
            self.q1[self.active[k]] = self.rhs[k];
        }
        self.state.add_impulses(&self.basis, &self.active, &self.q1);
        for &j in &self.active {
            self.impulse[j] += self.q1[j];
            self.impact_impulse[j] += self.q1[j];
        }
        for a in 0..p {
            self.v[a] += self
                .active
                .iter()
                .map(|&j| self.jump[a * p + j] * self.q1[j])
                .sum::<f64>();
        }
        Ok(solves)
    }
}

/// First `y ∈ (0, 1]` where the cubic Hermite interpolant with values `g0`,
/// `g1` and scaled slopes `d0`, `d1` (slope × interval) goes below `-tol`;
/// returns the zero crossing before it. With
/// `require_rise`, only a crossing after the cubic rose above `+tol` counts.
#[inline]
pub fn first_crossing(
    g0: f64,
    d0: f64,
    g1: f64,
    d1: f64,
    tol: f64,
    require_rise: bool,
) -> Option<f64> {
    // A start slightly below the road (round-off, or the O(θ⁴) gap of a point
    // just thrown off) counts as on the road: falling, it lands at once;
    // rising, it lands where it comes back.
    // (`g0.max(0.0)` as a plain comparison: a NaN becomes 0 as with `max`)
    let g0 = if g0 > 0.0 { g0 } else { 0.0 };
    // cheap rejection (inlined: most free points of most steps): all of the
    // cubic is above -tol (|H10|, |H11| <= 4/27); past `g1 >= -tol` neither
    // value is a NaN, so the plain minimum is `f64::min`
    if g1 >= -tol
        && (d0 >= 0.0 && d1 <= 0.0
            || (if g0 < g1 { g0 } else { g1 }) - 0.25 * (d0.abs() + d1.abs()) >= -tol)
    {
        return None;
    }
    crossing_of_cubic(g0, d0, g1, d1, tol, require_rise)
}

/// [`first_crossing`] past its cheap rejection, `g0 >= 0`.
fn crossing_of_cubic(
    g0: f64,
    d0: f64,
    g1: f64,
    d1: f64,
    tol: f64,
    require_rise: bool,
) -> Option<f64> {
    let c = [
        g0,
        d0,
        -3.0 * g0 - 2.0 * d0 + 3.0 * g1 - d1,
        2.0 * g0 + d0 - 2.0 * g1 + d1,
    ];
    let p = |y: f64| ((c[3] * y + c[2]) * y + c[1]) * y + c[0];
    // breakpoints: critical points of the cubic in (0, 1), then 1
    let (qa, qb, qc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut bp = [1.0f64; 3];
    let mut nb = 0;
    if qa.abs() > 1e-300 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let qq = -0.5 * (qb + qb.signum() * sq);
            for y in [qq / qa, if qq != 0.0 { qc / qq } else { f64::NAN }] {
                if y > 0.0 && y < 1.0 {
                    bp[nb] = y;
                    nb += 1;
                }
            }
        }
    } else if qb.abs() > 1e-300 {
        let y = -qc / qb;
        if y > 0.0 && y < 1.0 {
            bp[nb] = y;
            nb += 1;
        }
    }
    bp[nb] = 1.0;
    let bps = &mut bp[..nb + 1];
    bps.sort_by(f64::total_cmp);
    let mut ya = 0.0;
    let mut risen = !require_rise || g0 > tol;
    for &yb in bps.iter() {
        let pb = p(yb);
        if risen && pb < -tol {
            // monotone decreasing on [ya, yb]: bisect for p = 0
            if p(ya) < 0.0 {
                return Some(ya);
            }
            let (mut lo, mut hi) = (ya, yb);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if p(mid) >= 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        risen |= pb > tol;
        ya = yb;
    }
    None
}
