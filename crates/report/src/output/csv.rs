//! The run CSV (pandas-friendly): `t_s`, then `u{i}_m`, `v{i}_mps`, `q{i}_N`
//! (step-mean force, or mean over the `every` steps of a row so impulses are
//! kept), `gap{i}_m`, `contact{i}` (0/1). The rows are the run sampler's
//! samples ([`super::sampler`]): the force a window mean, the other values
//! the state at the row's time.

use crate::output::sampler::{LastWindow, Sampler, Stride};
use crate::output::sci::push_e9;
use std::io::Write;
use tirecontact_core::solver::simulation::Simulation;

/// The header row for `p` points.
pub fn header(p: usize) -> Vec<String> {
    let mut h = vec!["t_s".to_string()];
    for (prefix, suffix) in [
        ("u", "_m"),
        ("v", "_mps"),
        ("q", "_N"),
        ("gap", "_m"),
        ("contact", ""),
    ] {
        h.extend((0..p).map(|i| format!("{prefix}{i}{suffix}")));
    }
    h
}

/// Bytes of one value in a row: `-1.234567890e-10` and its comma, the
/// longest with a one- or two-digit exponent (most are 16 bytes or fewer).
pub const BYTES_PER_VALUE: u64 = 17;

/// Estimated size (bytes) of the CSV of a run of `steps` steps of `p` points
/// written every `every` steps: rows (header, initial state, one per `every`
/// steps and a last partial one) × columns (`1 + 5 p`) × [`BYTES_PER_VALUE`].
/// An overestimate for the 0/1 contact columns; exact enough to refuse a run
/// up front.
pub fn estimated_bytes(steps: u64, every: u64, p: usize) -> f64 {
    let rows = steps.div_ceil(every.max(1)) as f64 + 3.0;
    rows * (1 + 5 * p) as f64 * BYTES_PER_VALUE as f64
}

