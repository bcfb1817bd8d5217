//! `identify --data FILE.uff` of a file of FRFs: the frequency-domain fit
//! (method §6.5), its report, `--fit DIR` (modes.csv, fit.csv, fit.png),
//! `--diagram` and `-o` (the contact model, when a driving point allows
//! one and the fit is good or `--accept`ed).

use super::{IdentifyArgs, data_points, run_figures, sig6};
use crate::cli::CliResult;
use crate::cli::paths::{check_output_file, ensure_output_dir};
use std::fmt::Write as _;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::base::error::fmt_sig;
use tirecontact::fsio::write_atomic;
use tirecontact::identify::driving;
use tirecontact::identify::frequency::{
    FrfIdentification, FrfOptions, MAX_FIT_ERROR, MIN_TERM_TO_RESIDUAL, half_power_width_hz,
};
use tirecontact::model::lscf::FitOptions;
use tirecontact::output::figures::{Figure, Panel, Series, Style, render_png};
use tirecontact::output::stabilisation::{self, Method};
use tirecontact::readers::measured::frf::FrfRequest;
use tirecontact::scene::Tyre;

/// Whether `path` names a UFF file (`.uff`, `.unv`).
pub fn is_uff(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .is_some_and(|e| e == "uff" || e == "unv")
}

pub fn identify_frfs(args: &IdentifyArgs, data: &Path) -> CliResult {
    if let Some(path) = &args.output {
        check_output_file("-o", path, "RON")?;
    }
    if let Some(path) = &args.diagram {
        check_output_file("--diagram", path, "PNG")?;
    }
    if args.responses.is_some() {
        return Err(format!(
            "--responses: {} holds FRFs, fitted in the frequency domain: no impulse responses to write (use --fit DIR for data and fit)",
            data.display()
        )
        .into());
    }
    for (dir, flag) in [(&args.fit, "--fit"), (&args.figures, "--figures")] {
        if let Some(dir) = dir {
            ensure_output_dir(flag, dir)?;
        }
    }
    let mut fit = FitOptions::default();
    if let Some(n) = args.order {
        if !(1..=200).contains(&n) {
            return Err(format!("--order {n}: expected 1 to 200").into());
        }
        fit.order = Some(n);
        fit.max_order = fit.max_order.max(n);
    }
    let opts = FrfOptions {
        request: FrfRequest {
            band_hz: args.band_hz.as_ref().map(|b| (b[0], b[1])),
            nodes: args.nodes.clone(),
            flip: args.flip_direction.clone(),
        },
        fit,
    };
    if let Some((lo, hi)) = opts.request.band_hz
        && !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi)
    {
        return Err(format!("--band-hz {lo} {hi}: expected 0 <= LO < HI (Hz)").into());
    }
    let id = tirecontact::identify::frequency::identify_frfs(data, &opts)?;
    if let Some(p) = args.points
        && p != id.data.dofs.len()
    {
        return Err(format!(
            "--points {p}: {} has FRFs of {} ({}): expected --points {} or none",
            data.display(),
            tirecontact::output::count(id.data.dofs.len(), "degree of freedom"),
            dof_list(&id),
            id.data.dofs.len()
        )
        .into());
    }
    let name = data
        .file_stem()
        .map_or("data".into(), |s| s.to_string_lossy().into_owned());
    print!("{}", summary(&name, &id));
    if let Some(dir) = &args.fit {
        write_fit(dir, &name, &id)?;
    }
    if let Some(path) = &args.diagram {
        render_png(&diagram(&name, &id), path, 1200, 800)?;
        println!("wrote {}", path.display());
    }
    let see = match &args.fit {
        Some(d) => format!("see {} (data against fit)", d.join("fit.png").display()),
        None => "write the fit with --fit DIR to see data against fit".to_string(),
    };
    let contact = match &id.contact {
        Ok(c) => c,
        Err(e) => {
            println!("  no contact model: {e}");
            return match &args.output {
                Some(out) => Err(format!("-o {}: not written: {e}; {see}", out.display()).into()),
                None => Ok(()),
            };
        }
    };
    let poor = !id.is_good();
    if poor {
        println!(
            "  poor fit: complex error {:.4}, contact model error {:.4} (limit {MAX_FIT_ERROR}); {see}",
            id.complex.error, contact.error
        );
    }
    let mut scene = Scene::parse(
        tirecontact::DEFAULT_PRESET,
        tirecontact::DEFAULT_PRESET_NAME,
    )?;
    scene.name = format!("{name} (identified)");
    scene.description = format!(
        "Modes fitted in the frequency domain (LSCF, LSFD) to {} over {} to {} Hz: points {} placed 25 mm apart (set their positions).",
        data.display(),
        tirecontact::base::error::fmt_sig(id.data.band_hz.0, 6),
        tirecontact::base::error::fmt_sig(id.data.band_hz.1, 6),
        dof_list(&id)
    );
    scene.points = data_points(contact.dofs.len());
    scene.tyre = Tyre::Modal {
        modes: contact.modes.clone(),
    };
    scene.base_dir = None;
    if let Some(out) = &args.output {
        if poor && !args.accept {
            return Err(format!(
                "-o {}: not written: the fit is poor (complex error {:.4}, contact model error {:.4}, limit {MAX_FIT_ERROR}); {see}; change --band-hz or --order, or keep it with --accept",
                out.display(),
                id.complex.error,
                contact.error
            )
            .into());
        }
        if poor {
            println!(
                "  warning: a poor fit kept by --accept (contact model error {:.4})",
                contact.error
            );
        }
        scene.save(out)?;
        println!("wrote {}", out.display());
    }
    if let Some(dir) = &args.figures {
        run_figures(&scene, dir, &name, !args.figures_unclipped)?;
    }
    Ok(())
}

