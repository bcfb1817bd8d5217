//! The ground floor of file input and output: atomic writes (a temporary
//! beside the target, synced, renamed over it) whose temporaries are removed
//! when the command line is interrupted ([`interrupt`]), and bounded reads
//! of regular files only ([`read`]).

pub mod interrupt;
pub mod read;

use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes `bytes` to `path` atomically: a temporary file in the same folder,
/// flushed and synced, then renamed over `path`. On any failure the old file
/// is untouched and the temporary removed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// [`write_atomic`] with the contents produced by `write` into the temporary
/// file (for streamed contents; also the seam that lets tests interrupt a
/// write half-way: an error returned by `write` is handled exactly like a
/// failed disk write). The temporary is `.NAME.tmp-PID-N` beside `path`.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut f = AtomicFile::create(path)?;
    write(&mut f)?;
    f.commit()
}

/// A file written in place of `path` only when [`AtomicFile::commit`] is
/// called: until then the contents go to a temporary `.NAME.tmp-PID-N` in
/// the same folder, removed if the writer is dropped uncommitted (an error
/// or an interrupted run leaves the old file as it was).
pub struct AtomicFile {
    path: std::path::PathBuf,
    tmp: std::path::PathBuf,
    w: Option<std::io::BufWriter<std::fs::File>>,
    /// Its entry in the table of temporaries removed on a signal
    /// ([`interrupt`]).
    slot: Option<usize>,
}

impl AtomicFile {
    pub fn create(path: &Path) -> std::io::Result<Self> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => std::path::PathBuf::from("."),
        };
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.tmp-{}-{n}", std::process::id()));
        let f = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        let slot = interrupt::register(&tmp);
        Ok(AtomicFile {
            path: path.to_path_buf(),
            tmp,
            w: Some(std::io::BufWriter::new(f)),
            slot,
        })
    }

    /// Flushes, syncs and renames the temporary over the target.
    pub fn commit(mut self) -> std::io::Result<()> {
        let Some(w) = self.w.take() else {
            return Err(std::io::Error::other("atomic file already closed"));
        };
        let result = (|| {
            let f = w.into_inner().map_err(|e| e.into_error())?;
            f.sync_all()?;
            drop(f);
            std::fs::rename(&self.tmp, &self.path)
        })();
        if result.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        interrupt::forget(self.slot.take());
        result
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self.w.as_mut() {
            Some(w) => w.write(buf),
            None => Err(std::io::Error::other("atomic file already closed")),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        match self.w.as_mut() {
            Some(w) => w.flush(),
            None => Ok(()),
        }
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.w.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        interrupt::forget(self.slot.take());
    }
}
