//! Output sets written whole. A command that writes several files (`shoal plan`: plan.json, the
//! CSVs and the figures; `shoal simulate`: sim.json and its figures; `shoal seafloor export`: a
//! grid and its `.prj`) writes them into a staging directory beside their place, and only then
//! moves the set into place, removing the files of an earlier set that the new one does not have
//! (auv3.csv … auv6.csv of an earlier N = 7 plan beside an N = 3 one, figures kept by
//! `--no-plot`, a `.prj` that does not describe the new grid). A plan's folder has a manifest,
//! written last, that lists its set.
//!
//! The move is journalled: before the first file moves, the staging directory receives a
//! journal of what moves and what goes. A run killed before the journal leaves the earlier set
//! untouched, and its staging directory is removed by the next run; a run killed after it leaves
//! a set half moved, which the next shoal command that opens the folder (a new run, or a read of
//! its plan) completes from the journal. Either way the folder ends up with one whole set, the
//! earlier or the new.
//!
//! The bookkeeping touches only what is shoal's: every path a manifest or a journal names must
//! be relative, inside the folder, without `..` or links on the way, and one of the names the
//! set's command writes ([`Kind::owns`]); a manifest that names anything else is refused, never
//! obeyed. A link is never followed, never removed.

use crate::output::OutputError;
use serde::{Deserialize, Serialize};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};

/// The plan set's manifest in the output directory.
pub const MANIFEST: &str = ".shoal-outputs.json";

/// The flight `shoal plan --fly` writes into the plan's set.
pub const PLAN_FLIGHT: &str = "sim.json";

/// Prefix of staging directories.
const STAGING: &str = ".shoal-staging-";

/// The journal of a commit, inside its staging directory.
const JOURNAL: &str = ".shoal-commit.json";

/// What an output set holds, and so which files its bookkeeping may ever remove.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// `shoal plan`: plan.json, usv.csv, auvN.csv and figures/STEM.png|svg of
    /// [`crate::figures::FIGURES`] and [`crate::figures::TABLE`]; with `--fly`, its flight
    /// too: sim.json and figures/STEM.png|svg of [`crate::figures::SIM_FIGURES`] (so a plan
    /// written without `--fly` removes an earlier plan's flight from its manifest).
    Plan,
    /// `shoal simulate`: the record (its file name, e.g. "sim.json") and
    /// figures/STEM.png|svg of [`crate::figures::SIM_FIGURES`].
    Simulation(String),
    /// `shoal compare`: runs.csv, summary.md and the figure compare.png|svg (the plans it
    /// keeps are written one by one as their runs end, and are not part of the set).
    Compare,
    /// `shoal seafloor export`: a grid (its file name, e.g. "floor.asc") and, for an ESRI ASCII
    /// grid, its `.prj`.
    Grid(String),
}

impl Kind {
    /// The manifest's file name: a plan's folder has one ([`MANIFEST`]), since the set's files
    /// vary (one CSV per AUV); the other sets' files follow from their name, and they have none.
    pub fn manifest(&self) -> Option<&'static str> {
        match self {
            Kind::Plan => Some(MANIFEST),
            Kind::Simulation(_) | Kind::Compare | Kind::Grid(_) => None,
        }
    }

    /// Whether `rel` (relative to the set's folder, `/`-separated) is a file this set's
    /// command writes.
    pub fn owns(&self, rel: &str) -> bool {
        let figure = |stems: &[&str]| {
            rel.strip_prefix("figures/")
                .and_then(|f| f.strip_suffix(".png").or_else(|| f.strip_suffix(".svg")))
                .is_some_and(|stem| stems.contains(&stem))
        };
        match self {
            Kind::Plan => {
                rel == "plan.json"
                    || rel == "usv.csv"
                    || rel
                        .strip_prefix("auv")
                        .and_then(|r| r.strip_suffix(".csv"))
                        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
                    || figure(&crate::figures::FIGURES)
                    || figure(&[crate::figures::TABLE])
                    || rel == PLAN_FLIGHT
                    || figure(&crate::figures::SIM_FIGURES)
            }
            Kind::Simulation(f) => rel == f || figure(&crate::figures::SIM_FIGURES),
            Kind::Compare => {
                ["runs.csv", "summary.md", "compare.png", "compare.svg"].contains(&rel)
            }
            // an ESRI ASCII grid's .prj sidecar (a GeoTIFF holds its CRS)
            Kind::Grid(f) => {
                let asc = Path::new(f)
                    .extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("asc"));
                rel == f || (asc && Path::new(f).with_extension("prj").to_str() == Some(rel))
            }
        }
    }

    /// The files of an earlier set in `out` that has no manifest (written before manifests):
    /// every existing regular file with a name of this set's.
    fn by_name(&self, out: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(out)
            .map(|d| {
                d.flatten()
                    .filter_map(|e| e.file_name().to_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default();
        if let Ok(d) = std::fs::read_dir(out.join("figures")) {
            names.extend(
                d.flatten()
                    .filter_map(|e| e.file_name().to_str().map(|n| format!("figures/{n}"))),
            );
        }
        let mut files: Vec<String> = names
            .into_iter()
            .filter(|rel| self.owns(rel) && regular(out, rel).is_ok_and(|r| r))
            .collect();
        files.sort();
        files
    }
}

/// What the manifest records: the files of the set (relative paths) and, for a plan, the
/// check's verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Files of the set, relative to its folder.
    pub files: Vec<String>,
    /// Whether the plan passed its check (plan sets only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check_passed: Option<bool>,
}

/// What a commit will do, written before it starts: the files that move in from the staging
/// directory and the earlier set's files that go.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Journal {
    kind: Kind,
    files: Vec<String>,
    remove: Vec<String>,
    #[serde(default)]
    check_passed: Option<bool>,
}

