//! Files written whole or not at all: a temporary file beside the target, renamed over it when
//! complete, so that no command leaves a half-written output. The temporary file is created with
//! mode 0666 less the process's umask, like any file the user's tools create (a plain temporary
//! file is 0600, and that mode would pass to the output on rename).

use std::io::Write as _;
use std::path::Path;
use tempfile::NamedTempFile;

/// Prefix of the temporary files (hidden, and named for what made them).
const PREFIX: &str = ".shoal-";

/// A new temporary file in the directory of `path` (which must exist), to be persisted over
/// `path`.
pub(crate) fn temp_for(path: &Path) -> std::io::Result<NamedTempFile> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut b = tempfile::Builder::new();
    b.prefix(PREFIX);
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
