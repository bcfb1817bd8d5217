//! Output paths checked before any work: a file named on the command line
//! whose folder does not exist (or that is itself a folder) is refused up
//! front, naming the option, the path and what to do, instead of failing
//! with a bare OS error after the run (or a plotting backend's error).

use std::path::Path;

/// `Ok` when `path` can be created as a file: its folder exists and `path`
/// is not a folder. `option` is the flag as typed (`-o`, `--plot`), `what`
/// the kind of file expected (`CSV`, `PNG`).
pub fn check_output_file(option: &str, path: &Path, what: &str) -> Result<(), String> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(format!(
            "{option} {}: no folder {}: expected a {what} path in an existing folder (create it first: mkdir -p {})",
            path.display(),
            dir.display(),
            dir.display()
        ));
    }
    // `new/` names a folder even when it does not exist (yet)
    let slash = path
        .as_os_str()
        .to_string_lossy()
        .ends_with(std::path::MAIN_SEPARATOR);
    if path.is_dir() || slash {
        return Err(format!(
            "{option} {}: {}: expected a {what} file name, e.g. {}",
            path.display(),
            if path.is_dir() {
                "is a folder"
            } else {
                "ends with a folder separator"
            },
            path.join(format!("out.{}", what.to_lowercase())).display()
        ));
    }
    Ok(())
}

/// Creates the output folder `dir` of `option` (and its parents) when it
/// does not exist; refuses a path that is an existing file.
pub fn ensure_output_dir(option: &str, dir: &Path) -> Result<(), String> {
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "{option} {}: is a file: expected a folder (the files are written into it)",
            dir.display()
        ));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("{option} {}: cannot create the folder: {e}", dir.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_folder_and_folder_paths_are_refused() {
        let tmp = std::env::temp_dir().join(format!("tc-paths-{}", std::process::id()));
        std::fs::create_dir_all(&tmp).unwrap();
        assert!(check_output_file("-o", &tmp.join("a.csv"), "CSV").is_ok());
        assert!(check_output_file("-o", Path::new("a.csv"), "CSV").is_ok());
        let e = check_output_file("-o", &tmp.join("nope/a.csv"), "CSV").unwrap_err();
        assert!(
            e.starts_with("-o ") && e.contains("no folder") && e.contains("mkdir -p"),
            "{e}"
        );
        let e = check_output_file("--plot", &tmp, "PNG").unwrap_err();
        assert!(e.contains("is a folder") && e.contains("out.png"), "{e}");
        let file = tmp.join("f.txt");
        std::fs::write(&file, "x").unwrap();
        assert!(
            ensure_output_dir("--figures", &file)
                .unwrap_err()
                .contains("is a file")
        );
        let sub = tmp.join("x/y");
        ensure_output_dir("--figures", &sub).unwrap();
        assert!(sub.is_dir());
        std::fs::remove_dir_all(&tmp).ok();
    }
}
