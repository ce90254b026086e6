//! An output set written whole: `shoal plan` writes plan.json, the CSVs and the figures into a
//! staging directory inside the output directory, checks the plan it wrote, and only then moves
//! the set into place, removing the files of an earlier set that the new one does not have
//! (auv3.csv … auv6.csv of an earlier N = 7 plan beside an N = 3 one, figures kept by
//! `--no-plot`). A manifest, written last, lists the set and says it is complete; an
//! interrupted run leaves the earlier set (or none) and no manifest of its own, and its staging
//! directory is removed on Ctrl-C, or by the next run after a kill.

use crate::output::OutputError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The manifest's file name in the output directory.
pub const MANIFEST: &str = ".shoal-outputs.json";

/// Prefix of staging directories inside the output directory.
const STAGING: &str = ".shoal-staging-";

/// What the manifest records: the files of the set (relative paths) and the check's verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Files of the set, relative to the output directory.
    pub files: Vec<String>,
    /// Whether the plan passed its check.
    pub check_passed: bool,
}

/// An output set being written: files go into [`OutputSet::dir`], [`OutputSet::commit`] moves
/// them into the output directory.
#[derive(Debug)]
pub struct OutputSet {
    out: PathBuf,
    staging: tempfile::TempDir,
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Write {
        path: path.to_path_buf(),
        source,
    }
}

impl OutputSet {
    /// Start a set for the output directory `out`: refused at once (before any planning) when
    /// `out` exists and is not a directory. Creates `out`, and removes staging directories
    /// that killed runs left there.
    pub fn begin(out: &Path) -> Result<OutputSet, OutputError> {
        if out.exists() && !out.is_dir() {
            return Err(OutputError::NotADirectory {
                path: out.to_path_buf(),
            });
        }
        std::fs::create_dir_all(out).map_err(io(out))?;
        for entry in std::fs::read_dir(out).map_err(io(out))?.flatten() {
            let name = entry.file_name();
            if name.to_string_lossy().starts_with(STAGING) && entry.path().is_dir() {
                let _ = std::fs::remove_dir_all(entry.path());
            }
        }
        let staging = tempfile::Builder::new()
            .prefix(STAGING)
            .tempdir_in(out)
            .map_err(io(out))?;
        Ok(OutputSet {
            out: out.to_path_buf(),
            staging,
        })
    }

    /// The staging directory: write every file of the set here.
    pub fn dir(&self) -> &Path {
        self.staging.path()
    }

    /// Move the set into the output directory: remove the earlier set's files (those its
    /// manifest lists, or shoal's own names when it has none) that the new set does not have,
    /// rename each new file into place, then write the manifest. Returns the files, relative.
    pub fn commit(self, check_passed: bool) -> Result<Vec<String>, OutputError> {
        let out = &self.out;
        let mut files = Vec::new();
        collect(self.dir(), Path::new(""), &mut files).map_err(io(self.dir()))?;
        files.sort();
        // the earlier set is incomplete from here on
        let manifest = out.join(MANIFEST);
        let earlier = earlier_files(out);
        let _ = std::fs::remove_file(&manifest);
        for old in earlier.iter().filter(|f| !files.contains(f)) {
            let path = out.join(old);
            let _ = std::fs::remove_file(&path);
            // a directory of the earlier set (figures/) that is now empty goes too
            if let Some(parent) = path.parent().filter(|p| *p != out.as_path()) {
                let _ = std::fs::remove_dir(parent);
            }
        }
        for f in &files {
            let to = out.join(f);
            if let Some(parent) = to.parent() {
                std::fs::create_dir_all(parent).map_err(io(parent))?;
            }
            std::fs::rename(self.dir().join(f), &to).map_err(io(&to))?;
        }
        let record = Manifest {
            files: files.clone(),
            check_passed,
        };
        let json = serde_json::to_string_pretty(&record).expect("a manifest serialises");
        crate::atomic_file::write(&manifest, json.as_bytes()).map_err(io(&manifest))?;
        Ok(files)
    }
}

