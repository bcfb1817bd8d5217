//! `tirecontact`: without a subcommand, the visualiser on the embedded default
//! preset (or a headless run of it when built without the `gui` feature).

mod cli;

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "tirecontact",
    version,
    about = "Dynamic tyre/road contact by fast modal convolution"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene headless and write its time histories as CSV.
    Run(cli::run::RunArgs),
    /// Identify the modal model of a ring or measured tyre by LSCE (method §5-6).
    Identify(cli::identify::IdentifyArgs),
    /// Run a scene over a range of one parameter; summary and band levels per value.
    Sweep(cli::sweep::SweepArgs),
    /// Parameter studies: plan, run (in shards), merge.
    Study(cli::study::StudyArgs),
    /// Work-precision study and before/after timings of skipped work.
    Bench(cli::bench::BenchArgs),
    /// Parse and validate a scene preset.
    Check {
        /// Scene preset (RON).
        preset: PathBuf,
    },
    /// Print a link that opens a preset's scene in the visualiser's web page.
    Share {
        /// Scene preset (RON); a measured tyre or road cannot travel in a link.
        preset: PathBuf,
        /// The page the link opens.
        #[arg(long, default_value = tirecontact::scene::share::DEFAULT_BASE_URL)]
        base_url: String,
    },
    /// Open the visualiser on a preset (without a subcommand: the last
    /// session or the embedded default preset).
    #[cfg(feature = "gui")]
    Gui {
        /// Scene preset (RON).
        preset: Option<PathBuf>,
        /// Start in classroom mode (large fonts, presenter layout, slow motion).
        #[arg(long)]
        classroom: bool,
    },
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    if matches!(
        cli.command,
        Some(
            Command::Run(_)
                | Command::Sweep(_)
                | Command::Identify(_)
                | Command::Bench(_)
                | Command::Study(_)
                | Command::Check { .. }
        )
    ) {
        // an interrupted run leaves no half-written temporary behind
        tirecontact::fsio::interrupt::remove_temporaries_on_signal();
    }
    let result = match cli.command {
        Some(Command::Run(args)) => cli::run::run(&args),
        Some(Command::Check { preset }) => cli::check::check(&preset),
        Some(Command::Share { preset, base_url }) => cli::share::share(&preset, &base_url),
        #[cfg(feature = "gui")]
        Some(Command::Gui { preset, classroom }) => {
            tirecontact::gui::run_with_options(preset, classroom)
                .map_err(|e| format!("cannot open the visualiser: {e}").into())
        }
        Some(Command::Identify(args)) => cli::identify::identify(&args),
        Some(Command::Bench(args)) => cli::bench::bench(&args),
        Some(Command::Sweep(args)) => cli::sweep::sweep(&args),
        Some(Command::Study(args)) => cli::study::study(&args),
        None => default_action(),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(feature = "gui")]
fn default_action() -> cli::CliResult {
    tirecontact::gui::run().map_err(|e| format!("cannot open the visualiser: {e}").into())
}

#[cfg(not(feature = "gui"))]
fn default_action() -> cli::CliResult {
    headless_default()
}

#[cfg(not(feature = "gui"))]
fn headless_default() -> cli::CliResult {
    cli::run::run(&cli::run::RunArgs {
        preset: None,
        output: None,
        dt: None,
        duration: None,
        every: 1,
        max_output_gb: cli::run::DEFAULT_MAX_OUTPUT_GB,
        plot: None,
        plot_unclipped: false,
        plot_size: (1400, 900),
        spectrum: None,
        spectrum_plot: None,
        spectrum_from: None,
        spectrum_max_hz: 5000.0,
        frames: None,
        frames_clear: false,
        fps: 25.0,
        slow_motion: 20.0,
        frames_from: 0.0,
        frames_to: None,
        frame_size: (1280, 720),
        exact_rank: false,
        threads: 1,
        patch_summary: None,
        patch_every: 1,
        patch_frames: None,
        patch_frame_count: 40,
    })
}