/// A byte count for messages, in decimal units (`8.52 TB`).
pub fn human_bytes(b: f64) -> String {
    let units = ["bytes", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut x = b;
    let mut k = 0;
    while x >= 1000.0 && k + 1 < units.len() {
        x /= 1000.0;
        k += 1;
    }
    if k == 0 {
        format!("{x:.0} bytes")
    } else {
        format!("{x:.2} {}", units[k])
    }
}

/// Values (numbers) per formatting block: about 512 kB of rows kept before
/// they are formatted and written.
const BLOCK_VALUES: usize = 1 << 16;

/// Streams rows of a run, averaging forces over `every` steps.
///
/// Rows are kept as numbers and formatted a block at a time, the block split
/// between the machine's cores by values, whatever the row width
/// (formatting is a large part of a long `run -o`: about 45 ns per value
/// through [`push_e9`], 150 ns through `format!`). The bytes do not depend
/// on the thread count: `{:.9e}` for every number, `0`/`1` for the contact
/// flags, comma-separated, one `\n`-terminated line per row.
pub struct RunWriter<W: Write> {
    /// Where the formatted rows go.
    sink: Sink<W>,
    p: usize,
    sampler: Sampler,
    /// Rows not yet formatted, `1 + 5 p` numbers each.
    rows: Vec<f64>,
    /// Rows per block.
    block_rows: usize,
    /// One text buffer per formatting thread, reused block after block.
    text: Vec<Vec<u8>>,
    /// Rows below which a block part is not worth a thread of its own.
    min_rows_per_thread: usize,
}

impl<W: Write> RunWriter<W> {
    pub fn new(out: W, p: usize, every: u64) -> std::io::Result<Self> {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get().min(8));
        Self::with_layout(out, p, every, threads, BLOCK_VALUES)
    }

    /// [`RunWriter::new`] with `threads` formatting threads and blocks of
    /// about `block_values` numbers (at least one row).
    pub fn with_layout(
        mut out: W,
        p: usize,
        every: u64,
        threads: usize,
        block_values: usize,
    ) -> std::io::Result<Self> {
        out.write_all(header(p).join(",").as_bytes())?;
        out.write_all(b"\n")?;
        let width = 1 + 5 * p;
        let block_rows = (block_values / width).max(1);
        Ok(RunWriter {
            sink: Sink::Inline(out),
            p,
            sampler: Sampler::new(p, Stride::Every(every), LastWindow::Partial),
            rows: Vec::with_capacity(block_rows * width),
            block_rows,
            text: vec![Vec::new(); threads.max(1)],
            min_rows_per_thread: (MIN_VALUES_PER_THREAD / width).max(1),
        })
    }

    /// Writes the initial state (t = 0) row.
    pub fn write_initial(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.sampler.start(sim);
        self.push_row(sim)
    }

    /// Call after every step; writes a row every `every` steps, and one for
    /// the steps after the last whole window at the run's end.
    pub fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        if self.sampler.after_step(sim).is_some() {
            self.push_row(sim)?;
        }
        Ok(())
    }

    /// Keeps the row of the sampler's last window (its mean forces and
    /// `sim`'s state at its end); formats and writes the block once full.
    fn push_row(&mut self, sim: &Simulation) -> std::io::Result<()> {
        let p = self.p;
        self.rows.push(sim.time_s());
        self.rows.extend_from_slice(sim.displacement_m());
        self.rows.extend_from_slice(sim.velocity_mps());
        self.rows.extend_from_slice(self.sampler.last_window().q_n);
        self.rows.extend((0..p).map(|i| sim.gap_m(i)));
        self.rows
            .extend(sim.in_contact().iter().map(|&c| if c { 1.0 } else { 0.0 }));
        if self.rows.len() >= self.block_rows * (1 + 5 * p) {
            self.write_block()?;
        }
        Ok(())
    }

    /// Formats the kept rows, split by whole rows between the threads, and
    /// writes the parts in order.
    fn write_block(&mut self) -> std::io::Result<()> {
        let (p, width) = (self.p, 1 + 5 * self.p);
        let nrows = self.rows.len() / width;
        if nrows == 0 {
            return Ok(());
        }
        let out = match &mut self.sink {
            Sink::Inline(out) => out,
            Sink::Piped(pipe) => {
                let spare = pipe
                    .spare
                    .try_recv()
                    .unwrap_or_else(|_| Vec::with_capacity(self.rows.capacity()));
                let block = std::mem::replace(&mut self.rows, spare);
                if pipe.blocks.send(block).is_ok() {
                    return Ok(());
                }
                // the thread stopped on an error: its result says which
                return Err(match self.sink.close() {
                    Err(e) => e,
                    Ok(_) => std::io::Error::other("the CSV thread stopped"),
                });
            }
            Sink::Closed => return Err(std::io::Error::other("the CSV output was closed")),
        };
        let parts = self
            .text
            .len()
            .min(nrows.div_ceil(self.min_rows_per_thread))
            .max(1);
        let per = nrows.div_ceil(parts);
        // (as many parts as chunks of `per` rows, which can be fewer)
        let parts = nrows.div_ceil(per);
        let chunks = self.rows.chunks(per * width);
        let texts = &mut self.text[..parts];
        if parts == 1 {
            format_rows(&self.rows, p, &mut texts[0]);
        } else {
            std::thread::scope(|scope| {
                let mut texts = texts.iter_mut();
                let mut chunks = chunks;
                let first = (texts.next(), chunks.next());
                for (text, rows) in texts.zip(chunks) {
                    scope.spawn(move || format_rows(rows, p, text));
                }
                if let (Some(text), Some(rows)) = first {
                    format_rows(rows, p, text);
                }
            });
        }
        for text in &self.text[..parts] {
            out.write_all(text)?;
        }
        self.rows.clear();
        Ok(())
    }

    pub fn finish(mut self) -> std::io::Result<W> {
        if !self.rows.is_empty() {
            self.write_block()?;
        }
        let mut out = self.sink.close()?;
        out.flush()?;
        Ok(out)
    }
}

impl<W: Write> Drop for RunWriter<W> {
    /// A piped writer dropped without [`RunWriter::finish`] (a run that
    /// failed) waits for its thread, so that the output is dropped before
    /// the writer is gone (an atomic file then removes its temporary file,
    /// as it does without the thread).
    fn drop(&mut self) {
        if let Sink::Piped(_) = self.sink {
            let _ = self.sink.close();
        }
    }
}

impl<W: Write + Send + 'static> RunWriter<W> {
    /// [`RunWriter::new`] whose blocks are formatted and written by a thread
    /// of their own while the run goes on (the same bytes): a long `run -o`
    /// then waits on the solver or on the formatting, not on both.
    pub fn piped(out: W, p: usize, every: u64) -> std::io::Result<Self> {
        let mut w = Self::with_layout(out, p, every, 1, BLOCK_VALUES)?;
        let mut out = w.sink.close()?;
        // one block queued while one is formatted and one filled
        let (blocks, queued) = std::sync::mpsc::sync_channel::<Vec<f64>>(1);
        let (give_back, spare) = std::sync::mpsc::sync_channel::<Vec<f64>>(2);
        let worker = std::thread::Builder::new()
            .name("csv".into())
            .spawn(move || {
                let mut text = Vec::new();
                for mut rows in queued {
                    format_rows(&rows, p, &mut text);
                    out.write_all(&text)?;
                    rows.clear();
                    // (a full channel: the buffer is dropped)
                    let _ = give_back.try_send(rows);
                }
                Ok(out)
            })?;
        w.sink = Sink::Piped(Pipe {
            blocks,
            spare,
            worker,
        });
        Ok(w)
    }
}