/// Relative paths of every file under `dir`.
fn collect(dir: &Path, rel: &Path, files: &mut Vec<String>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let rel = rel.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            collect(&entry.path(), &rel, files)?;
        } else {
            files.push(rel.to_string_lossy().into_owned());
        }
    }
    Ok(())
}

/// The files of the set already in `out`: its manifest's, or (written before manifests) every
/// file with one of the names `shoal plan` writes.
fn earlier_files(out: &Path) -> Vec<String> {
    if let Some(m) = std::fs::read_to_string(out.join(MANIFEST))
        .ok()
        .and_then(|t| serde_json::from_str::<Manifest>(&t).ok())
    {
        return m.files;
    }
    let mut files = Vec::new();
    let ours = |name: &str| {
        name == "plan.json"
            || name == "usv.csv"
            || name
                .strip_prefix("auv")
                .and_then(|r| r.strip_suffix(".csv"))
                .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
    };
    if let Ok(dir) = std::fs::read_dir(out) {
        for e in dir.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if e.path().is_file() && ours(&name) {
                files.push(name);
            }
        }
    }
    for stem in crate::figures::FIGURES {
        for ext in ["png", "svg"] {
            let rel = format!("figures/{stem}.{ext}");
            if out.join(&rel).is_file() {
                files.push(rel);
            }
        }
    }
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(out: &Path, files: &[&str], passed: bool) -> Vec<String> {
        let s = OutputSet::begin(out).unwrap();
        for f in files {
            crate::output::write_atomic(&s.dir().join(f), f.as_bytes()).unwrap();
        }
        s.commit(passed).unwrap()
    }

    /// Regression (issue 13): re-planning into a directory left auv3.csv … auv6.csv of an
    /// earlier N = 7 plan beside an N = 3 one, and `--no-plot` kept the earlier figures.
    #[test]
    fn regression_replanning_left_stale_files() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        std::fs::create_dir_all(out.join("figures")).unwrap();
        // an earlier set, written before manifests, and a file of the user's
        for f in ["auv5.csv", "plan.json", "figures/seafloor.png", "notes.txt"] {
            std::fs::write(out.join(f), "old").unwrap();
        }
        let files = set(&out, &["plan.json", "usv.csv", "auv0.csv"], true);
        assert_eq!(files, ["auv0.csv", "plan.json", "usv.csv"]);
        assert!(!out.join("auv5.csv").exists() && !out.join("figures").exists());
        assert_eq!(
            std::fs::read_to_string(out.join("plan.json")).unwrap(),
            "plan.json"
        );
        assert!(out.join("notes.txt").exists(), "not ours: kept");
        // the manifest lists the set; the next set removes what it no longer has
        set(&out, &["plan.json", "figures/map.svg"], false);
        assert!(!out.join("usv.csv").exists() && out.join("figures/map.svg").exists());
        let m: Manifest =
            serde_json::from_str(&std::fs::read_to_string(out.join(MANIFEST)).unwrap()).unwrap();
        assert_eq!(m.files, ["figures/map.svg", "plan.json"]);
        assert!(!m.check_passed);
        // no staging directory is left
        let left: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with(STAGING))
            .collect();
        assert!(left.is_empty());
    }

    /// Regression (issue 13): `-o` naming an existing file failed only after planning.
    #[test]
    fn regression_an_output_that_is_a_file_is_refused_at_once() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("out");
        std::fs::write(&file, "x").unwrap();
        let e = OutputSet::begin(&file).unwrap_err().to_string();
        assert!(e.contains("is not a directory"), "{e}");
    }

    /// A killed run's staging directory is removed by the next run.
    #[test]
    fn a_killed_runs_staging_is_removed() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let left = out.join(format!("{STAGING}abc"));
        std::fs::create_dir_all(&left).unwrap();
        std::fs::write(left.join("plan.json"), "half").unwrap();
        let s = OutputSet::begin(&out).unwrap();
        assert!(!left.exists());
        drop(s);
    }
}