/// Whether `rel` is a safe relative path of `kind` inside a set's folder: one or two plain
/// components (no root, no `.` or `..`, no hidden shoal names) naming a file the set's command
/// writes.
fn safe(kind: &Kind, rel: &str) -> bool {
    let p = Path::new(rel);
    let parts: Vec<Component> = p.components().collect();
    !rel.is_empty()
        && !rel.contains('\\')
        && (1..=2).contains(&parts.len())
        && parts.iter().all(|c| match c {
            Component::Normal(n) => n.to_str().is_some_and(|n| !n.starts_with(".shoal-")),
            _ => false,
        })
        && kind.owns(rel)
}

/// Whether `out/rel` is a regular file reached through real directories only: Ok(true) a
/// regular file, Ok(false) absent; Err when a link or something else stands in the way.
fn regular(out: &Path, rel: &str) -> Result<bool, String> {
    let mut at = out.to_path_buf();
    let parts: Vec<&str> = rel.split('/').collect();
    for (i, part) in parts.iter().enumerate() {
        at.push(part);
        let meta = match std::fs::symlink_metadata(&at) {
            Ok(m) => m,
            Err(_) => return Ok(false),
        };
        let last = i + 1 == parts.len();
        let t = meta.file_type();
        if t.is_symlink() {
            return Err(format!("{} is a symbolic link", at.display()));
        }
        if last && !t.is_file() {
            return Err(format!("{} is not a regular file", at.display()));
        }
        if !last && !t.is_dir() {
            return Err(format!("{} is not a directory", at.display()));
        }
    }
    Ok(true)
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Write {
        path: path.to_path_buf(),
        source,
    }
}

/// The manifest of `kind` in `out`, its entries checked: Ok(None) when there is none; an error
/// when it cannot be read as a manifest or names a file that is not the set's own.
fn read_manifest(out: &Path, kind: &Kind) -> Result<Option<Manifest>, OutputError> {
    let Some(name) = kind.manifest() else {
        return Ok(None);
    };
    let path = out.join(name);
    let refuse = |why: String| OutputError::Manifest {
        path: path.clone(),
        why,
    };
    match std::fs::symlink_metadata(&path) {
        Err(_) => return Ok(None),
        Ok(m) if !m.file_type().is_file() => {
            return Err(refuse("it is not a regular file".into()));
        }
        Ok(_) => {}
    }
    let text = std::fs::read_to_string(&path).map_err(|e| refuse(e.to_string()))?;
    let m: Manifest =
        serde_json::from_str(&text).map_err(|e| refuse(format!("it is damaged ({e})")))?;
    if let Some(bad) = m.files.iter().find(|f| !safe(kind, f)) {
        return Err(refuse(format!(
            "it lists {:?}, which is not a file this command writes inside {}",
            bad,
            out.display()
        )));
    }
    Ok(Some(m))
}

/// The state a Ctrl-C handler and the thread committing a set share: an interrupt before the
/// commit may end the process (and remove the staging directory); once the commit has begun,
/// an interrupt waits for it to end, so that no set is left half moved.
#[derive(Debug, Default)]
pub struct CommitGate(AtomicU8);

const RUNNING: u8 = 0;
const COMMITTING: u8 = 1;
const INTERRUPTED: u8 = 2;

impl CommitGate {
    /// A gate before any commit.
    pub const fn new() -> CommitGate {
        CommitGate(AtomicU8::new(RUNNING))
    }