/// Where a [`RunWriter`]'s rows go: formatted in the writer's own
/// thread(s) into the output, to the formatting thread of
/// [`RunWriter::piped`], or nowhere once the output was handed back.
enum Sink<W> {
    Inline(W),
    Piped(Pipe<W>),
    Closed,
}

impl<W> Sink<W> {
    /// The output, once every block sent is written (a piped sink's thread
    /// joined), or the first error; the sink is closed after.
    fn close(&mut self) -> std::io::Result<W> {
        match std::mem::replace(self, Sink::Closed) {
            Sink::Inline(out) => Ok(out),
            Sink::Piped(pipe) => pipe.join(),
            Sink::Closed => Err(std::io::Error::other("the CSV output was closed")),
        }
    }
}

/// The formatting thread of [`RunWriter::piped`]: blocks of rows go to it,
/// their emptied buffers come back.
struct Pipe<W> {
    blocks: std::sync::mpsc::SyncSender<Vec<f64>>,
    spare: std::sync::mpsc::Receiver<Vec<f64>>,
    worker: std::thread::JoinHandle<std::io::Result<W>>,
}

impl<W> Pipe<W> {
    /// Closes the queue and waits for the thread: the output once every
    /// block is written, or the first error.
    fn join(self) -> std::io::Result<W> {
        drop(self.blocks);
        match self.worker.join() {
            Ok(r) => r,
            Err(_) => Err(std::io::Error::other("the CSV thread panicked")),
        }
    }
}

/// Values below which a block part is not worth a thread of its own
/// (about 0.4 ms of formatting against some 20 µs to start a thread).
const MIN_VALUES_PER_THREAD: usize = 8_192;

/// `rows` (`1 + 5 p` numbers each) as CSV lines into `text` (cleared first).
fn format_rows(rows: &[f64], p: usize, text: &mut Vec<u8>) {
    text.clear();
    for row in rows.chunks_exact(1 + 5 * p) {
        let (values, flags) = row.split_at(1 + 4 * p);
        for (k, &x) in values.iter().enumerate() {
            if k > 0 {
                text.push(b',');
            }
            // `{:.9e}`, byte for byte
            push_e9(text, x);
        }
        for &c in flags {
            text.extend_from_slice(if c != 0.0 { b",1" } else { b",0" });
        }
        text.push(b'\n');
    }
}

impl<W: Write> tirecontact_core::solver::drive::Probe for RunWriter<W> {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.write_initial(sim)
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        RunWriter::after_step(self, sim)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tirecontact_io::SceneSimulation;
    use tirecontact_io::scene::Scene;

    /// The rows of `steps` steps of the three-point preset (impacts,
    /// releases, every point in and out of contact), formatted the plain way:
    /// each value on its own, rows averaged over `every` steps here.
    fn plain(scene: &Scene, steps: u64, every: u64) -> String {
        let mut sim = Simulation::from_scene(scene).unwrap();
        let p = sim.num_points();
        let mut out = header(p).join(",") + "\n";
        let row = |sim: &Simulation, q: &[f64]| {
            let mut fields = vec![format!("{:.9e}", sim.time_s())];
            fields.extend(sim.displacement_m().iter().map(|x| format!("{x:.9e}")));
            fields.extend(sim.velocity_mps().iter().map(|x| format!("{x:.9e}")));
            fields.extend(q.iter().map(|x| format!("{x:.9e}")));
            fields.extend((0..p).map(|i| format!("{:.9e}", sim.gap_m(i))));
            fields.extend(sim.in_contact().iter().map(|&c| u8::from(c).to_string()));
            fields.join(",") + "\n"
        };
        out += &row(&sim, &vec![0.0; p]);
        let (mut sum, mut n) = (vec![0.0; p], 0u64);
        for _ in 0..steps {
            sim.step().unwrap();
            sum.iter_mut().zip(sim.force_n()).for_each(|(s, q)| *s += q);
            n += 1;
            if n == every || sim.finished() {
                let mean: Vec<f64> = sum.iter().map(|s| s / n as f64).collect();
                out += &row(&sim, &mean);
                sum.fill(0.0);
                n = 0;
            }
        }
        out
    }

