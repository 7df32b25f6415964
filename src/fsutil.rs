//! Files never half-written: write to a temporary name in the same folder, then rename
//! over the target (atomic on POSIX file systems and on NTFS for a rename within one
//! volume), so a run killed halfway leaves either the old file or the new one, never a
//! truncated file with the final name.

use std::io::Write;
use std::path::{Path, PathBuf};

/// The temporary name beside `path`: `.tmp-<pid>-<name>` in the same folder (hidden,
/// distinct per process so two runs writing the same file do not share it, and keeping
/// the extension, which some writers read to choose the format).
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "file".into());
    path.with_file_name(format!(".tmp-{}-{name}", std::process::id()))
}

/// Write a file through `fill`, which receives the temporary path and writes it; then
/// sync and rename it to `path`. On error the temporary file is removed and `path` is
/// untouched.
pub fn write_atomic_with<T, E: From<std::io::Error>>(
    path: &Path,
    fill: impl FnOnce(&Path) -> Result<T, E>,
) -> Result<T, E> {
    let tmp = temporary_path(path);
    let done = fill(&tmp).and_then(|v| {
        std::fs::File::open(&tmp)?.sync_all()?;
        std::fs::rename(&tmp, path)?;
        Ok(v)
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// Write `bytes` to `path` atomically (see the module).
pub fn write_atomic(path: &Path, bytes: impl AsRef<[u8]>) -> std::io::Result<()> {
    write_atomic_with(path, |tmp| -> std::io::Result<()> {
        let mut f = std::fs::File::create(tmp)?;
        f.write_all(bytes.as_ref())?;
        f.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = std::env::temp_dir().join(format!("raceway-fsutil-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("out.csv");
        write_atomic(&f, "old\n").unwrap();
        let r = write_atomic_with(&f, |tmp| {
            std::fs::write(tmp, "half")?;
            Err::<(), std::io::Error>(std::io::Error::other("killed"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "old\n");
        assert!(!temporary_path(&f).exists());
        write_atomic(&f, "new\n").unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "new\n");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
