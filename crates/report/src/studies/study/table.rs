//! A study's table as files: read (a last line cut short by a killed run
//! is left out), written sorted by row in the one form every table has,
//! and the parts of a sharded study merged, checked to be one study with
//! every row once. The command line (`study run`, `study merge`) and the
//! Python package write through here, so that merged shards, a resumed
//! run and a one-process run give the same bytes.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A table's records by row id (each its fields, the id first).
pub type TableRows = BTreeMap<usize, Vec<String>>;

/// A study table: its header and its records by row.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StudyTable {
    pub header: Vec<String>,
    pub rows: TableRows,
}

/// Why a table could not be read, written or merged: the file, the row
/// and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    #[error("{}: {message}", .path.display())]
    File { path: PathBuf, message: String },
    #[error("{}: line {line}: row = `{value}`: expected a row number", .path.display())]
    RowNumber {
        path: PathBuf,
        line: usize,
        value: String,
    },
    #[error("{}: row {id} twice: expected every row once", .path.display())]
    RowTwice { path: PathBuf, id: usize },
    #[error("a record with row = `{value}`: expected a row number")]
    RecordRowNumber { value: String },
    #[error("row {id} twice: expected every row once")]
    RecordTwice { id: usize },
    #[error("{}: its columns differ from {}'s: expected parts of one study", .path.display(), .first.display())]
    Columns { path: PathBuf, first: PathBuf },
    #[error("{}: row {id} is of study {hash}, the first part's of {first_hash}: expected parts of one study", .path.display())]
    OtherStudy {
        path: PathBuf,
        id: usize,
        hash: String,
        first_hash: String,
    },
    #[error("{}: row {id}: of = `{of}`: expected the study's row count", .path.display())]
    RowCount {
        path: PathBuf,
        id: usize,
        of: String,
    },
    #[error("{}: row {id}: of = {of}: expected {expected} as in the other rows", .path.display())]
    OtherRowCount {
        path: PathBuf,
        id: usize,
        of: usize,
        expected: usize,
    },
    #[error("{}: row {id} is in two parts: expected every row once", .path.display())]
    InTwoParts { path: PathBuf, id: usize },
    #[error("{} of {total} rows missing: {}{}; run them (study run --rows A..B) and merge again", .missing.len(), shown(.missing), if .missing.len() > 20 { ", …" } else { "" })]
    Missing { missing: Vec<usize>, total: usize },
}