    /// For the handler: true when the process may end now (no commit has begun; from now on
    /// none will), false while a set is being moved into place.
    pub fn interrupt(&self) -> bool {
        match self
            .0
            .compare_exchange(RUNNING, INTERRUPTED, Ordering::SeqCst, Ordering::SeqCst)
        {
            Ok(_) => true,
            Err(state) => state == INTERRUPTED,
        }
    }

    /// Whether an interrupt has ended (or is ending) the run.
    pub fn interrupted(&self) -> bool {
        self.0.load(Ordering::SeqCst) == INTERRUPTED
    }

    /// For the committing thread: false when an interrupt came first (the handler is ending
    /// the process: do not start moving files).
    pub fn enter(&self) -> bool {
        self.0
            .compare_exchange(RUNNING, COMMITTING, Ordering::SeqCst, Ordering::SeqCst)
            .is_ok()
    }
}

/// An output set being written: files go into [`OutputSet::dir`], [`OutputSet::commit`] moves
/// them into the set's folder.
#[derive(Debug)]
pub struct OutputSet {
    out: PathBuf,
    kind: Kind,
    staging: tempfile::TempDir,
}

impl OutputSet {
    /// Start a plan set for the output directory `out` ([`OutputSet::begin_kind`] with
    /// [`Kind::Plan`]).
    pub fn begin(out: &Path) -> Result<OutputSet, OutputError> {
        OutputSet::begin_kind(out, Kind::Plan)
    }

    /// Start a set of `kind` in the folder `out`: refused at once (before any work) when `out`
    /// exists and is not a directory, or when its manifest cannot be trusted. Creates `out`,
    /// completes sets that killed runs left half moved, and removes their staging directories.
    pub fn begin_kind(out: &Path, kind: Kind) -> Result<OutputSet, OutputError> {
        if out.exists() && !out.is_dir() {
            return Err(OutputError::NotADirectory {
                path: out.to_path_buf(),
            });
        }
        std::fs::create_dir_all(out).map_err(io(out))?;
        settle(out);
        read_manifest(out, &kind)?;
        let staging = tempfile::Builder::new()
            .prefix(&format!("{STAGING}{}", crate::atomic_file::tag()))
            .tempdir_in(out)
            .map_err(io(out))?;
        Ok(OutputSet {
            out: out.to_path_buf(),
            kind,
            staging,
        })
    }

    /// The staging directory: write every file of the set here, at its place relative to the
    /// set's folder.
    pub fn dir(&self) -> &Path {
        self.staging.path()
    }

    /// Move the set into its folder: journal the move, remove the earlier set's files (those
    /// its manifest lists, or the set's own names when it has none) that the new set does not
    /// have, rename each new file into place, then write the manifest (with `check_passed`, for
    /// a plan). Returns the files, relative.
    pub fn commit(self, check_passed: Option<bool>) -> Result<Vec<String>, OutputError> {
        let out = self.out.clone();
        let mut files = Vec::new();
        collect(self.dir(), "", &mut files).map_err(io(self.dir()))?;
        files.sort();
        if let Some(bad) = files.iter().find(|f| !safe(&self.kind, f)) {
            return Err(OutputError::Write {
                path: self.dir().join(bad),
                source: std::io::Error::other("not a file of this output set"),
            });
        }
        for f in &files {
            // a folder of the set (figures/) that is a link would take the file elsewhere
            if let Some((parent, _)) = f.rsplit_once('/') {
                let at = out.join(parent);
                if std::fs::symlink_metadata(&at).is_ok_and(|m| !m.file_type().is_dir()) {
                    return Err(OutputError::Write {
                        path: at,
                        source: std::io::Error::other(
                            "is not a directory (a link, or a file): shoal writes only into \
                             real folders inside its output folder",
                        ),
                    });
                }
            }
        }
        let earlier = match read_manifest(&out, &self.kind)? {
            Some(m) => m.files,
            None => self.kind.by_name(&out),
        };
        let journal = Journal {
            kind: self.kind.clone(),
            remove: earlier.into_iter().filter(|f| !files.contains(f)).collect(),
            files: files.clone(),
            check_passed,
        };
        let text = serde_json::to_string_pretty(&journal).expect("a journal serialises");
        let path = self.dir().join(JOURNAL);
        cut::point()?;
        crate::atomic_file::write(&path, text.as_bytes()).map_err(io(&path))?;
        // from here on the set is committed: a kill leaves it for `settle` to finish
        let staging = self.staging.keep();
        roll_forward(&out, &staging, &journal)?;
        Ok(files)
    }
}

