//! Files written whole or not at all: a temporary file beside the target, renamed over it when
//! complete, so that no command leaves a half-written output. The temporary file is created with
//! mode 0666 less the process's umask, like any file the user's tools create (a plain temporary
//! file is 0600, and that mode would pass to the output on rename).
//!
//! Temporary files and staging directories are named `.shoal-HOST-PID-XXXXXX` (and
//! `.shoal-staging-HOST-PID-XXXXXX`): the host and process that made them. A process killed
//! before it could rename or remove its temporary file leaves it behind; the next write into
//! that directory removes every such file whose process is gone ([`is_stale`]). Files of a
//! process still running, or of another host (a cluster's shared file system), are left alone.

use std::collections::HashSet;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use tempfile::NamedTempFile;

/// Prefix of the temporary files (hidden, and named for what made them).
pub(crate) const PREFIX: &str = ".shoal-";

/// How long a temporary file without a host and process in its name (written by an older
/// shoal) must be left untouched before it counts as stale, seconds.
const UNTAGGED_STALE_S: u64 = 600;

/// This host's name, reduced to the characters a file name keeps everywhere.
fn host() -> &'static str {
    static HOST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    HOST.get_or_init(|| {
        let raw = host_name().unwrap_or_default();
        let name: String = raw
            .chars()
            .filter(|c| c.is_ascii_alphanumeric() || *c == '.')
            .take(64)
            .collect();
        if name.is_empty() {
            "host".into()
        } else {
            name
        }
    })
}

#[cfg(unix)]
fn host_name() -> Option<String> {
    let mut buf = [0u8; 256];
    // SAFETY: the buffer is valid for its length; gethostname writes at most that many bytes.
    let rc = unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) };
    if rc != 0 {
        return None;
    }
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    Some(String::from_utf8_lossy(&buf[..end]).into_owned())
}

#[cfg(not(unix))]
fn host_name() -> Option<String> {
    std::env::var("COMPUTERNAME").ok()
}

/// The tag of this process in the names of its temporary files: `HOST-PID-`.
pub(crate) fn tag() -> String {
    format!("{}-{}-", host(), std::process::id())
}

/// Whether process `pid` of this host is gone.
#[cfg(unix)]
fn gone(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: signal 0 only asks whether the process exists.
    let rc = unsafe { libc::kill(pid, 0) };
    rc != 0 && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH)
}

#[cfg(not(unix))]
fn gone(_pid: u32) -> bool {
    false
}

/// Whether the entry `name` (after its prefix, `.shoal-` or `.shoal-staging-`) at `path` is a
/// temporary of a process that is gone: its name carries this host and a process that no longer
/// runs, or (an older shoal's, `.shoal-XXXXXX`) it carries none and is older than ten minutes.
pub(crate) fn is_stale(rest: &str, path: &Path) -> bool {
    // HOST-PID-RANDOM, the host possibly with dots
    let tagged = rest
        .rsplit_once('-')
        .and_then(|(front, _random)| front.rsplit_once('-'))
        .and_then(|(h, pid)| Some((h, pid.parse::<u32>().ok()?)));
    match tagged {
        Some((h, pid)) => h == host() && gone(pid),
        // an older shoal's: six random characters, nothing else
        None if rest.len() == 6 && rest.bytes().all(|b| b.is_ascii_alphanumeric()) => {
            std::fs::symlink_metadata(path)
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age.as_secs() > UNTAGGED_STALE_S)
        }
        None => false,
    }
}

/// Remove the stale temporary files of `dir` (regular files only, never what a link points
/// to), once per directory and process.
fn sweep_stale(dir: &Path) {
    static SWEPT: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);
    {
        let mut swept = SWEPT.lock().unwrap_or_else(|p| p.into_inner());
        if !swept
            .get_or_insert_with(HashSet::new)
            .insert(dir.to_path_buf())
        {
            return;
        }
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(PREFIX)) else {
            continue;
        };
        if rest.starts_with("staging-") || rest.starts_with("outputs") {
            continue; // an output set's, handled by crate::output_set
        }
        let regular = e.file_type().is_ok_and(|t| t.is_file());
        if regular && is_stale(rest, &e.path()) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// The folder that holds `path` ("." for a bare file name).
pub(crate) fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A new temporary file in the directory of `path` (which must exist), to be persisted over
/// `path`. Stale temporary files of killed runs in that directory are removed first.
pub(crate) fn temp_for(path: &Path) -> std::io::Result<NamedTempFile> {
    let dir = folder_of(path);
    sweep_stale(dir);
    let prefix = format!("{PREFIX}{}", tag());
    let mut b = tempfile::Builder::new();
    b.prefix(&prefix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b.tempfile_in(dir)
}

/// Write `bytes` to `path` atomically: a temporary file beside it, synced, then renamed.
pub(crate) fn write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut tmp = temp_for(path)?;
    tmp.write_all(bytes)?;
    persist(tmp, path)
}

/// Sync a temporary file of [`temp_for`] written whole and rename it over `path`.
pub(crate) fn persist(tmp: NamedTempFile, path: &Path) -> std::io::Result<()> {
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(all(test, unix))]
mod tests {
    use std::os::unix::fs::PermissionsExt;

    /// Regression (issue 13): every output was mode 0600, the temporary file's mode leaking
    /// into plan.json, CSVs, figures and exports. It is now 0666 less the umask.
    #[test]
    fn regression_outputs_were_mode_0600() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        super::write(&path, b"x").unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        let umask = current_umask();
        assert_eq!(mode, 0o666 & !umask, "mode {mode:o}, umask {umask:o}");
        assert_eq!(std::fs::read(&path).unwrap(), b"x");
        // nothing else is left in the directory
        assert_eq!(
            std::fs::read_dir(path.parent().unwrap()).unwrap().count(),
            1
        );
    }

    /// The process's umask, read from /proc (Linux) or assumed 0022.
    fn current_umask() -> u32 {
        std::fs::read_to_string("/proc/self/status")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find_map(|l| l.strip_prefix("Umask:"))
                    .and_then(|v| u32::from_str_radix(v.trim(), 8).ok())
            })
            .unwrap_or(0o022)
    }
}