    fn written(
        scene: &Scene,
        steps: u64,
        every: u64,
        (threads, block, min_rows): (usize, usize, usize),
    ) -> String {
        let mut sim = Simulation::from_scene(scene).unwrap();
        let mut w =
            RunWriter::with_layout(Vec::new(), sim.num_points(), every, threads, block).unwrap();
        w.min_rows_per_thread = min_rows;
        w.write_initial(&sim).unwrap();
        for _ in 0..steps {
            sim.step().unwrap();
            w.after_step(&sim).unwrap();
        }
        String::from_utf8(w.finish().unwrap()).unwrap()
    }

    /// Blocks and threads change nothing: every layout writes the bytes of
    /// the plain row-by-row formatting, including the partial last block,
    /// a block split unevenly between threads or into fewer parts than
    /// threads, and the mean forces of rows that gather several steps (the
    /// run ends inside a gathered row).
    #[test]
    fn blocks_and_threads_write_the_plain_rows() {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        scene.duration_s = 3001.0 * scene.dt_s;
        let steps = scene.num_steps();
        assert_eq!(steps, 3001);
        let width = 1 + 5 * scene.num_points();
        for every in [1, 7] {
            let want = plain(&scene, steps, every);
            assert!(
                want.contains(",1,") && want.contains(",0"),
                "contact flags of both kinds"
            );
            // (threads, rows per block, fewest rows per thread): one block;
            // a row per block; even and uneven splits; 8 threads on blocks
            // of 16 rows, 8 parts of 2, then a last block of 10 (every 1)
            // or 14 rows (every 7), which splits into 5 parts of 2, or 7 of 2
            let layouts = [
                (1, 100_000, 256),
                (1, 1, 256),
                (2, 2000, 256),
                (3, 1000, 256),
                (8, 5000, 256),
                (4, 9, 1),
                (8, 16, 1),
            ];
            for (threads, block_rows, min_rows) in layouts {
                let got = written(
                    &scene,
                    steps,
                    every,
                    (threads, block_rows * width, min_rows),
                );
                assert!(
                    got == want,
                    "every {every}, {threads} threads, {block_rows} rows per block: rows differ"
                );
            }
            // formatted on a thread of its own while the run goes on
            let mut sim = Simulation::from_scene(&scene).unwrap();
            let mut w = RunWriter::piped(Vec::new(), sim.num_points(), every).unwrap();
            w.write_initial(&sim).unwrap();
            for _ in 0..steps {
                sim.step().unwrap();
                w.after_step(&sim).unwrap();
            }
            let got = String::from_utf8(w.finish().unwrap()).unwrap();
            assert!(got == want, "every {every}, piped: rows differ");
        }
    }

    /// A piped writer dropped without `finish` (a failed run) has dropped
    /// its output when the drop returns, even while the thread is still
    /// writing: an atomic file's temporary file does not outlive the run.
    #[test]
    fn a_dropped_piped_writer_drops_its_output_first() {
        use std::sync::Arc;
        use std::sync::atomic::{AtomicBool, Ordering};
        struct Slow(Arc<AtomicBool>);
        impl Write for Slow {
            fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
                std::thread::sleep(std::time::Duration::from_millis(20));
                Ok(b.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        impl Drop for Slow {
            fn drop(&mut self) {
                self.0.store(true, Ordering::SeqCst);
            }
        }
        let scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let dropped = Arc::new(AtomicBool::new(false));
        let mut w = RunWriter::piped(Slow(dropped.clone()), sim.num_points(), 1).unwrap();
        w.write_initial(&sim).unwrap();
        for _ in 0..20_000 {
            sim.step().unwrap();
            w.after_step(&sim).unwrap();
        }
        assert!(!dropped.load(Ordering::SeqCst), "still writing");
        drop(w);
        assert!(
            dropped.load(Ordering::SeqCst),
            "the output outlived the writer"
        );
    }

    /// A piped writer's failing output is an error of the run (at a later
    /// block or at the end), not a panic or a silent loss.
    #[test]
    fn a_piped_writer_reports_the_output_error() {
        struct Full(usize);
        impl Write for Full {
            fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
                if self.0 < b.len() {
                    return Err(std::io::Error::other("disk full"));
                }
                self.0 -= b.len();
                Ok(b.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut w = RunWriter::piped(Full(200_000), sim.num_points(), 1).unwrap();
        let mut failed = None;
        w.write_initial(&sim).unwrap();
        for _ in 0..20_000 {
            sim.step().unwrap();
            if let Err(e) = w.after_step(&sim) {
                failed = Some(e);
                break;
            }
        }
        let e = match failed {
            Some(e) => e,
            None => w.finish().err().expect("the output filled up"),
        };
        assert_eq!(e.to_string(), "disk full");
    }
}