/// Relative paths (`/`-separated) of every file under `dir`.
fn collect(dir: &Path, rel: &str, files: &mut Vec<String>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let rel = match rel {
            "" => name,
            _ => format!("{rel}/{name}"),
        };
        if entry.file_type()?.is_dir() {
            collect(&entry.path(), &rel, files)?;
        } else {
            files.push(rel);
        }
    }
    Ok(())
}

/// Carry out a journalled commit in `out` from `staging`: the manifest goes (the set is in
/// motion), the earlier files go, the new files move in, the manifest is written, the staging
/// directory goes. Each step can be repeated, so a commit cut anywhere is finished by running
/// this again.
fn roll_forward(out: &Path, staging: &Path, j: &Journal) -> Result<(), OutputError> {
    let manifest = j.kind.manifest().map(|m| out.join(m));
    if let Some(manifest) = &manifest {
        if std::fs::symlink_metadata(manifest).is_ok_and(|m| m.file_type().is_file()) {
            cut::point()?;
            std::fs::remove_file(manifest).map_err(io(manifest))?;
        }
    }
    for old in &j.remove {
        if regular(out, old) != Ok(true) {
            continue; // gone already, or not a plain file of ours: left alone
        }
        let path = out.join(old);
        cut::point()?;
        std::fs::remove_file(&path).map_err(io(&path))?;
        // a folder of the earlier set (figures/) left empty goes too
        if let Some((parent, _)) = old.rsplit_once('/') {
            let _ = std::fs::remove_dir(out.join(parent));
        }
    }
    for f in &j.files {
        let from = staging.join(f);
        if std::fs::symlink_metadata(&from).is_err() {
            continue; // moved already
        }
        let to = out.join(f);
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent).map_err(io(parent))?;
        }
        cut::point()?;
        std::fs::rename(&from, &to).map_err(io(&to))?;
    }
    if let Some(manifest) = &manifest {
        let record = Manifest {
            files: j.files.clone(),
            check_passed: j.check_passed,
        };
        let json = serde_json::to_string_pretty(&record).expect("a manifest serialises");
        cut::point()?;
        crate::atomic_file::write(manifest, json.as_bytes()).map_err(io(manifest))?;
    }
    cut::point()?;
    std::fs::remove_dir_all(staging).map_err(io(staging))?;
    Ok(())
}

/// Where the tests cut a commit as a kill would: before each change to the file system.
mod cut {
    use crate::output::OutputError;

    #[cfg(test)]
    thread_local! {
        /// The changes left before the cut; None: no cut.
        pub(super) static LEFT: std::cell::Cell<Option<usize>> = const { std::cell::Cell::new(None) };
    }

    /// Err when the test's cut is here.
    #[inline]
    pub(super) fn point() -> Result<(), OutputError> {
        #[cfg(test)]
        if let Some(n) = LEFT.with(|c| c.get()) {
            if n == 0 {
                return Err(OutputError::Write {
                    path: "cut".into(),
                    source: std::io::Error::other("cut by the test"),
                });
            }
            LEFT.with(|c| c.set(Some(n - 1)));
        }
        Ok(())
    }
}

/// Finish what killed runs left in `dir`: a staging directory with a journal (a commit cut
/// half way) is rolled forward; one without (a run killed before its commit) is removed. Only
/// the staging directories of processes that are gone are touched; a running process's (a
/// concurrent run into the same folder) are left alone. Errors are left for the next run: a
/// reader cannot mend a folder it may not write.
pub fn settle(dir: &Path) {
    settle_where(dir, crate::atomic_file::is_stale)
}

/// [`settle`], with `stale(rest, path)` telling which staging directories are a gone
/// process's (`rest`: the name after the prefix).
fn settle_where(dir: &Path, stale: impl Fn(&str, &Path) -> bool) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(STAGING)) else {
            continue;
        };
        let path = e.path();
        // a real directory of a process that is gone; never a link
        if !e.file_type().is_ok_and(|t| t.is_dir()) || !stale(rest, &path) {
            continue;
        }
        let journal = std::fs::read_to_string(path.join(JOURNAL))
            .ok()
            .and_then(|t| serde_json::from_str::<Journal>(&t).ok())
            .filter(|j| j.files.iter().chain(&j.remove).all(|f| safe(&j.kind, f)));
        match journal {
            Some(j) => {
                let _ = roll_forward(dir, &path, &j);
            }
            None => {
                let _ = std::fs::remove_dir_all(&path);
            }
        }
    }
}

#[cfg(test)]
mod tests;