/// `node 1 +Z, node 2 +Z, …`.
fn dof_list(id: &FrfIdentification) -> String {
    id.data
        .dofs
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The pair's name, `node 1 +Z / node 2 +Z`.
fn pair_name(id: &FrfIdentification, k: usize) -> String {
    let (a, b) = id.data.set.pairs[k];
    format!("{} / {}", id.data.dofs[a], id.data.dofs[b])
}

fn summary(name: &str, id: &FrfIdentification) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{name}: {} fitted in the frequency domain (LSCF order {}, LSFD) in {:.3} s; relative L2 error over {} to {} Hz, all pairs: complex modes with residual terms {:.3e}, real modes {:.3e}{}",
        tirecontact::output::count(id.poles.len(), "mode"),
        id.order,
        id.elapsed_s,
        tirecontact::base::error::fmt_sig(id.data.band_hz.0, 6),
        tirecontact::base::error::fmt_sig(id.data.band_hz.1, 6),
        id.complex.error,
        id.real.error,
        match &id.contact {
            Ok(c) => format!(", contact model {:.3e}", c.error),
            Err(_) => String::new(),
        }
    );
    for n in &id.data.notes {
        let _ = writeln!(s, "  {n}");
    }
    let _ = writeln!(
        s,
        "  a mode: a pole stable against the order below (frequency within {} %, damping within {} %, with several references a vector MAC of at least {}) at one of orders {} to {} and at each order below it in a run of {} consecutive orders, drawn at the {} orders below; damping ratio below {}, inside the band, its term over its half-power band (two lines each side at least) {} times the fit's residual there or more; of poles within {} % one",
        fmt_sig(100.0 * id.options.freq_tol, 6),
        fmt_sig(100.0 * id.options.damping_tol, 6),
        fmt_sig(id.options.mac_min, 6),
        id.order.saturating_sub(id.options.persist).max(1),
        id.order,
        (id.options.persist / tirecontact::model::lscf::references(&id.data.set.pairs).max(1))
            .clamp(1, id.options.persist.max(1)),
        id.options.persist,
        fmt_sig(id.options.max_damping_ratio, 6),
        fmt_sig(MIN_TERM_TO_RESIDUAL, 6),
        fmt_sig(100.0 * id.options.freq_tol, 6)
    );
    for (k, (p, run)) in id.poles.iter().zip(&id.persistence).enumerate() {
        let resolved = if id.unresolved(k) {
            format!(
                " (unresolved: half-power width 2·xi·f = {} Hz, below two frequency lines of {} Hz)",
                fmt_sig(half_power_width_hz(p), 3),
                fmt_sig(id.line_hz, 6)
            )
        } else {
            String::new()
        };
        let split = if run.split_hz.is_empty() {
            String::new()
        } else {
            format!(
                "; split at order {} ({} Hz merged)",
                run.order,
                run.split_hz
                    .iter()
                    .map(|f| format!("{f:.3}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let _ = writeln!(
            s,
            "  mode {k:2}: {:9.3} Hz  xi {}{resolved}  stable at orders {} to {} (taken at {}){split}",
            p.freq_hz,
            sig6(p.damping_ratio),
            run.stable_orders.0,
            run.stable_orders.1,
            run.order
        );
    }
    for fp in &id.flagged {
        let _ = writeln!(
            s,
            "  pole {:9.3} Hz  xi {}  flagged: {}",
            fp.pole.freq_hz,
            sig6(fp.pole.damping_ratio),
            fp.why
        );
    }
    let units = id.data.set.ordinate.units();
    for k in 0..id.data.set.pairs.len() {
        let _ = writeln!(
            s,
            "  {}: residual terms lower {:.4e}, upper {:.4e} (receptance terms, m/N·(rad/s)² and m/N; the fit in {units})",
            pair_name(id, k),
            id.complex.lower[k],
            id.complex.upper[k]
        );
    }
    for (dof, d) in &id.driving {
        let _ = writeln!(s, "  {}", driving::describe(d, &dof.to_string(), dof.node));
    }
    if let Ok(c) = &id.contact {
        for n in &c.notes {
            let _ = writeln!(s, "  {n}");
        }
    }
    s
}

/// `--fit DIR`: modes.csv, fit.csv and fit.png.
fn write_fit(dir: &Path, name: &str, id: &FrfIdentification) -> CliResult {
    let mut modes = String::from("freq_hz,damping_ratio,stable,note\n");
    let mut rows: Vec<(f64, f64, bool, String)> = id
        .poles
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let note = if id.unresolved(k) {
                format!(
                    "damping unresolved: half-power width below two lines of {} Hz",
                    fmt_sig(id.line_hz, 6)
                )
            } else {
                String::new()
            };
            (p.freq_hz, p.damping_ratio, true, note)
        })
        .collect();
    for fp in &id.flagged {
        rows.push((
            fp.pole.freq_hz,
            fp.pole.damping_ratio,
            false,
            format!("flagged: {}", fp.why),
        ));
    }
    if let Some(chosen) = id.order.checked_sub(1).and_then(|o| id.diagram.get(o)) {
        for p in &chosen.poles {
            let kept = id
                .poles
                .iter()
                .any(|k| (k.freq_hz - p.freq_hz).abs() <= id.options.freq_tol * p.freq_hz);
            if !kept {
                rows.push((
                    p.freq_hz,
                    p.damping_ratio,
                    false,
                    format!("order {}: not kept", id.order),
                ));
            }
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (f, xi, st, note) in rows {
        // the note quoted: it holds commas
        let _ = writeln!(modes, "{f:e},{xi:e},{st},\"{}\"", note.replace('"', "'"));
    }
    let path = dir.join("modes.csv");
    write_atomic(&path, modes.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    let mut csv =
        String::from("freq_hz,response_node,reference_node,data_re,data_im,fit_re,fit_im\n");
    for (k, &(a, b)) in id.data.set.pairs.iter().enumerate() {
        let (ra, rb) = (id.data.dofs[a].node, id.data.dofs[b].node);
        for (f, (d, m)) in id
            .data
            .set
            .freq_hz
            .iter()
            .zip(id.data.set.h[k].iter().zip(&id.complex.fit[k]))
        {
            let _ = writeln!(
                csv,
                "{f:e},{ra},{rb},{:e},{:e},{:e},{:e}",
                d.re, d.im, m.re, m.im
            );
        }
    }
    let path = dir.join("fit.csv");
    write_atomic(&path, csv.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    let path = dir.join("fit.png");
    let fig = fit_figure(name, id);
    let height = (150 + 300 * fig.panels.len()).min(8000) as u32;
    render_png(&fig, &path, 1400, height)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Most pairs drawn in fit.png (the CSV has all).
const MAX_PANELS: usize = 12;

/// Data against fit per pair: magnitude in dB re 1 SI unit.
fn fit_figure(name: &str, id: &FrfIdentification) -> Figure {
    let set = &id.data.set;
    let units = set.ordinate.units();
    let db = |v: &faer::c64| 20.0 * v.norm().max(1e-300).log10();
    let line = |label: &str, vals: &[faer::c64], style: Style, color: usize| Series {
        name: label.into(),
        points: set
            .freq_hz
            .iter()
            .zip(vals)
            .map(|(f, v)| (*f, db(v)))
            .collect(),
        style,
        color: Some(color),
    };
    let panels = (0..set.pairs.len().min(MAX_PANELS))
        .map(|k| {
            let mut series = Vec::with_capacity(4);
            if let Ok(c) = &id.contact {
                series.push(line(
                    "contact model (real modes)",
                    &c.fit[k],
                    Style::ThinLine,
                    6,
                ));
            }
            series.push(line(
                "complex modes + residual terms",
                &id.complex.fit[k],
                Style::ThinLine,
                2,
            ));
            // the data on top, and the complex fit's error below them
            series.push(line("data", &set.h[k], Style::ThinLine, 0));
            let diff: Vec<faer::c64> = set.h[k]
                .iter()
                .zip(&id.complex.fit[k])
                .map(|(a, b)| a - b)
                .collect();
            series.push(line("|data − complex fit|", &diff, Style::ThinLine, 8));
            Panel {
                title: pair_name(id, k),
                x_label: "frequency (Hz)".into(),
                y_label: format!("|H| (dB re 1 {units})"),
                series,
                ..Panel::default()
            }
        })
        .collect();
    Figure {
        title: format!("{name}: {} data against fit", set.ordinate.name()),
        subtitle: format!(
            "{} at LSCF order {}; relative L2 error: complex {:.3e}, real modes {:.3e}, contact model {}{}",
            tirecontact::output::count(id.poles.len(), "mode"),
            id.order,
            id.complex.error,
            id.real.error,
            match &id.contact {
                Ok(c) => format!("{:.3e}", c.error),
                Err(_) => "none".to_string(),
            },
            if set.pairs.len() > MAX_PANELS {
                format!("; first {MAX_PANELS} of {} pairs drawn", set.pairs.len())
            } else {
                String::new()
            }
        ),
        panels,
    }
}

/// The stabilisation diagram of the fit.
fn diagram(name: &str, id: &FrfIdentification) -> Figure {
    let kept: Vec<f64> = id.poles.iter().map(|p| p.freq_hz).collect();
    Figure {
        title: format!("{name}: LSCF stabilisation diagram"),
        subtitle: format!(
            "{}; complex error {:.3e}, real modes {:.3e}",
            tirecontact::output::count(id.poles.len(), "mode"),
            id.complex.error,
            id.real.error
        ),
        panels: vec![stabilisation::panel(
            &id.diagram,
            Method::Lscf,
            id.order,
            &kept,
        )],
    }
}