fn shown(missing: &[usize]) -> String {
    missing
        .iter()
        .take(20)
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

fn file_error(path: &Path, e: impl std::fmt::Display) -> TableError {
    TableError::File {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// The table at `path` (a part, a merged table or one being written by
/// `study run`): its header and records by row; a last line cut short
/// (a killed run) is left out.
pub fn read_table(path: &Path) -> Result<StudyTable, TableError> {
    let text = std::fs::read_to_string(path).map_err(|e| file_error(path, e))?;
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header: Vec<String> = rdr
        .headers()
        .map_err(|e| file_error(path, e))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut rows = BTreeMap::new();
    for (k, rec) in rdr.records().enumerate() {
        let Ok(rec) = rec else { continue };
        if rec.len() != header.len() {
            continue; // cut short
        }
        let id: usize = rec[0].parse().map_err(|_| TableError::RowNumber {
            path: path.to_path_buf(),
            line: k + 2,
            value: rec[0].to_string(),
        })?;
        let fields: Vec<String> = rec.iter().map(str::to_string).collect();
        if rows.insert(id, fields).is_some() {
            return Err(TableError::RowTwice {
                path: path.to_path_buf(),
                id,
            });
        }
    }
    Ok(StudyTable { header, rows })
}

/// `records` (as [`super::record`] makes them, in any order) by row id.
pub fn rows_by_id(records: Vec<Vec<String>>) -> Result<TableRows, TableError> {
    let mut rows = BTreeMap::new();
    for r in records {
        let value = r.first().cloned().unwrap_or_default();
        let id: usize = value
            .parse()
            .map_err(|_| TableError::RecordRowNumber { value })?;
        if rows.insert(id, r).is_some() {
            return Err(TableError::RecordTwice { id });
        }
    }
    Ok(rows)
}

/// Writes `header` and `rows` (by id) to `path` atomically: the one form
/// of every study table ([`super::table_bytes`]).
pub fn write_table(path: &Path, header: &[String], rows: &TableRows) -> Result<(), TableError> {
    let bytes = super::table_bytes(header, rows.values()).map_err(|e| file_error(path, e))?;
    tirecontact_io::fsio::write_atomic(path, &bytes).map_err(|e| file_error(path, e))
}

/// The parts at `parts` merged into one table: the same columns, rows of
/// one study (its hash) and one row count, every row once and none
/// missing.
pub fn merge(parts: &[PathBuf]) -> Result<StudyTable, TableError> {
    let mut header: Option<Vec<String>> = None;
    let mut all = BTreeMap::new();
    let mut hash: Option<String> = None;
    let mut total: Option<usize> = None;
    for p in parts {
        let part = read_table(p)?;
        match &header {
            None => header = Some(part.header),
            Some(h0) if *h0 != part.header => {
                return Err(TableError::Columns {
                    path: p.clone(),
                    first: parts[0].clone(),
                });
            }
            _ => {}
        }
        for (id, r) in part.rows {
            let (of, hs) = (
                r.get(1).cloned().unwrap_or_default(),
                r.get(2).cloned().unwrap_or_default(),
            );
            let first_hash = hash.get_or_insert_with(|| hs.clone());
            if *first_hash != hs {
                return Err(TableError::OtherStudy {
                    path: p.clone(),
                    id,
                    hash: hs,
                    first_hash: first_hash.clone(),
                });
            }
            let of: usize = of.parse().map_err(|_| TableError::RowCount {
                path: p.clone(),
                id,
                of: of.clone(),
            })?;
            let expected = *total.get_or_insert(of);
            if expected != of {
                return Err(TableError::OtherRowCount {
                    path: p.clone(),
                    id,
                    of,
                    expected,
                });
            }
            if all.insert(id, r).is_some() {
                return Err(TableError::InTwoParts {
                    path: p.clone(),
                    id,
                });
            }
        }
    }
    let total = total.unwrap_or(0);
    let missing: Vec<usize> = (0..total).filter(|id| !all.contains_key(id)).collect();
    if !missing.is_empty() {
        return Err(TableError::Missing { missing, total });
    }
    Ok(StudyTable {
        header: header.unwrap_or_default(),
        rows: all,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(id: usize, of: usize, hash: &str, v: &str) -> Vec<String> {
        [id.to_string(), of.to_string(), hash.into(), v.into()].to_vec()
    }

    fn header() -> Vec<String> {
        ["row", "of", "study", "x"].map(String::from).to_vec()
    }

    /// Shards written in any order merge to the bytes of the whole table
    /// written at once; a duplicate, a missing row, another study and a
    /// cut-short last line are each caught or skipped as documented.
    #[test]
    fn parts_merge_to_the_one_process_table() {
        let dir = tempfile::tempdir().unwrap();
        let n = 7;
        let all: Vec<Vec<String>> = (0..n).map(|i| rec(i, n, "h", &format!("{i}.5"))).collect();
        let whole = dir.path().join("whole.csv");
        write_table(&whole, &header(), &rows_by_id(all.clone()).unwrap()).unwrap();
        let mut parts = Vec::new();
        for k in 0..3 {
            // each shard's rows reversed: the order written does not matter
            let mine: Vec<Vec<String>> = all.iter().skip(k).step_by(3).rev().cloned().collect();
            let p = dir.path().join(format!("part{k}.csv"));
            let bytes = crate::studies::study::table_bytes(&header(), &mine).unwrap();
            std::fs::write(&p, bytes).unwrap();
            parts.push(p);
        }
        // a killed run's last line, cut short
        std::fs::OpenOptions::new()
            .append(true)
            .open(&parts[2])
            .and_then(|mut f| std::io::Write::write_all(&mut f, b"6,7"))
            .unwrap();
        let merged = merge(&parts).unwrap();
        let out = dir.path().join("merged.csv");
        write_table(&out, &merged.header, &merged.rows).unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&whole).unwrap());

        let e = merge(&parts[..2]).unwrap_err().to_string();
        assert!(e.starts_with("2 of 7 rows missing: 2, 5;"), "{e}");
        let e = merge(&[parts[0].clone(), parts[0].clone()]).unwrap_err();
        assert!(matches!(e, TableError::InTwoParts { id: 0, .. }), "{e}");
        let other = dir.path().join("other.csv");
        let bytes = crate::studies::study::table_bytes(&header(), &[rec(1, n, "g", "1")]).unwrap();
        std::fs::write(&other, bytes).unwrap();
        let e = merge(&[parts[0].clone(), other]).unwrap_err().to_string();
        assert!(
            e.contains("row 1 is of study g, the first part's of h"),
            "{e}"
        );
        let e = rows_by_id(vec![rec(3, n, "h", "a"), rec(3, n, "h", "b")]).unwrap_err();
        assert_eq!(e.to_string(), "row 3 twice: expected every row once");
    }
}
