//! Reading the user's files without trusting them: only regular files are
//! opened (a named pipe would block the open forever, a device such as
//! `/dev/zero` never ends), and text readers refuse a line longer than a
//! bound instead of buffering it whole.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// Opens `path` for reading if it is a regular file (after symbolic
/// links); a folder, a device, a pipe or a socket is an error saying so.
/// On unix the file is opened without blocking, so that a named pipe with
/// no writer is refused rather than waited on.
pub fn open_regular(path: &Path) -> io::Result<File> {
    let mut opts = std::fs::OpenOptions::new();
    opts.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.custom_flags(libc::O_NONBLOCK);
    }
    let file = opts.open(path)?;
    let kind = file.metadata()?.file_type();
    if kind.is_file() {
        return Ok(file);
    }
    let what = if kind.is_dir() {
        "a folder"
    } else {
        "not a regular file (a device, a named pipe or a socket)"
    };
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("is {what}"),
    ))
}

/// A reader that fails with [`io::ErrorKind::InvalidData`] once a line
/// (bytes between two `\n`) grows past `max_line` bytes.
pub struct LineCap<R> {
    inner: R,
    run: usize,
    max_line: usize,
    /// Line ends seen so far.
    lines: u64,
}

impl<R: Read> LineCap<R> {
    pub fn new(inner: R, max_line: usize) -> Self {
        LineCap {
            inner,
            run: 0,
            max_line,
            lines: 0,
        }
    }
}

impl<R: Read> Read for LineCap<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            if b == b'\n' {
                self.run = 0;
                self.lines += 1;
            } else {
                self.run += 1;
                if self.run > self.max_line {
                    return Err(io::Error::new(
                        io::ErrorKind::InvalidData,
                        format!(
                            "line {} is longer than {} bytes",
                            self.lines + 1,
                            self.max_line
                        ),
                    ));
                }
            }
        }
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_line_is_refused_and_short_ones_pass() {
        let text = b"1, 2\n3, 4\n".repeat(100);
        let mut out = Vec::new();
        LineCap::new(&text[..], 8).read_to_end(&mut out).unwrap();
        assert_eq!(out, text);
        let long = [b'0'; 100];
        let e = LineCap::new(&long[..], 64)
            .read_to_end(&mut Vec::new())
            .unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidData);
        assert!(
            e.to_string().contains("line 1 is longer than 64 bytes"),
            "{e}"
        );
        let third = [&b"a\nb\n"[..], &[b'0'; 100]].concat();
        let e = LineCap::new(&third[..], 64)
            .read_to_end(&mut Vec::new())
            .unwrap_err();
        assert!(e.to_string().contains("line 3 is"), "{e}");
    }

    #[test]
    fn only_regular_files_open() {
        let dir = std::env::temp_dir();
        let e = open_regular(&dir).unwrap_err();
        assert!(e.to_string().contains("folder"), "{e}");
        #[cfg(unix)]
        {
            let e = open_regular(Path::new("/dev/zero")).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
    }
}
